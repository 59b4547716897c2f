//! A glTF or GLB asset: every node is a link (its meshes placed by the node's world
//! transform in the default scene), joints come from each node's `extras.joint` (the
//! sidecar's joint record; `parent` defaults to the node's parent, `child` to the node) or,
//! when a `<name>.joints.json` sidecar exists, from the sidecar alone. A node that no joint
//! moves is welded to its parent node (a second root node to the first root).
//!
//! Buffers are resolved by [`super::gltf_data`], not by the gltf crate.

use std::collections::HashSet;
use std::path::{Path, PathBuf};

use ::gltf::accessor::{DataType, Dimensions};
use ::gltf::mesh::{Mode, Semantic};
use nalgebra::Matrix4;
use pairs::math::Point3;
use serde::Deserialize;

use super::gltf_data::{document, load_buffers, parse, read_accessor, split_glb, ExternalLoader};
use super::mesh_build::build_mesh;
use super::obj_groups::category;
use super::sidecar::{read_sidecar, sidecar_path, JointSpec, Sidecar};
use super::skeleton::{RawJoint, RawKind, RawLink, Skeleton};
use super::surface::{Surface, SurfaceMaterial};
use super::{text, ImportError};
use articulated::mesh::Mesh;
use std::sync::Arc;

/// The skeleton of the glTF or GLB at `path` and the other files read (sidecar, buffers).
pub fn read_gltf_asset(path: &Path) -> Result<(Skeleton, Vec<PathBuf>), ImportError> {
    let bytes = text::read_bytes(path)?;
    let sidecar = sidecar_path(path);
    let spec = if sidecar.is_file() { Some(read_sidecar(&sidecar)?) } else { None };
    let base = path.parent().unwrap_or(Path::new(".")).to_path_buf();
    let external = move |uri: &str| {
        let file = base.join(uri);
        Ok((text::read_bytes(&file)?, file))
    };
    let (skeleton, mut files) = gltf_skeleton(path, &bytes, spec.as_ref(), &external)?;
    if spec.is_some() {
        files.insert(0, sidecar);
    }
    Ok((skeleton, files))
}

/// What a node's `extras` may hold.
#[derive(Debug, Deserialize)]
struct NodeExtras {
    #[serde(default)]
    joint: Option<JointSpec>,
}

/// The skeleton of glTF or GLB bytes (`path` names them in errors and gives the default
/// category), with joints from `sidecar` when given, else from node extras.
pub fn gltf_skeleton(
    path: &Path,
    bytes: &[u8],
    sidecar: Option<&Sidecar>,
    external: &ExternalLoader,
) -> Result<(Skeleton, Vec<PathBuf>), ImportError> {
    let (json, bin) = split_glb(path, bytes)?;
    if let Err(e) = std::str::from_utf8(json) {
        return Err(ImportError::NotUtf8 { path: path.into(), offset: e.valid_up_to() });
    }
    if json.starts_with(b"glTF") {
        return Err(parse(path, "glTF", "a GLB inside a JSON chunk".into()));
    }
    let document = document(path, json)?;
    let mut files = Vec::new();
    let buffers = load_buffers(&document, bin, external, &mut files)?;
    let materials = super::gltf_data::materials(&document, &buffers, external);
    let nodes = scene_nodes(&document)?;
    let mut links = Vec::with_capacity(nodes.len());
    let mut declared = Vec::new();
    let all: Vec<::gltf::Node> = document.nodes().collect();
    for placed in &nodes {
        let node = all.get(placed.index).ok_or_else(|| cycle(placed))?;
        let (mesh, surface) = node_mesh(node, placed, &buffers, &materials)?;
        links.push(RawLink { name: placed.name.clone(), mesh, surface });
        if sidecar.is_none() {
            if let Some(extras) = node.extras() {
                let extras: NodeExtras = serde_json::from_str(extras.get()).map_err(|e| {
                    parse(path, "glTF", format!("node {:?} extras: {e}", placed.name))
                })?;
                if let Some(spec) = extras.joint {
                    let parent = placed.parent.map(|p| nodes[p].name.as_str());
                    declared.push(spec.to_raw(parent, Some(&placed.name))?);
                }
            }
        }
    }
    if let Some(spec) = sidecar {
        declared = spec.joints.iter().map(|j| j.to_raw(None, None)).collect::<Result<_, _>>()?;
    }
    let moved: HashSet<&str> = declared.iter().map(|j| j.child.as_str()).collect();
    let mut joints = declared.clone();
    for (i, placed) in nodes.iter().enumerate() {
        // Welded to the hierarchy parent, or a later root to the first root.
        let parent = match placed.parent {
            Some(p) => p,
            None if i > 0 => 0,
            None => continue,
        };
        if !moved.contains(placed.name.as_str()) {
            joints.push(RawJoint {
                name: format!("fixed:{}", placed.name),
                kind: RawKind::Fixed,
                parent: nodes[parent].name.clone(),
                child: placed.name.clone(),
                origin: [0.0; 3],
                axis: [1.0, 0.0, 0.0],
                limits: None,
                mimic: None,
            });
        }
    }
    let category = category(path, sidecar.and_then(|s| s.category.as_deref()));
    Ok((Skeleton { category, links, joints }, files))
}

/// A node reached from the scene: its index, name, parent (index into the placed list)
/// and world transform.
#[derive(Debug, Clone)]
struct Placed {
    index: usize,
    name: String,
    parent: Option<usize>,
    world: Matrix4<f32>,
}

fn cycle(placed: &Placed) -> ImportError {
    ImportError::Cycle { link: placed.name.clone() }
}

/// The nodes of the default scene (or of the first scene, or every node that is nobody's
/// child), parents before children, each reached once.
fn scene_nodes(document: &::gltf::Document) -> Result<Vec<Placed>, ImportError> {
    let roots: Vec<::gltf::Node> =
        match document.default_scene().or_else(|| document.scenes().next()) {
            Some(scene) => scene.nodes().collect(),
            None => {
                let children: HashSet<usize> =
                    document.nodes().flat_map(|n| n.children().map(|c| c.index())).collect();
                document.nodes().filter(|n| !children.contains(&n.index())).collect()
            }
        };
    let mut placed: Vec<Placed> = Vec::new();
    let mut seen = HashSet::new();
    let mut stack: Vec<(::gltf::Node, Option<usize>)> =
        roots.into_iter().rev().map(|n| (n, None)).collect();
    while let Some((node, parent)) = stack.pop() {
        let name = node.name().map_or_else(|| format!("node{}", node.index()), String::from);
        if !seen.insert(node.index()) {
            return Err(ImportError::Cycle { link: name });
        }
        let local = Matrix4::from(node.transform().matrix());
        if !local.iter().all(|c| c.is_finite()) {
            return Err(ImportError::NonFinite { item: name, field: "transform" });
        }
        let world = parent.map_or(local, |p: usize| placed[p].world * local);
        let me = placed.len();
        placed.push(Placed { index: node.index(), name, parent, world });
        let children: Vec<_> = node.children().collect();
        stack.extend(children.into_iter().rev().map(|c| (c, Some(me))));
    }
    Ok(placed)
}

/// The triangles of a node's mesh in the rest frame (empty for a node without a mesh) and
/// their surface (each primitive's material and `TEXCOORD_0`); primitives that are not
/// triangle lists are skipped.
fn node_mesh(
    node: &::gltf::Node,
    placed: &Placed,
    buffers: &[Vec<u8>],
    materials: &[Arc<SurfaceMaterial>],
) -> Result<(Mesh, Surface), ImportError> {
    let Some(mesh) = node.mesh() else { return Ok((Mesh::default(), Surface::default())) };
    let (mut positions, mut triangles) = (Vec::new(), Vec::new());
    let mut surface = Surface::default();
    for primitive in mesh.primitives().filter(|p| p.mode() == Mode::Triangles) {
        let fail = |reason: String| ImportError::Accessor { node: placed.name.clone(), reason };
        let accessor = primitive
            .get(&Semantic::Positions)
            .ok_or_else(|| fail("a primitive without POSITION".into()))?;
        if accessor.data_type() != DataType::F32 || accessor.dimensions() != Dimensions::Vec3 {
            return Err(fail("POSITION is not a float VEC3".into()));
        }
        let offset = positions.len() as u32;
        let local = read_accessor(&accessor, buffers).map_err(&fail)?;
        positions.extend(local.chunks_exact(12).map(|c| {
            let f = |i: usize| f32::from_le_bytes([c[i], c[i + 1], c[i + 2], c[i + 3]]);
            placed.world.transform_point(&Point3::new(f(0), f(4), f(8)))
        }));
        let count = (positions.len() as u32) - offset;
        let indices: Vec<u32> = match primitive.indices() {
            None => (0..count).collect(),
            Some(accessor) => {
                if accessor.dimensions() != Dimensions::Scalar {
                    return Err(fail("indices are not SCALAR".into()));
                }
                let data = read_accessor(&accessor, buffers).map_err(&fail)?;
                match accessor.data_type() {
                    DataType::U8 => data.iter().map(|&b| u32::from(b)).collect(),
                    DataType::U16 => data
                        .chunks_exact(2)
                        .map(|c| u32::from(u16::from_le_bytes([c[0], c[1]])))
                        .collect(),
                    DataType::U32 => data
                        .chunks_exact(4)
                        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
                        .collect(),
                    _ => return Err(fail("indices are not unsigned integers".into())),
                }
            }
        };
        let uv = texcoords(&primitive, buffers);
        let material = primitive.material().index().and_then(|i| materials.get(i).cloned());
        for t in indices.chunks_exact(3) {
            // An index past this primitive's vertices is past every vertex: `u32::MAX`.
            let shift = |i: u32| if i < count { i + offset } else { u32::MAX };
            triangles.push([shift(t[0]), shift(t[1]), shift(t[2])]);
            if t.iter().all(|&i| i < count) {
                let at = |k: usize| positions[(t[k] + offset) as usize];
                surface.corners.push([at(0), at(1), at(2)]);
                let corner = |i: u32| uv.as_ref().and_then(|uv| uv.get(i as usize).copied());
                surface.uv.push(match (corner(t[0]), corner(t[1]), corner(t[2])) {
                    (Some(a), Some(b), Some(c)) => Some([a, b, c]),
                    _ => None,
                });
                surface.material.push(material.clone());
            }
        }
    }
    if triangles.is_empty() {
        return Ok((Mesh::default(), Surface::default()));
    }
    let mesh = build_mesh(&placed.name, &positions, &triangles).map_err(|e| match e {
        ImportError::MeshFile { reason, .. } => {
            ImportError::Accessor { node: placed.name.clone(), reason }
        }
        other => other,
    })?;
    Ok((mesh, surface))
}

/// A primitive's `TEXCOORD_0` as float pairs with v flipped to the OBJ convention (glTF's
/// origin is the image's top-left, OBJ's its bottom-left); `None` when absent or not float.
fn texcoords(primitive: &::gltf::Primitive, buffers: &[Vec<u8>]) -> Option<Vec<[f32; 2]>> {
    let accessor = primitive.get(&Semantic::TexCoords(0))?;
    if accessor.data_type() != DataType::F32 || accessor.dimensions() != Dimensions::Vec2 {
        return None;
    }
    let bytes = read_accessor(&accessor, buffers).ok()?;
    let f = |c: &[u8]| f32::from_le_bytes([c[0], c[1], c[2], c[3]]);
    Some(bytes.chunks_exact(8).map(|c| [f(&c[0..4]), 1.0 - f(&c[4..8])]).collect())
}
