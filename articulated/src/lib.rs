//! The articulated object library: what an object is and how it moves.
//!
//! An [`objects::ArticulatedObject`] is a tree of rigid links joined by revolute, prismatic
//! or fixed joints, each link a [`mesh::Mesh`] of convex pieces. The procedural
//! [`categories`] build such objects from a seed ([`seed`]); [`kinematics`] poses them from
//! joint values, [`sampling`] draws points on their surface, and [`check`] tells whether a
//! posed object is physically plausible (moving links touch their parents, no two links
//! pass through each other).
//!
//! The crates above read users' assets into this model (`assets`), scan it (`scanner`) and
//! turn it into datasets (`generator`).
//!
//! ```
//! use articulated::categories::find;
//! use articulated::seed::{rng_for, Stream};
//!
//! let laptop = find("laptop").expect("a built-in category");
//! let object = (laptop.build)(&mut rng_for(0, 0, Stream::Object));
//! assert_eq!(object.links.len(), 2);
//! ```
#![deny(missing_docs)]

pub mod categories;
pub mod check;
pub mod kinematics;
pub mod mesh;
pub mod objects;
pub mod sampling;
pub mod seed;

/// The version every output records as `generator_version` (datasets, renders, object
/// folders): the workspace's version, which changes when the objects or the protocol do.
pub const GENERATOR_VERSION: &str = env!("CARGO_PKG_VERSION");
