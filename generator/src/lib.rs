//! Synthetic articulated objects, posed and sampled into point-cloud pairs with complete
//! ground truth, written as dataset folders (docs/FORMAT.md).
//!
//! The stages are separate modules with plain-data inputs and outputs: an
//! [`objects::ArticulatedObject`] from a [`categories::Category`]; joint states from
//! [`protocol`]; link poses from [`kinematics`]; surface samples from [`sampling`] or
//! virtual scans from [`scan`]; parts and ground truth from [`label`]; and [`generate`]
//! runs them per pair and writes datasets.
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
pub mod categories;
pub mod check;
pub mod commands;
pub mod config;
pub mod export;
pub mod gallery;
pub mod generate;
pub mod import;
pub mod kinematics;
pub mod label;
pub mod mesh;
pub mod multiview;
pub mod objects;
pub mod protocol;
pub mod sampling;
pub mod scan;
pub mod scan_config;
pub mod seed;
pub mod shard;
pub mod stream;
