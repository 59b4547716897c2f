//! Articulated objects for simulators: one folder per object in the PartNet-Mobility layout,
//! with URDF, MJCF and USD descriptions of the same object ([`urdf`], [`mjcf`], [`usd`]),
//! convex collision hulls ([`collision`]) and mass properties ([`inertia`]), both gathered
//! per link by [`physics`]; [`objects`] writes the folders.
//!
//! The export is written into a staging folder beside its output folder and renamed into
//! place when complete ([`pairs::atomic::Staging`]): an output folder that is not empty is
//! refused unless the caller forces it, and an interrupted export leaves the old contents
//! as they were.

#![deny(missing_docs)]

pub mod collision;
pub mod fit;
pub mod inertia;
pub mod mjcf;
pub mod objects;
pub mod physics;
pub mod urdf;
pub mod usd;

pub use objects::{
    export_objects, write_object, ExportError, ExportOptions, ExportedObject, ObjectFormat,
    StateDraw,
};
