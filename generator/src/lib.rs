//! Synthetic articulated objects, posed and sampled into point-cloud pairs with complete
//! ground truth, written as dataset folders (docs/FORMAT.md).
//!
//! The stages are separate modules and crates with plain-data inputs and outputs: an
//! [`ArticulatedObject`](articulated::objects::ArticulatedObject) from a built-in category
//! ([`articulated::categories`]) or a user's asset ([`assets`]); joint states from
//! [`protocol`]; link poses from [`articulated::kinematics`]; surface samples from
//! [`articulated::sampling`] or virtual scans from [`scanner`]; parts and ground truth from
//! [`label`]; and [`generate`] runs them per pair and writes datasets.
//!
//! ```
//! use generator::{config::GeneratorConfig, generate::object_pairs};
//!
//! let config = GeneratorConfig { objects: 1, points: 128, ..Default::default() };
//! let pairs = object_pairs(&config, 0).expect("a laptop gives five pairs");
//! assert_eq!(pairs.len(), 5);
//! assert_eq!(pairs[0].pair.provenance().category, "laptop");
//! ```
#![deny(missing_docs)]

pub mod asset_dataset;
pub mod commands;
pub mod config;
pub mod gallery;
pub mod generate;
pub mod label;
pub mod objects;
pub mod protocol;
pub mod shard;
pub mod stream;
