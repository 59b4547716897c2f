//! A glTF or GLB asset: every node is a link (its meshes placed by the node's world
//! transform in the default scene), joints come from each node's `extras.joint` (the
//! sidecar's joint record; `parent` defaults to the node's parent, `child` to the node) or,
//! when a `<name>.joints.json` sidecar exists, from the sidecar alone. A node that no joint
//! moves is welded to its parent node (a second root node to the first root).
//!
//! Buffers are resolved here, not by the gltf crate: the GLB container is split with
//! checked lengths, `data:` URIs are decoded, other URIs are read relative to the file,
//! and every buffer, view and accessor is checked against the bytes actually present, so
//! that a file claiming a 2 GB buffer is an error rather than an allocation.

use std::collections::HashSet;
use std::path::{Path, PathBuf};

use ::gltf::accessor::{DataType, Dimensions};
use ::gltf::buffer::Source;
use ::gltf::mesh::{Mode, Semantic};
use base64::Engine as _;
use nalgebra::Matrix4;
use pairs::math::Point3;
use serde::Deserialize;

use super::mesh_build::build_mesh;
use super::obj_groups::category;
use super::sidecar::{read_sidecar, sidecar_path, JointSpec, Sidecar};
use super::skeleton::{RawJoint, RawKind, RawLink, Skeleton};
use super::{text, ImportError};
use crate::mesh::Mesh;

/// Reads a buffer that a URI names: (bytes, the file read).
pub type ExternalLoader<'a> = dyn Fn(&str) -> Result<(Vec<u8>, PathBuf), ImportError> + 'a;

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
    let nodes = scene_nodes(&document)?;
    let mut links = Vec::with_capacity(nodes.len());
    let mut declared = Vec::new();
    let all: Vec<::gltf::Node> = document.nodes().collect();
    for placed in &nodes {
        let node = all.get(placed.index).ok_or_else(|| cycle(placed))?;
        links.push(RawLink { name: placed.name.clone(), mesh: node_mesh(node, placed, &buffers)? });
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

/// The glTF document of JSON bytes, validated.
fn document(path: &Path, json: &[u8]) -> Result<::gltf::Document, ImportError> {
    let root: ::gltf::json::Root = ::gltf::json::deserialize::from_slice(json)
        .map_err(|e| parse(path, "glTF", e.to_string()))?;
    // gltf-json 1.4.1 looks up a primitive's POSITION accessor while validating, before it
    // checks the index, and panics on one out of range: check every attribute first.
    // Found by fuzzing: generator/tests/fuzz_regressions/gltf/.
    for (m, mesh) in root.meshes.iter().enumerate() {
        for primitive in &mesh.primitives {
            if primitive.attributes.values().any(|a| a.value() >= root.accessors.len()) {
                let reason = format!("mesh {m} names an accessor that does not exist");
                return Err(parse(path, "glTF", reason));
            }
        }
    }
    ::gltf::Document::from_json(root).map_err(|e| parse(path, "glTF", e.to_string()))
}

fn parse(path: &Path, format: &'static str, reason: String) -> ImportError {
    ImportError::Parse { path: path.into(), format, reason }
}

/// The JSON chunk and BIN chunk of a GLB (checked lengths), or the bytes as JSON.
fn split_glb<'a>(
    path: &Path,
    bytes: &'a [u8],
) -> Result<(&'a [u8], Option<&'a [u8]>), ImportError> {
    if !bytes.starts_with(b"glTF") {
        return Ok((bytes, None));
    }
    let fail = |reason: &str| parse(path, "GLB", reason.into());
    let word = |at: usize| -> Option<usize> {
        let b = bytes.get(at..at.checked_add(4)?)?;
        Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize)
    };
    let (version, length) = (word(4), word(8));
    if version != Some(2) {
        return Err(fail("only GLB version 2 is supported"));
    }
    let end = match length {
        Some(n) if (12..=bytes.len()).contains(&n) => n,
        _ => return Err(fail("the header's length is outside the file")),
    };
    let chunk = |at: usize| -> Option<(&'a [u8], &'a [u8], usize)> {
        let length = word(at)?;
        let kind = bytes.get(at + 4..at + 8)?;
        let start = at.checked_add(8)?;
        let stop = start.checked_add(length)?;
        (stop <= end).then(|| (kind, &bytes[start..stop], stop))
    };
    let (kind, json, next) = chunk(12).ok_or_else(|| fail("the JSON chunk is cut short"))?;
    if kind != b"JSON" {
        return Err(fail("the first chunk is not JSON"));
    }
    let bin = match next.checked_add(8) {
        Some(n) if n <= end => {
            let (kind, data, _) = chunk(next).ok_or_else(|| fail("the BIN chunk is cut short"))?;
            (kind == b"BIN\0").then_some(data)
        }
        _ => None,
    };
    Ok((json, bin))
}

/// Every buffer's bytes, checked to hold at least the length the buffer claims.
fn load_buffers(
    document: &::gltf::Document,
    bin: Option<&[u8]>,
    external: &ExternalLoader,
    files: &mut Vec<PathBuf>,
) -> Result<Vec<Vec<u8>>, ImportError> {
    let mut buffers = Vec::new();
    for buffer in document.buffers() {
        let index = buffer.index();
        let fail = |reason: String| ImportError::Buffer { index, reason };
        let data = match buffer.source() {
            Source::Bin => {
                bin.ok_or_else(|| fail("refers to a BIN chunk the file lacks".into()))?.to_vec()
            }
            Source::Uri(uri) if uri.starts_with("data:") => {
                let (head, payload) =
                    uri.split_once(',').ok_or_else(|| fail("a data URI without a comma".into()))?;
                if !head.ends_with(";base64") {
                    return Err(fail("only base64 data URIs are supported".into()));
                }
                base64::engine::general_purpose::STANDARD
                    .decode(payload)
                    .map_err(|e| fail(format!("bad base64: {e}")))?
            }
            Source::Uri(uri) => {
                let (data, file) = external(uri)?;
                files.push(file);
                data
            }
        };
        if data.len() < buffer.length() {
            return Err(fail(format!("claims {} bytes but holds {}", buffer.length(), data.len())));
        }
        buffers.push(data);
    }
    Ok(buffers)
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

/// The triangles of a node's mesh in the rest frame (empty for a node without a mesh);
/// primitives that are not triangle lists are skipped.
fn node_mesh(
    node: &::gltf::Node,
    placed: &Placed,
    buffers: &[Vec<u8>],
) -> Result<Mesh, ImportError> {
    let Some(mesh) = node.mesh() else { return Ok(Mesh::default()) };
    let (mut positions, mut triangles) = (Vec::new(), Vec::new());
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
        for t in indices.chunks_exact(3) {
            // An index past this primitive's vertices is past every vertex: `u32::MAX`.
            let shift = |i: u32| if i < count { i + offset } else { u32::MAX };
            triangles.push([shift(t[0]), shift(t[1]), shift(t[2])]);
        }
    }
    if triangles.is_empty() {
        return Ok(Mesh::default());
    }
    build_mesh(&placed.name, &positions, &triangles).map_err(|e| match e {
        ImportError::MeshFile { reason, .. } => {
            ImportError::Accessor { node: placed.name.clone(), reason }
        }
        other => other,
    })
}

/// An accessor's elements packed tightly (`count * element size` bytes), after checking
/// that the accessor fits its view and the view fits the buffer's real bytes.
fn read_accessor(accessor: &::gltf::Accessor, buffers: &[Vec<u8>]) -> Result<Vec<u8>, String> {
    if accessor.sparse().is_some() {
        return Err("sparse accessors are not supported".into());
    }
    let view = accessor.view().ok_or("an accessor without a buffer view")?;
    let buffer = buffers.get(view.buffer().index()).ok_or("a view of a missing buffer")?;
    let element = accessor.size();
    let stride = view.stride().unwrap_or(element);
    if stride < element {
        return Err(format!("byteStride {stride} is smaller than an element ({element} bytes)"));
    }
    let view_end = view.offset().checked_add(view.length());
    let data = match view_end {
        Some(end) if end <= buffer.len() => &buffer[view.offset()..end],
        _ => return Err("a buffer view reaches past its buffer's bytes".into()),
    };
    let count = accessor.count();
    let needed = match count {
        0 => Some(0),
        n => stride
            .checked_mul(n - 1)
            .and_then(|b| b.checked_add(element))
            .and_then(|b| b.checked_add(accessor.offset())),
    };
    match needed {
        Some(n) if n <= data.len() => {}
        _ => return Err(format!("{count} elements do not fit the buffer view")),
    }
    let mut packed = Vec::with_capacity(count * element);
    for i in 0..count {
        let start = accessor.offset() + i * stride;
        packed.extend_from_slice(&data[start..start + element]);
    }
    Ok(packed)
}
