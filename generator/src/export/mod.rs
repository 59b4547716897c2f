//! Exports for other tools: objects as simulation-ready URDF folders in the
//! PartNet-Mobility layout ([`objects`]), and datasets in the layouts other methods read
//! ([`formats`]: the paper authors' `.mat` files, MultiBodySync's `npz` files).
//!
//! Every export is written into a staging folder beside its output folder and renamed into
//! place when complete ([`output::Staging`]): an output folder that is not empty is refused
//! unless the caller forces it, and an interrupted export leaves the old contents as they
//! were.

pub mod formats;
pub mod objects;
pub mod output;
pub mod urdf;

pub use output::{write_file, OutputError, Staging};
