//! What a leaderboard row is: the registry of rows, the default one, the parameters a row
//! exposes for tuning, the reference rows and the rows read from prediction files.

pub mod external;
pub mod grid;
pub mod reference;
pub mod registry;
pub mod runner;
pub mod standard;
