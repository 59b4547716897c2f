//! Multi-view renders for image-based methods (PARIS, DigitalTwinArt, ArtGS): an object in
//! S articulation states, each seen by the same V calibrated cameras. Per view: an RGB
//! image (material, procedural texture and a fixed light, [`appearance`]; never the part
//! label), depth, part-label and normal images. [`layout`] writes them in our layout or in
//! the layout a method's loader reads.
//!
//! Everything random (the states, the materials) flows from the seed and the object id;
//! the cameras are fixed by the config, so the same config and seed give identical files.

//!
//! The crate writes what `generator render` and the evaluator's render benchmark write:
//! [`RenderJob::new`] draws and poses an object, [`layout::write_render`] renders and writes
//! the folder, [`backproject`] turns a render folder back into point-cloud pairs.

#![deny(missing_docs)]

pub mod appearance;
pub mod backproject;
pub mod cameras;
pub mod config;
pub mod error;
pub mod job;
pub mod layout;
pub mod scene;
pub mod shade;

pub use config::{RenderConfig, MAX_SIDE};
pub use error::RenderError;
pub use job::{JointStates, RenderJob};
