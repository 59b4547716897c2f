//! Articulated objects and the building blocks categories are made of, one family per file.

pub mod articulated;
pub mod bracket;
pub mod container;
pub mod door;
pub mod drawer;
pub mod handle;
pub mod hinge;
pub mod keyboard;
pub mod motion;
pub mod profile;
pub mod shell;

pub use articulated::{ArticulatedObject, Joint, Link, ObjectError};
