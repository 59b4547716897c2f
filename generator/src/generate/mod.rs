//! Generation of pairs and datasets: object -> states -> posed samples -> labelled pairs ->
//! dataset files, in parallel, deterministic per pair whatever the thread count.
//!
//! [`object`] builds an object and draws its states, [`object_pairs`] makes its pairs (each
//! through `pair`, which observes and labels one pair), `set` its sets of K views, and
//! [`dataset`] writes whole datasets.

pub mod dataset;
pub mod error;
pub mod object;
pub mod object_pairs;
mod pair;
mod set;

pub use dataset::{dataset_origin, generate_dataset};
pub use error::GenerateError;
pub use object::{build_object, object_states};
pub use object_pairs::{
    cross_pairs_of_object, dataset_object_pairs, object_pairs, object_pairs_with, pairs_of_object,
    GeneratedPair, Variant, PARTNER_ATTEMPTS,
};
pub use set::{object_sets, set_id, sets_of_object, GeneratedSet, SET_ATTEMPTS};
