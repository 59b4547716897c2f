//! Articulated objects and the building blocks categories are made of, one family per file.

pub mod arm;
pub mod articulated;
pub mod bucket;
pub mod door;
pub mod drawer;
pub mod handle;
pub mod joints;
pub mod rotor;
pub mod tube;

pub use articulated::{ArticulatedObject, Joint, Link, ObjectError};
