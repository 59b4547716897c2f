//! Running a row on a dataset and the cache of its results: the parallel run and its
//! scoring, the runs files, the iteration passes, the memory probe and the source hashes
//! that key the cache.

pub mod memory;
pub mod passes;
pub mod record;
pub mod renders;
pub mod run;
pub mod sets;
pub mod source_hash;
