//! The intermediate every importer produces (named links and joints in the asset's rest
//! frame) and the check that its joints form a tree; [`super::assembly`] turns it into
//! the articulated-object model.

use std::collections::HashMap;

use super::surface::Surface;
use super::ImportError;
use articulated::mesh::Mesh;

/// A named rigid piece with its mesh in the asset's rest frame (all joints at 0).
#[derive(Debug, Clone, PartialEq)]
pub struct RawLink {
    /// Link, part or node name.
    pub name: String,
    /// Surface in the rest frame; may be empty for a link welded to a non-empty one.
    pub mesh: Mesh,
    /// Its triangles' materials, same frame (for renders; may be empty).
    pub surface: Surface,
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
