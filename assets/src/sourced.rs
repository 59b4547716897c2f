//! An object together with where it came from: what the renderer and the simulator exports
//! take, whether the object is a built-in category's or was read from a user's asset.

use serde::Serialize;

use articulated::objects::{identifier, ArticulatedObject};

use crate::surface::Surface;

/// Where an object came from (written into each render's and object folder's metadata).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Source {
    /// A built-in category, object `object_id` of a dataset with the config's seed.
    BuiltIn {
        /// The split the categories were drawn from.
        split: String,
    },
    /// A user asset.
    Asset {
        /// The asset's main file, relative to the folder given to `--assets`.
        path: String,
    },
}

/// One object to render or export.
#[derive(Debug, Clone)]
pub struct SourcedObject {
    /// Its index in the dataset it belongs to (the folder's number).
    pub object_id: u32,
    /// The object.
    pub object: ArticulatedObject,
    /// Where it came from.
    pub source: Source,
    /// Each link's materials and textures from the asset; empty for the built-in objects,
    /// which get a procedural material.
    pub surfaces: Vec<Surface>,
}

impl SourcedObject {
    /// Its folder name in a render or an export: its id (6 digits, so that folders sort in
    /// object order) and its category.
    pub fn folder_name(&self) -> String {
        folder_name(self.object_id, &self.object.category)
    }
}

/// Folder name of object `object_id` of `category` (see [`SourcedObject::folder_name`]).
pub fn folder_name(object_id: u32, category: &str) -> String {
    format!("{object_id:06}_{}", identifier(category))
}
