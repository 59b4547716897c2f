//! The intermediate every importer produces, and its assembly into the articulated-object
//! model: one set of rules for every format.

use std::collections::HashMap;

use pairs::math::{Point3, Real};
use pairs::JointKind;

use super::ImportError;
use crate::mesh::Mesh;
use crate::objects::{ArticulatedObject, Joint, Link, Mimic};

/// A named rigid piece with its mesh in the asset's rest frame (all joints at 0).
#[derive(Debug, Clone, PartialEq)]
pub struct RawLink {
    /// Link, part or node name.
    pub name: String,
    /// Surface in the rest frame; may be empty for a link welded to a non-empty one.
    pub mesh: Mesh,
}

/// Joint types of the asset formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RawKind {
    /// Rotation within limits.
    Revolute,
    /// Rotation without limits (given the configured range).
    Continuous,
    /// Translation within limits.
    Prismatic,
    /// No motion: the child is welded into its parent's part.
    Fixed,
}

impl RawKind {
    /// The kind named `name` in a URDF, sidecar or glTF extras, or a typed error.
    pub fn parse(joint: &str, name: &str) -> Result<Self, ImportError> {
        match name {
            "revolute" => Ok(Self::Revolute),
            "continuous" => Ok(Self::Continuous),
            "prismatic" => Ok(Self::Prismatic),
            "fixed" => Ok(Self::Fixed),
            "floating" | "planar" | "spherical" => {
                Err(ImportError::UnsupportedJoint { joint: joint.into(), kind: name.into() })
            }
            _ => Err(ImportError::UnknownJointType { joint: joint.into(), found: name.into() }),
        }
    }
}

/// A joint follows another: `value = multiplier * leader + offset`.
#[derive(Debug, Clone, PartialEq)]
pub struct RawMimic {
    /// Name of the joint followed.
    pub leader: String,
    /// Factor (URDF default 1).
    pub multiplier: f64,
    /// Offset (URDF default 0).
    pub offset: f64,
}

/// A named joint with its axis line in the rest frame.
#[derive(Debug, Clone, PartialEq)]
pub struct RawJoint {
    /// Joint name.
    pub name: String,
    /// Type.
    pub kind: RawKind,
    /// Parent link name.
    pub parent: String,
    /// Child link name.
    pub child: String,
    /// A point on the axis, rest frame.
    pub origin: [f64; 3],
    /// Axis direction, rest frame (any non-zero length).
    pub axis: [f64; 3],
    /// Lower and upper limit (radians or units); `None` where the format gave none.
    pub limits: Option<(f64, f64)>,
    /// The joint it follows, if any.
    pub mimic: Option<RawMimic>,
}

/// An asset read into named links and joints.
#[derive(Debug, Clone, PartialEq)]
pub struct Skeleton {
    /// Category written into provenance (URDF robot name, sidecar `category`, file stem).
    pub category: String,
    /// Links in file order.
    pub links: Vec<RawLink>,
    /// Joints in file order.
    pub joints: Vec<RawJoint>,
}

/// Joint names, link names and parent links checked: `parent_joint[link]` is the index of
/// the joint whose child the link is, and `root` the one link without one.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Tree {
    /// Per link, its parent joint.
    pub parent_joint: Vec<Option<usize>>,
    /// Per joint, (parent link, child link).
    pub ends: Vec<(usize, usize)>,
    /// The root link.
    pub root: usize,
}

/// Checks that `joints` (name, parent, child) form a tree over `links`: unique names,
/// known links, one parent per link, no cycle, one root.
pub fn check_tree<'a>(
    links: &[&'a str],
    joints: &[(&'a str, &'a str, &'a str)],
) -> Result<Tree, ImportError> {
    let mut index: HashMap<&str, usize> = HashMap::new();
    for (i, name) in links.iter().enumerate() {
        if index.insert(name, i).is_some() {
            return Err(ImportError::DuplicateName { what: "link", name: (*name).into() });
        }
    }
    let mut joint_names: HashMap<&str, ()> = HashMap::new();
    let mut parent_joint = vec![None; links.len()];
    let mut ends = Vec::with_capacity(joints.len());
    for (j, &(name, parent, child)) in joints.iter().enumerate() {
        if joint_names.insert(name, ()).is_some() {
            return Err(ImportError::DuplicateName { what: "joint", name: name.into() });
        }
        let find = |link: &str| {
            index
                .get(link)
                .copied()
                .ok_or_else(|| ImportError::UnknownLink { joint: name.into(), link: link.into() })
        };
        let (p, c) = (find(parent)?, find(child)?);
        if p == c {
            return Err(ImportError::Cycle { link: child.into() });
        }
        if let Some(first) = parent_joint[c].replace(j) {
            return Err(ImportError::MultipleParents {
                link: child.into(),
                first: joints[first].0.into(),
                second: name.into(),
            });
        }
        ends.push((p, c));
    }
    // With one parent per link, a walk up longer than the number of links is a cycle.
    for start in 0..links.len() {
        let mut at = start;
        for _ in 0..=links.len() {
            match parent_joint[at] {
                Some(j) => at = ends[j].0,
                None => break,
            }
        }
        if parent_joint[at].is_some() {
            return Err(ImportError::Cycle { link: links[at].into() });
        }
    }
    let roots: Vec<usize> = (0..links.len()).filter(|&l| parent_joint[l].is_none()).collect();
    match roots.as_slice() {
        [root] => Ok(Tree { parent_joint, ends, root: *root }),
        _ => Err(ImportError::Roots { roots: roots.iter().map(|&l| links[l].into()).collect() }),
    }
}

impl Skeleton {
    /// The joint graph checked as a tree.
    pub fn tree(&self) -> Result<Tree, ImportError> {
        let links: Vec<&str> = self.links.iter().map(|l| l.name.as_str()).collect();
        let joints: Vec<(&str, &str, &str)> = self
            .joints
            .iter()
            .map(|j| (j.name.as_str(), j.parent.as_str(), j.child.as_str()))
            .collect();
        check_tree(&links, &joints)
    }
}

/// The articulated object of a skeleton (module docs of `crate::import` give the rules);
/// `continuous` is the range of joints without limits, radians.
pub fn assemble(
    skeleton: Skeleton,
    continuous: (f64, f64),
) -> Result<ArticulatedObject, ImportError> {
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
    // Depth first from the root, siblings by name: parts in that order, welded links
    // appended to their part's mesh in the same order.
    let mut order: Vec<usize> = Vec::new(); // parts (their first link)
    let mut moving: Vec<usize> = Vec::new(); // joint of each part but the root
    let mut meshes: HashMap<usize, Mesh> = HashMap::new();
    let mut stack = vec![tree.root];
    while let Some(link) = stack.pop() {
        let part = part_of(link);
        if part == link {
            order.push(link);
            if let Some(j) = tree.parent_joint[link] {
                moving.push(j);
            }
        }
        meshes.entry(part).or_default().append(links[link].mesh.clone());
        stack.extend(children_of(link).into_iter().rev().map(|j| tree.ends[j].1));
    }
    let position: HashMap<usize, usize> = order.iter().enumerate().map(|(i, &l)| (l, i)).collect();
    let mut object_links = Vec::with_capacity(order.len());
    for &l in &order {
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
    Ok(object)
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
