//! Every method on every dataset, scored into reproducible leaderboards. The crate is laid
//! out by job:
//!
//! - [`rows`]: what a leaderboard row is. The [`rows::registry`] names every row: whole
//!   methods, segmenters combined with a flow source (`seqransac@net-flow`), the `gt`
//!   oracle, and rows read from prediction files ([`rows::external`]); [`rows::standard`]
//!   is the default registry, [`rows::grid`] the parameters a row exposes for tuning and
//!   [`rows::reference`] the reference rows.
//! - [`running`]: a row run on a [`datasets`] dataset in parallel over pairs
//!   ([`running::run`]), each prediction scored with `pairs::metrics::score_pair` and the
//!   per-pair results cached ([`running::record`]); an iterative row (`net-iter`) also
//!   scores each of its passes as it runs ([`running::passes`]).
//! - [`tuning`]: the baselines' parameters cross-validated on the validation sets.
//! - [`boards`]: the cached results aggregated with polars into the CSV leaderboards
//!   ([`boards::leaderboard`]), the PCC curves ([`boards::plots`]), the segmentation
//!   pictures ([`boards::gallery`]), the paper's Table 4 ([`boards::iterations`]) and
//!   `LEADERBOARD.md` beside the paper's numbers ([`boards::report`], [`boards::paper`]).
//! - [`commands`]: the whole evaluation ([`commands::pipeline`]) and the scoring and writing
//!   of prediction files of methods run elsewhere ([`commands::files`]).
//!
//! ```
//! use std::sync::Arc;
//! use evaluator::rows::reference::OnePart;
//! use evaluator::rows::registry::{FlowSource, Registry};
//!
//! let mut registry = Registry::new();
//! registry.oracle().combine(Arc::new(OnePart), FlowSource::GroundTruth, "v1", None);
//! let names: Vec<&str> = registry.entries().iter().map(|e| e.name.as_str()).collect();
//! assert_eq!(names, ["gt", "one-part@gt-flow"]);
//! ```
#![deny(missing_docs)]

pub mod boards;
pub mod commands;
pub mod datasets;
pub mod error;
pub mod rows;
pub mod running;
pub mod tuning;

pub use error::EvalError;
