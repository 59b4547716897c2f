//! Random articulated assemblies: the paper's category-free training data (Yi et al. 2018,
//! "Training Dataset"), built from primitives instead of segmented ShapeNet shapes. A root
//! primitive grows a tree of boxes, each standing on a face of another; 2 to 6 of them move,
//! three in four turning about an axis through their contact region and one in four sliding
//! along its contact normal out of a sleeve, so that every part stays connected.

mod boxes;
mod builder;
mod collision;
mod geometry;
mod growth;
mod links;
mod motions;
mod params;
mod root;
mod segments;
mod shape;
mod sweeps;
mod visibility;

pub use builder::random_assembly;
pub use params::AssemblyParams;
