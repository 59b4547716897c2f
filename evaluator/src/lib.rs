//! Every method on every dataset, scored into reproducible leaderboards.
//!
//! The [`registry`] names every leaderboard row: whole methods, segmenters combined with a
//! flow source (`seqransac@net-flow`), and the `gt` oracle. [`run`] runs a row on a
//! [`datasets`] dataset in parallel over pairs, scoring each prediction with [`score`]
//! (`pairs::metrics`) and caching per-pair results ([`record`]). [`leaderboard`] aggregates
//! them with polars into the CSV leaderboards; [`plots`], [`gallery`] and [`report`] draw the
//! PCC curves and segmentation pictures and write `LEADERBOARD.md` beside the paper's
//! numbers ([`paper`]). An iterative row (`net-iter`) also scores each of its passes as it
//! runs ([`passes`], cached beside its runs file), and [`iterations`] writes the paper's
//! Table 4 from them; [`joints`] holds the joint scores of its first and last passes.
//! [`tuning`] cross-validates the baselines' parameters on the validation sets,
//! [`external`] and [`commands`] score and write prediction files of methods run elsewhere,
//! [`standard`] is the default registry and [`pipeline`] the whole evaluation.
//!
//! ```
//! use std::sync::Arc;
//! use evaluator::reference::OnePart;
//! use evaluator::registry::{FlowSource, Registry};
//!
//! let mut registry = Registry::new();
//! registry.oracle().combine(Arc::new(OnePart), FlowSource::GroundTruth, "v1", None);
//! let names: Vec<&str> = registry.entries().iter().map(|e| e.name.as_str()).collect();
//! assert_eq!(names, ["gt", "one-part@gt-flow"]);
//! ```
#![deny(missing_docs)]

pub mod commands;
pub mod datasets;
pub mod error;
pub mod external;
pub mod gallery;
pub mod iterations;
pub mod joints;
pub mod leaderboard;
pub mod memory;
pub mod paper;
pub mod passes;
pub mod pipeline;
pub mod plots;
pub mod record;
pub mod reference;
pub mod registry;
pub mod report;
pub mod run;
pub mod score;
pub mod source_hash;
pub mod standard;
pub mod tuning;

pub use error::EvalError;
