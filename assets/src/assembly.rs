//! A skeleton into the articulated-object model, by one set of rules for every format:
//! fixed joints weld a link into its parent's part, parts are ordered parents first, then
//! by name, joints get their limits (continuous ones the configured range), and
//! mimic joints are resolved onto their first leader.

use std::collections::HashMap;

use pairs::math::{Point3, Real};
use pairs::JointKind;

use super::skeleton::{RawJoint, RawKind, Skeleton};
use super::surface::Surface;
use super::ImportError;
use articulated::mesh::Mesh;
use articulated::objects::{ArticulatedObject, Joint, Link, Mimic};

/// The articulated object of a skeleton (module docs of `crate::import` give the rules);
/// `continuous` is the range of joints without limits, radians.
pub fn assemble(
    skeleton: Skeleton,
    continuous: (f64, f64),
) -> Result<ArticulatedObject, ImportError> {
    assemble_with_surfaces(skeleton, continuous).map(|(object, _)| object)
}

/// [`assemble`], also returning each object link's surface (its links' surfaces appended
/// in the order their meshes are).
pub fn assemble_with_surfaces(
    skeleton: Skeleton,
    continuous: (f64, f64),
) -> Result<(ArticulatedObject, Vec<Surface>), ImportError> {
    let tree = skeleton.tree()?;
    let Skeleton { category, links, joints } = skeleton;
    // Each link's part: the nearest ancestor (or itself) not attached by a fixed joint.
    let part_of = |mut link: usize| loop {
        match tree.parent_joint[link] {
            Some(j) if joints[j].kind == RawKind::Fixed => link = tree.ends[j].0,
            _ => return link,
        }
    };
    let children_of = |link: usize| {
        let mut c: Vec<usize> = joints
            .iter()
            .enumerate()
            .filter(|(j, _)| tree.ends[*j].0 == link)
            .map(|(j, _)| j)
            .collect();
        c.sort_by(|&a, &b| links[tree.ends[a].1].name.cmp(&links[tree.ends[b].1].name));
        c
    };
    // Depth first from the root, siblings by name: each part's mesh is its links' meshes
    // appended in that order.
    let mut parts: Vec<usize> = Vec::new(); // each part's first link, depth first
    let mut meshes: HashMap<usize, Mesh> = HashMap::new();
    let mut surfaces: HashMap<usize, Surface> = HashMap::new();
    let mut stack = vec![tree.root];
    while let Some(link) = stack.pop() {
        let part = part_of(link);
        if part == link {
            parts.push(link);
        }
        meshes.entry(part).or_default().append(links[link].mesh.clone());
        surfaces.entry(part).or_default().append(links[link].surface.clone());
        stack.extend(children_of(link).into_iter().rev().map(|j| tree.ends[j].1));
    }
    // Parts in order: parents before children, otherwise by name in natural order
    // (`link_2` before `link_10`), so that any order with parents first can be written
    // down by naming, as `generator export-objects` does.
    let parent_part = |part: usize| tree.parent_joint[part].map(|j| part_of(tree.ends[j].0));
    let mut order: Vec<usize> = Vec::with_capacity(parts.len());
    let mut ready: Vec<usize> = vec![tree.root];
    while !ready.is_empty() {
        let next = (0..ready.len())
            .min_by(|&a, &b| {
                alphanumeric_sort::compare_str(&links[ready[a]].name, &links[ready[b]].name)
                    .then_with(|| links[ready[a]].name.cmp(&links[ready[b]].name))
            })
            .unwrap_or(0);
        let part = ready.swap_remove(next);
        order.push(part);
        ready.extend(parts.iter().copied().filter(|&child| parent_part(child) == Some(part)));
    }
    // Joint of each part but the root, in part order.
    let moving: Vec<usize> = order.iter().filter_map(|&l| tree.parent_joint[l]).collect();
    let position: HashMap<usize, usize> = order.iter().enumerate().map(|(i, &l)| (l, i)).collect();
    let mut object_links = Vec::with_capacity(order.len());
    let mut object_surfaces = Vec::with_capacity(order.len());
    for &l in &order {
        object_surfaces.push(surfaces.remove(&l).unwrap_or_default());
        let mesh = meshes.remove(&l).unwrap_or_default();
        if mesh.triangles.is_empty() {
            return Err(ImportError::EmptyMesh { link: links[l].name.clone() });
        }
        object_links.push(Link { name: links[l].name.clone(), mesh });
    }
    let mut object_joints = Vec::with_capacity(moving.len());
    for &j in &moving {
        let raw = &joints[j];
        let (parent, child) = (position[&part_of(tree.ends[j].0)], position[&tree.ends[j].1]);
        object_joints.push(model_joint(raw, parent, child, continuous)?);
    }
    let joint_index: HashMap<&str, usize> =
        moving.iter().enumerate().map(|(i, &j)| (joints[j].name.as_str(), i)).collect();
    let mimics = resolve_mimics(&joints, &moving, &joint_index, &mut object_joints)?;
    let object = ArticulatedObject { category, links: object_links, joints: object_joints, mimics };
    object.validate()?;
    Ok((object, object_surfaces))
}

/// A moving joint of the model from an asset joint.
fn model_joint(
    raw: &RawJoint,
    parent: usize,
    child: usize,
    continuous: (f64, f64),
) -> Result<Joint, ImportError> {
    let name = || raw.name.clone();
    let finite = |v: &[f64]| v.iter().all(|c| c.is_finite());
    if !finite(&raw.axis) {
        return Err(ImportError::NonFinite { item: name(), field: "axis" });
    }
    if !finite(&raw.origin) {
        return Err(ImportError::NonFinite { item: name(), field: "origin" });
    }
    let axis = nalgebra::Vector3::from(raw.axis);
    let length = axis.norm();
    // The entries are finite here, so the length is too.
    if length <= 1e-9 {
        return Err(ImportError::ZeroAxis { joint: name() });
    }
    let (lo, hi) = match (raw.kind, raw.limits) {
        (RawKind::Continuous, _) => continuous,
        (_, Some(limits)) => limits,
        (_, None) => (0.0, 0.0),
    };
    if !(lo.is_finite() && hi.is_finite() && lo < hi && (lo as Real) < (hi as Real)) {
        return Err(ImportError::BadLimits { joint: name(), lower: lo, upper: hi });
    }
    let kind = match raw.kind {
        RawKind::Prismatic => JointKind::Prismatic,
        _ => JointKind::Revolute,
    };
    let limits = (lo as Real, hi as Real);
    Ok(Joint {
        name: raw.name.clone(),
        kind,
        parent,
        child,
        pivot: Point3::from(raw.origin.map(|c| c as Real)),
        axis: (axis / length).cast::<Real>(),
        limits,
        rest: 0.0f32.clamp(limits.0, limits.1),
    })
}

/// The model's mimics: chains of mimics are composed onto their first leader, and each
/// follower's limits and rest value become the image of its leader's.
fn resolve_mimics(
    joints: &[RawJoint],
    moving: &[usize],
    index: &HashMap<&str, usize>,
    model: &mut [Joint],
) -> Result<Vec<Mimic>, ImportError> {
    let mut mimics = Vec::new();
    for (i, &j) in moving.iter().enumerate() {
        let Some(mimic) = &joints[j].mimic else { continue };
        let fail = |reason: String| ImportError::Mimic { joint: joints[j].name.clone(), reason };
        if !(mimic.multiplier.is_finite() && mimic.offset.is_finite()) {
            return Err(ImportError::NonFinite { item: joints[j].name.clone(), field: "mimic" });
        }
        let (mut multiplier, mut offset) = (mimic.multiplier, mimic.offset);
        let mut leader_name = mimic.leader.as_str();
        let mut steps = 0;
        let leader = loop {
            let Some(&leader) = index.get(leader_name) else {
                return Err(fail(format!("follows {leader_name:?}, which is not a moving joint")));
            };
            match &joints[moving[leader]].mimic {
                None => break leader,
                Some(next) => {
                    steps += 1;
                    if steps > moving.len() {
                        return Err(fail("joints follow each other in a cycle".into()));
                    }
                    offset += multiplier * next.offset;
                    multiplier *= next.multiplier;
                    leader_name = next.leader.as_str();
                }
            }
        };
        if leader == i {
            return Err(fail("joints follow each other in a cycle".into()));
        }
        let (m, o) = (multiplier as Real, offset as Real);
        let (a, b) = (m * model[leader].limits.0 + o, m * model[leader].limits.1 + o);
        let limits = (a.min(b), a.max(b));
        if limits.0 >= limits.1 || !limits.0.is_finite() || !limits.1.is_finite() {
            return Err(fail(format!("multiplier {multiplier} leaves no range of motion")));
        }
        model[i].limits = limits;
        model[i].rest = m * model[leader].rest + o;
        mimics.push(Mimic { joint: i, leader, multiplier: m, offset: o });
    }
    Ok(mimics)
}
