//! Articulated objects and the building blocks categories are made of, one family per file.

pub mod arm;
pub mod articulated;
pub mod assembly;
pub mod bracket;
pub mod bucket;
pub mod car_body;
pub mod carcass;
pub mod contact;
pub mod container;
pub mod controls;
pub mod door;
pub mod drawer;
pub mod handle;
pub mod joints;
pub mod keyboard;
pub mod panel;
pub mod profile;
pub mod rack;
pub mod rotor;
pub mod round;
pub mod shell;
pub mod tube;

pub use articulated::{identifier, ArticulatedObject, Joint, Link, Mimic, ObjectError};
