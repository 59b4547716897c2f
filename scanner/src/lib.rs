//! The virtual scanner: a pinhole camera at a random viewpoint renders the posed object by
//! ray casting ([`render`](mod@render)), the noise model turns the rendering into a measurement
//! ([`noise`]), valid pixels are back-projected to points, and farthest point sampling
//! ([`pairs::sampling::farthest_point_sampling`]) keeps N of them. Viewpoints that see too
//! little of the object, or too little of any part, are drawn again ([`scan_side`], in
//! [`side`]). [`visibility`] decides which surface
//! points a camera sees, for the correspondence mask. [`config::ScanConfig`] holds every
//! setting (the `[scan]` table of a generator config).

#![deny(missing_docs)]

pub mod camera;
pub mod config;
pub mod images;
pub mod noise;
pub mod render;
pub mod scene;
pub mod side;
pub mod visibility;

pub use side::{scan_side, Requirements, ScannedSide, SURFACE_TOLERANCE};
