//! One asset file to one articulated object, whichever its format.

use std::path::{Path, PathBuf};

use super::assembly::assemble_with_surfaces;
use super::discover::extension;
use super::gltf::read_gltf_asset;
use super::obj_groups::read_obj_asset;
use super::surface::Surface;
use super::urdf::read_urdf_asset;
use super::{ImportError, ImportOptions};
use articulated::objects::ArticulatedObject;

/// An imported asset.
#[derive(Debug, Clone, PartialEq)]
pub struct Imported {
    /// The object, valid by the model's rules.
    pub object: ArticulatedObject,
    /// Files read besides the asset's own (sidecar, meshes, buffers), in reading order.
    pub files: Vec<PathBuf>,
    /// Each link's surface (materials and textures, for renders), in link order.
    pub surfaces: Vec<Surface>,
}

/// Reads the asset at `path` by its extension: `.urdf`, `.obj` (with its sidecar),
/// `.gltf` or `.glb`.
pub fn load_asset(path: &Path, options: &ImportOptions) -> Result<Imported, ImportError> {
    let continuous = options.continuous_range().map_err(ImportError::Options)?;
    let (skeleton, files) = match extension(path).as_str() {
        "urdf" => read_urdf_asset(path, options)?,
        "obj" => read_obj_asset(path)?,
        "gltf" | "glb" => read_gltf_asset(path)?,
        _ => return Err(ImportError::UnknownFormat { path: path.into() }),
    };
    let (object, surfaces) = assemble_with_surfaces(skeleton, continuous)?;
    Ok(Imported { object, files, surfaces })
}
