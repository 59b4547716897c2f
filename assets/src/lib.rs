//! User assets: articulated objects read from URDF (with OBJ or STL meshes), from an OBJ
//! with one group per part plus a JSON sidecar of joints, or from glTF / GLB with a node
//! hierarchy; each becomes an [`ArticulatedObject`](articulated::objects::ArticulatedObject) that
//! the rest of the generator treats as it treats a built-in category.
//!
//! Every format is read into one plain intermediate, a [`skeleton::Skeleton`] of named
//! links (meshes in the asset's rest frame) and named joints, and [`assembly::assemble`]
//! turns that into the model the same way for every format: fixed joints weld a link into
//! its parent's part, parts are ordered parents first, then by name (natural order), mimic
//! joints are resolved, and every rule breach is a typed [`ImportError`]. Nothing here panics on
//! bad input; `assets/fuzz` holds one fuzz target per parser.

#![deny(missing_docs)]

pub mod assembly;
pub mod discover;
pub mod error;
pub mod gltf;
pub mod gltf_data;
pub mod load;
pub mod mesh_build;
pub mod mesh_files;
pub mod obj_groups;
pub mod options;
pub mod sidecar;
pub mod skeleton;
pub mod sourced;
pub mod surface;
pub mod text;
pub mod urdf;

pub use assembly::assemble;
pub use discover::discover_assets;
pub use error::ImportError;
pub use load::{load_asset, Imported};
pub use options::ImportOptions;
pub use sourced::{Source, SourcedObject};
