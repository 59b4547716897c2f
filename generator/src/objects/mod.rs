//! Articulated objects and the building blocks categories are made of, one family per file.

pub mod articulated;
pub mod assembly;
pub mod door;
pub mod drawer;
pub mod handle;

pub use articulated::{ArticulatedObject, Joint, Link, ObjectError};
