//! The set record: K >= 2 observations of one object in K articulation states (the
//! MultiBodySync setting), with part ids consistent across all K, and the pair record of
//! any two of them ([`Set::pair`]).
//!
//! A *set part* is a group of links that move rigidly together in all K states. Between
//! two views i and j fewer parts may move apart (a joint that sits at the same value in
//! both states), so the pair (i, j) merges set parts exactly as the pair generator merges
//! links: the record stores, for every ordered pair of views, which set parts form one
//! part of that pair ([`SetTruth::pair_parts`]), and every other field of the pair's
//! ground truth follows from the views' own fields.
//!
//! [`types`] holds what a set is made of, [`record`] the record and its pairs, and the
//! checks a set passes when built are in `validate`.

pub mod record;
pub mod types;
mod validate;

pub use record::{pair_kind, Set};
pub use types::*;

#[cfg(test)]
mod tests;
