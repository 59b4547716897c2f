//! Exports for other tools: objects as simulation-ready folders in the PartNet-Mobility
//! layout, with URDF, MJCF and USD descriptions, convex collision hulls and mass
//! properties ([`objects`], [`urdf`], [`mjcf`], [`usd`], [`physics`]), and datasets in the
//! layouts other methods read ([`formats`]: the paper authors' `.mat` files,
//! MultiBodySync's `npz` files).
//!
//! Every export is written into a staging folder beside its output folder and renamed into
//! place when complete ([`output::Staging`]): an output folder that is not empty is refused
//! unless the caller forces it, and an interrupted export leaves the old contents as they
//! were.

pub mod collision;
pub mod formats;
pub mod inertia;
pub mod mjcf;
pub mod objects;
pub mod output;
pub mod physics;
pub mod urdf;
pub mod usd;

pub use output::{write_file, OutputError, Staging};
