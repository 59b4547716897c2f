//! `generator export-objects`: objects as folders in the PartNet-Mobility layout, ready for
//! MuJoCo, PyBullet, SAPIEN, Isaac or any URDF reader, with the articulation states the
//! dataset protocol draws for them.
//!
//! One folder per object, `<object id, 6 digits>_<category>/`:
//! - `mobility.urdf`, `textured_objs/link_<i>.obj`, `mobility_v2.json` ([`crate::urdf`]);
//! - `collision/link_<i>_hull_<k>.obj`: each link's convex collision hulls
//!   ([`crate::collision`]), used by every format; masses and inertias from the link's
//!   geometry and a density ([`crate::inertia`]);
//! - `mobility.xml` (MJCF, [`crate::mjcf`]) and `mobility.usda` (USD with UsdPhysics,
//!   [`crate::usd`]), from the same description (each can be left out, [`ObjectFormat`]);
//! - `meta.json`: category, object id, seed, split, generator version, where the object
//!   came from (built in or an asset file), each URDF link's name in the generator, and
//!   each link's mass, collision hulls, their fit and any fallback;
//! - `states.json`: the object's articulation states (every joint by name), in the order
//!   `provenance.articulation_p` / `_q` index them in a dataset made with the same settings.
//!
//! Folders sort in object order, so `generator --assets <out>` with the same settings makes
//! the same pairs as the built-in objects did.

use std::collections::BTreeMap;
use std::path::Path;

use rayon::prelude::*;
use serde::Serialize;

use crate::fit::Fit;
use crate::inertia::MassSource;
use crate::mjcf::mjcf_text;
use crate::physics::{object_physics, summary, CollisionSummary, PhysicsOptions};
use crate::urdf::{hull_path, link_name, mesh_path, mobility_json, obj_text, urdf_text};
use crate::usd::usda_text;
use articulated::mesh::Mesh;
use articulated::GENERATOR_VERSION;
use assets::SourcedObject;
use pairs::atomic::{write_file, OutputError, Staging};
use pairs::math::Real;

/// Version of the object folder layout, in every `meta.json`.
pub const OBJECT_FORMAT_VERSION: u32 = 2;

/// Objects written at once before the next batch: bounds memory.
const BATCH: usize = 64;

/// A description of an object for a simulator.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ObjectFormat {
    /// `mobility.urdf` (PyBullet, SAPIEN, Isaac's URDF importer, yourdfpy).
    Urdf,
    /// `mobility.xml` (MuJoCo).
    Mjcf,
    /// `mobility.usda` (USD with UsdPhysics: Isaac Sim, any USD reader).
    Usd,
}

impl ObjectFormat {
    /// Every format, in the order they are written.
    pub const ALL: [Self; 3] = [Self::Urdf, Self::Mjcf, Self::Usd];

    /// Its name on the command line and in `meta.json`.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Urdf => "urdf",
            Self::Mjcf => "mjcf",
            Self::Usd => "usd",
        }
    }

    /// The file it is written to, in the object folder.
    pub fn file_name(self) -> &'static str {
        match self {
            Self::Urdf => "mobility.urdf",
            Self::Mjcf => "mobility.xml",
            Self::Usd => "mobility.usda",
        }
    }
}

impl std::str::FromStr for ObjectFormat {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|f| f.as_str() == s.trim().to_ascii_lowercase())
            .ok_or_else(|| format!("unknown object format {s:?}: use urdf, mjcf or usd"))
    }
}

/// How objects are exported.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportOptions {
    /// The descriptions written (each object folder has the meshes, hulls, `meta.json`,
    /// `states.json` and `mobility_v2.json` whichever are chosen).
    pub formats: Vec<ObjectFormat>,
    /// Density and collision budget.
    pub physics: PhysicsOptions,
}

impl Default for ExportOptions {
    fn default() -> Self {
        Self { formats: ObjectFormat::ALL.to_vec(), physics: PhysicsOptions::default() }
    }
}

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
    /// Its collision hulls and mass.
    pub collision: CollisionSummary,
    /// Fallbacks taken for its links (`link_i: what happened`); empty when none.
    pub notes: Vec<String>,
}

/// One link's physical properties in `meta.json`.
#[derive(Debug, Serialize)]
struct LinkMeta {
    mass: f64,
    mass_from: MassSource,
    hulls: usize,
    fit: Fit,
    notes: Vec<String>,
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
    source: &'a assets::Source,
    generator_version: &'static str,
    /// URDF link name -> the generator's link name.
    links: BTreeMap<String, &'a str>,
    /// Joint names in the generator's order (the order of `states.json` rows' keys does
    /// not matter; this is the order of `ArticulatedObject::joints`).
    joints: Vec<&'a str>,
    /// The descriptions written.
    formats: &'a [ObjectFormat],
    /// Density and collision budget.
    physics: &'a PhysicsOptions,
    /// URDF link name -> its mass, collision hulls and their fit.
    link_physics: BTreeMap<String, LinkMeta>,
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

/// The joint values of each state of an object, in the order of its joints.
pub type DrawStates<'a> = dyn Fn(&SourcedObject) -> Vec<Vec<Real>> + Sync + 'a;

/// The articulation states an object folder's `states.json` lists: how they were drawn, and
/// the draw (the generator's protocol, so that state `k` is the dataset's articulation `k`).
pub struct StateDraw<'a> {
    /// The seed the states are drawn with.
    pub seed: u64,
    /// The probability of a joint at rest, in the draw.
    pub rest_probability: f64,
    /// The joint values of each state of an object, in the order of its joints.
    pub draw: Box<DrawStates<'a>>,
}

/// Writes every object into `out` (refused if `out` is not empty, unless `force`), plus an
/// `objects.json` listing them; `progress` gets the count written so far.
pub fn export_objects(
    states: &StateDraw<'_>,
    objects: &[SourcedObject],
    out: &Path,
    force: bool,
    options: &ExportOptions,
    mut progress: impl FnMut(u64),
) -> Result<Vec<ExportedObject>, ExportError> {
    if objects.is_empty() {
        return Err(ExportError::Empty);
    }
    let staging = Staging::new(out, force)?;
    let mut exported = Vec::with_capacity(objects.len());
    for batch in objects.chunks(BATCH) {
        let written: Vec<Result<ExportedObject, ExportError>> =
            batch.par_iter().map(|o| write_object(states, o, staging.path(), options)).collect();
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
    states: &StateDraw<'_>,
    item: &SourcedObject,
    root: &Path,
    options: &ExportOptions,
) -> Result<ExportedObject, ExportError> {
    let object = &item.object;
    let folder = item.folder_name();
    let dir = root.join(&folder);
    for sub in ["textured_objs", "collision"] {
        let sub = dir.join(sub);
        std::fs::create_dir_all(&sub).map_err(OutputError::io(&sub))?;
    }
    let physics = object_physics(object, &options.physics);
    for format in ObjectFormat::ALL.into_iter().filter(|f| options.formats.contains(f)) {
        let text = match format {
            ObjectFormat::Urdf => urdf_text(object, &physics),
            ObjectFormat::Mjcf => mjcf_text(object, &physics),
            ObjectFormat::Usd => usda_text(object, &physics),
        };
        write(&dir.join(format.file_name()), text.as_bytes())?;
    }
    for (i, link) in object.links.iter().enumerate() {
        write(&dir.join(mesh_path(i)), obj_text(&link.mesh, &link.name).as_bytes())?;
        for (k, hull) in physics[i].collision.hulls.iter().enumerate() {
            let mesh = Mesh {
                vertices: hull.vertices.clone(),
                triangles: hull.triangles.clone(),
                pieces: vec![0],
            };
            let name = format!("{} hull {k}", link.name);
            write(&dir.join(hull_path(i, k)), obj_text(&mesh, &name).as_bytes())?;
        }
    }
    let notes: Vec<String> = physics
        .iter()
        .enumerate()
        .flat_map(|(i, p)| p.collision.notes.iter().map(move |n| format!("{}: {n}", link_name(i))))
        .collect();
    write(&dir.join("mobility_v2.json"), pretty(&mobility_json(object)).as_bytes())?;
    let meta = Meta {
        format: "part_induction.Object",
        format_version: OBJECT_FORMAT_VERSION,
        model_cat: &object.category,
        category: &object.category,
        object_id: item.object_id,
        seed: states.seed,
        source: &item.source,
        generator_version: GENERATOR_VERSION,
        links: object
            .links
            .iter()
            .enumerate()
            .map(|(i, l)| (link_name(i), l.name.as_str()))
            .collect(),
        joints: object.joints.iter().map(|j| j.name.as_str()).collect(),
        formats: &options.formats,
        physics: &options.physics,
        link_physics: physics
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let meta = LinkMeta {
                    mass: p.inertial.mass,
                    mass_from: p.inertial.source,
                    hulls: p.collision.hulls.len(),
                    fit: p.collision.fit,
                    notes: p.collision.notes.clone(),
                };
                (link_name(i), meta)
            })
            .collect(),
    };
    write(&dir.join("meta.json"), pretty(&meta).as_bytes())?;
    let listed = States {
        seed: states.seed,
        rest_probability: states.rest_probability,
        states: (states.draw)(item).iter().map(|values| object.configuration(values)).collect(),
    };
    write(&dir.join("states.json"), pretty(&listed).as_bytes())?;
    Ok(ExportedObject {
        folder,
        category: object.category.clone(),
        object_id: item.object_id,
        links: object.links.len(),
        joints: object.joints.len(),
        collision: summary(&physics),
        notes,
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
