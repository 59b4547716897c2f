//! `generator export-objects`: objects as folders in the PartNet-Mobility layout, ready for
//! SAPIEN, PyBullet, Isaac or any URDF reader, with the articulation states the dataset
//! protocol draws for them.
//!
//! One folder per object, `<object id, 6 digits>_<category>/`:
//! - `mobility.urdf`, `textured_objs/link_<i>.obj`, `mobility_v2.json` ([`super::urdf`]);
//! - `meta.json`: category, object id, seed, split, generator version, where the object
//!   came from (built in or an asset file), and each URDF link's name in the generator;
//! - `states.json`: the object's articulation states (every joint by name), in the order
//!   `provenance.articulation_p` / `_q` index them in a dataset made with the same settings.
//!
//! Folders sort in object order, so `generator --assets <out>` with the same settings makes
//! the same pairs as the built-in objects did.

use std::collections::BTreeMap;
use std::path::Path;

use rayon::prelude::*;
use serde::Serialize;

use super::output::{write_file, OutputError, Staging};
use super::urdf::{link_name, mesh_path, mobility_json, obj_text, urdf_text};
use crate::config::GeneratorConfig;
use crate::generate::{configuration, object_states, GENERATOR_VERSION};
use crate::objects::{identifier, ArticulatedObject};

/// Version of the object folder layout, in every `meta.json`.
pub const OBJECT_FORMAT_VERSION: u32 = 1;

/// Objects written at once before the next batch: bounds memory.
const BATCH: usize = 64;

/// Why an export failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ExportError {
    /// The output folder cannot be written.
    #[error(transparent)]
    Output(#[from] OutputError),
    /// Nothing to export.
    #[error("no objects to export")]
    Empty,
}

/// Where an exported object came from.
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

/// One object to export.
#[derive(Debug, Clone)]
pub struct ObjectToExport {
    /// Its index in the dataset it belongs to (the folder's number).
    pub object_id: u32,
    /// The object.
    pub object: ArticulatedObject,
    /// Where it came from.
    pub source: Source,
    /// Each link's materials and textures from the asset (`generator render`); empty for
    /// the built-in objects, which get a procedural material.
    pub surfaces: Vec<crate::import::surface::Surface>,
}

/// One exported object.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ExportedObject {
    /// Folder name under the output folder.
    pub folder: String,
    /// Category.
    pub category: String,
    /// Object id.
    pub object_id: u32,
    /// Links (URDF `link_i`), joints.
    pub links: usize,
    /// Moving joints.
    pub joints: usize,
}

/// `meta.json` of an object folder.
#[derive(Debug, Serialize)]
struct Meta<'a> {
    format: &'static str,
    format_version: u32,
    model_cat: &'a str,
    category: &'a str,
    object_id: u32,
    seed: u64,
    source: &'a Source,
    generator_version: &'static str,
    /// URDF link name -> the generator's link name.
    links: BTreeMap<String, &'a str>,
    /// Joint names in the generator's order (the order of `states.json` rows' keys does
    /// not matter; this is the order of `ArticulatedObject::joints`).
    joints: Vec<&'a str>,
}

/// `states.json` of an object folder.
#[derive(Debug, Serialize)]
struct States {
    /// The settings the states were drawn with.
    seed: u64,
    rest_probability: f64,
    /// State `k` (the dataset's articulation id `k`): every joint by name.
    states: Vec<BTreeMap<String, f32>>,
}

/// The built-in objects a config selects (objects `0..config.objects`, categories in turn).
pub fn built_in_objects(
    config: &GeneratorConfig,
) -> Result<Vec<ObjectToExport>, crate::generate::GenerateError> {
    (0..config.objects)
        .into_par_iter()
        .map(|i| {
            let object = crate::generate::build_object(config, i)?;
            Ok(ObjectToExport {
                object_id: i,
                object,
                source: Source::BuiltIn { split: config.split.as_str().into() },
                surfaces: Vec::new(),
            })
        })
        .collect()
}

/// Folder name of an object: its id (6 digits, so that folders sort in object order) and
/// its category.
pub fn folder_name(object_id: u32, category: &str) -> String {
    format!("{object_id:06}_{}", identifier(category))
}

/// Writes every object into `out` (refused if `out` is not empty, unless `force`), plus an
/// `objects.json` listing them; `progress` gets the count written so far.
pub fn export_objects(
    config: &GeneratorConfig,
    objects: &[ObjectToExport],
    out: &Path,
    force: bool,
    mut progress: impl FnMut(u64),
) -> Result<Vec<ExportedObject>, ExportError> {
    if objects.is_empty() {
        return Err(ExportError::Empty);
    }
    let staging = Staging::new(out, force)?;
    let mut exported = Vec::with_capacity(objects.len());
    for batch in objects.chunks(BATCH) {
        let written: Vec<Result<ExportedObject, ExportError>> =
            batch.par_iter().map(|o| write_object(config, o, staging.path())).collect();
        for w in written {
            exported.push(w?);
            progress(exported.len() as u64);
        }
    }
    write(&staging.path().join("objects.json"), pretty(&exported).as_bytes())?;
    staging.commit()?;
    Ok(exported)
}

/// Writes one object's folder under `root`.
pub fn write_object(
    config: &GeneratorConfig,
    item: &ObjectToExport,
    root: &Path,
) -> Result<ExportedObject, ExportError> {
    let object = &item.object;
    let folder = folder_name(item.object_id, &object.category);
    let dir = root.join(&folder);
    let meshes = dir.join("textured_objs");
    std::fs::create_dir_all(&meshes).map_err(OutputError::io(&meshes))?;
    write(&dir.join("mobility.urdf"), urdf_text(object).as_bytes())?;
    for (i, link) in object.links.iter().enumerate() {
        write(&dir.join(mesh_path(i)), obj_text(&link.mesh, &link.name).as_bytes())?;
    }
    write(&dir.join("mobility_v2.json"), pretty(&mobility_json(object)).as_bytes())?;
    let meta = Meta {
        format: "part_induction.Object",
        format_version: OBJECT_FORMAT_VERSION,
        model_cat: &object.category,
        category: &object.category,
        object_id: item.object_id,
        seed: config.seed,
        source: &item.source,
        generator_version: GENERATOR_VERSION,
        links: object
            .links
            .iter()
            .enumerate()
            .map(|(i, l)| (link_name(i), l.name.as_str()))
            .collect(),
        joints: object.joints.iter().map(|j| j.name.as_str()).collect(),
    };
    write(&dir.join("meta.json"), pretty(&meta).as_bytes())?;
    let states = States {
        seed: config.seed,
        rest_probability: config.rest_probability,
        states: object_states(config, object, item.object_id)
            .iter()
            .map(|values| configuration(object, values))
            .collect(),
    };
    write(&dir.join("states.json"), pretty(&states).as_bytes())?;
    Ok(ExportedObject {
        folder,
        category: object.category.clone(),
        object_id: item.object_id,
        links: object.links.len(),
        joints: object.joints.len(),
    })
}

/// Pretty JSON with a final newline.
fn pretty<T: Serialize>(value: &T) -> String {
    let mut text = serde_json::to_string_pretty(value).expect("plain data serialises");
    text.push('\n');
    text
}

fn write(path: &Path, bytes: &[u8]) -> Result<(), ExportError> {
    write_file(path, bytes)?;
    Ok(())
}
