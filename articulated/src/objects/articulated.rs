//! The articulated-object model: links with triangle meshes, joined by revolute and
//! prismatic joints in a tree.

use pairs::math::{Point3, Real, Vector3};
use pairs::JointKind;

use crate::mesh::Mesh;

/// A rigid piece of an object, its mesh given in the object's rest frame (all joints at 0).
#[derive(Debug, Clone, PartialEq)]
pub struct Link {
    /// Human-readable name (`lid`, `drawer`).
    pub name: String,
    /// Surface in the rest frame, object units.
    pub mesh: Mesh,
}

/// A joint that moves `child` relative to `parent`.
///
/// Axis and pivot are given in the rest frame; they move with the parent link.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    /// Name, unique within the object: the asset's joint name for imported objects; for
    /// built-in ones given by [`ArticulatedObject::attach`] from the child link's name.
    /// Provenance records joint values by it and exported URDFs use it.
    pub name: String,
    /// Revolute (value in radians) or prismatic (value in object units).
    pub kind: JointKind,
    /// Index of the parent link.
    pub parent: usize,
    /// Index of the child link; always greater than `parent`.
    pub child: usize,
    /// A point on the axis (rest frame); unused for prismatic joints.
    pub pivot: Point3,
    /// Unit axis direction (rest frame).
    pub axis: Vector3,
    /// Lowest and highest value.
    pub limits: (Real, Real),
    /// Value in the object's rest state (a closed door), within the limits.
    pub rest: Real,
}

/// A joint whose value follows another's, as a URDF `mimic` joint does:
/// `value[joint] = multiplier * value[leader] + offset`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mimic {
    /// Index of the joint that follows.
    pub joint: usize,
    /// Index of the joint it follows; never itself a follower.
    pub leader: usize,
    /// Factor applied to the leader's value.
    pub multiplier: Real,
    /// Added after the factor (radians or object units).
    pub offset: Real,
}

/// An object whose link 0 is the root; every other link has exactly one parent joint.
#[derive(Debug, Clone, PartialEq)]
pub struct ArticulatedObject {
    /// Category name.
    pub category: String,
    /// Links; index 0 is the root.
    pub links: Vec<Link>,
    /// Joints, one per non-root link.
    pub joints: Vec<Joint>,
    /// Joints whose values follow other joints (imported assets); empty for the built-in
    /// categories, whose joints all move independently.
    pub mimics: Vec<Mimic>,
}

/// An object that breaks the model's rules.
#[derive(Debug, thiserror::Error, PartialEq)]
#[non_exhaustive]
pub enum ObjectError {
    /// A link has no triangles, or a non-finite vertex.
    #[error("{category}: link {link} has an empty or non-finite mesh")]
    BadMesh {
        /// Category name.
        category: String,
        /// Link name.
        link: String,
    },
    /// The joints do not form a tree rooted at link 0 with parents before children.
    #[error("{category}: joint {joint} does not fit a tree rooted at link 0 ({reason})")]
    NotATree {
        /// Category name.
        category: String,
        /// Joint index.
        joint: usize,
        /// What is wrong.
        reason: String,
    },
    /// A joint's axis is not unit length, or its limits or rest value are out of order.
    #[error("{category}: joint {joint} has {reason}")]
    BadJoint {
        /// Category name.
        category: String,
        /// Joint index.
        joint: usize,
        /// What is wrong.
        reason: String,
    },
}

impl Joint {
    /// A revolute joint about `axis` (normalised here) through `pivot`, with `limits` in
    /// radians and rest value 0; the right-hand rule about `axis` gives the turning sense.
    /// `parent` and `child` are set by [`ArticulatedObject::attach`].
    pub fn revolute(pivot: Point3, axis: Vector3, limits: (Real, Real)) -> Self {
        Self {
            name: String::new(),
            kind: JointKind::Revolute,
            parent: 0,
            child: 0,
            pivot,
            // A zero axis is a category's mistake; z keeps it from filling a dataset with
            // NaNs (the object checks then see a joint that turns about z).
            axis: pairs::math::unit_or(&axis, Vector3::z()),
            limits,
            rest: 0.0,
        }
    }

    /// A prismatic joint along `axis` (normalised here), `limits` in object units, rest
    /// value 0; `at` marks where the slide is (the pivot), for readers of the joint.
    pub fn prismatic(at: Point3, axis: Vector3, limits: (Real, Real)) -> Self {
        Self { kind: JointKind::Prismatic, ..Self::revolute(at, axis, limits) }
    }

    /// A hinge that is closed at 0 (the rest value) and opens to `max_angle` radians.
    pub fn hinge(pivot: Point3, axis: Vector3, max_angle: Real) -> Self {
        Self::revolute(pivot, axis, (0.0, max_angle))
    }

    /// A slide that is closed at 0 (the rest value) and pulls out by up to `max_travel`.
    pub fn slide(at: Point3, axis: Vector3, max_travel: Real) -> Self {
        Self::prismatic(at, axis, (0.0, max_travel))
    }
}

/// `name` with every character outside `[A-Za-z0-9_-]` as `_` (`_` for an empty name): a
/// name safe in URDF, file names and shell commands.
pub fn identifier(name: &str) -> String {
    let id: String =
        name.chars().map(|c| if c.is_ascii_alphanumeric() || c == '-' { c } else { '_' }).collect();
    if id.is_empty() {
        "_".into()
    } else {
        id
    }
}

impl ArticulatedObject {
    /// An object with only its root link.
    pub fn new(category: &str, root: Link) -> Self {
        Self {
            category: category.into(),
            links: vec![root],
            joints: Vec::new(),
            mimics: Vec::new(),
        }
    }

    /// Adds `link` as the child of `parent` through a joint; returns the new link's index.
    /// A joint without a name gets the child link's (spaces and other characters outside
    /// `[A-Za-z0-9_-]` as `_`), with `_<link index>` added if another joint has it.
    pub fn attach(&mut self, parent: usize, link: Link, mut joint: Joint) -> usize {
        let child = self.links.len();
        if joint.name.is_empty() {
            joint.name = identifier(&link.name);
            if self.joints.iter().any(|j| j.name == joint.name) {
                joint.name = format!("{}_{child}", joint.name);
            }
        }
        self.links.push(link);
        joint.parent = parent;
        joint.child = child;
        self.joints.push(joint);
        child
    }

    /// Index of the joint whose child is `link`, for every link (None for the root).
    pub fn parent_joints(&self) -> Vec<Option<usize>> {
        let mut parents = vec![None; self.links.len()];
        for (j, joint) in self.joints.iter().enumerate() {
            if let Some(slot) = parents.get_mut(joint.child) {
                *slot = Some(j);
            }
        }
        parents
    }

    /// A state as a map from joint name to value (`values` in the order of
    /// [`Self::joints`]), as the provenance and `states.json` files write it.
    pub fn configuration(&self, values: &[Real]) -> std::collections::BTreeMap<String, Real> {
        self.joints.iter().zip(values).map(|(j, &v)| (j.name.clone(), v)).collect()
    }

    /// Sets every mimic joint of a state from its leader, so that the values agree with
    /// the object's couplings; a no-op for objects without mimic joints.
    pub fn follow_mimics(&self, values: &mut [Real]) {
        for m in &self.mimics {
            if let (Some(&leader), true) = (values.get(m.leader), m.joint < values.len()) {
                values[m.joint] = m.multiplier * leader + m.offset;
            }
        }
    }

    /// Checks the rules of the model: non-empty finite meshes, a tree with parents before
    /// children, unit axes, ordered limits that hold the rest value, mimic joints that
    /// follow a joint that is not itself a follower.
    pub fn validate(&self) -> Result<(), ObjectError> {
        let category = || self.category.clone();
        for link in &self.links {
            let finite = link.mesh.vertices.iter().all(|v| v.coords.iter().all(|c| c.is_finite()));
            if link.mesh.triangles.is_empty() || !finite {
                return Err(ObjectError::BadMesh { category: category(), link: link.name.clone() });
            }
        }
        let mut seen = vec![false; self.links.len()];
        for (j, joint) in self.joints.iter().enumerate() {
            let tree_error = |reason: &str| ObjectError::NotATree {
                category: category(),
                joint: j,
                reason: reason.into(),
            };
            if joint.child >= self.links.len() || joint.child == 0 {
                return Err(tree_error("child is the root or out of range"));
            }
            if joint.parent >= joint.child {
                return Err(tree_error("parent does not come before child"));
            }
            if std::mem::replace(&mut seen[joint.child], true) {
                return Err(tree_error("child already has a parent joint"));
            }
            let joint_error = |reason: &str| ObjectError::BadJoint {
                category: category(),
                joint: j,
                reason: reason.into(),
            };
            if (joint.axis.norm() - 1.0).abs() > 1e-4 {
                return Err(joint_error("an axis that is not unit length"));
            }
            if joint.name.is_empty() || self.joints[..j].iter().any(|o| o.name == joint.name) {
                return Err(joint_error("an empty name or the name of another joint"));
            }
            let (lo, hi) = joint.limits;
            if !(lo < hi && lo <= joint.rest && joint.rest <= hi) {
                return Err(joint_error("limits out of order or a rest value outside them"));
            }
        }
        self.validate_mimics()?;
        if let Some(orphan) = seen.iter().skip(1).position(|s| !s) {
            let reason = format!("link {} has no parent joint", orphan + 1);
            return Err(ObjectError::NotATree {
                category: category(),
                joint: self.joints.len(),
                reason,
            });
        }
        Ok(())
    }

    /// The mimic rules of [`Self::validate`].
    fn validate_mimics(&self) -> Result<(), ObjectError> {
        let n = self.joints.len();
        for m in &self.mimics {
            let bad = |reason: &str| ObjectError::BadJoint {
                category: self.category.clone(),
                joint: m.joint,
                reason: reason.into(),
            };
            if m.joint >= n || m.leader >= n || m.joint == m.leader {
                return Err(bad("a mimic of itself or of a joint out of range"));
            }
            if self.mimics.iter().any(|o| o.joint == m.leader) {
                return Err(bad("a mimic of a joint that is itself a mimic"));
            }
            if !(m.multiplier.is_finite() && m.offset.is_finite()) {
                return Err(bad("a non-finite mimic multiplier or offset"));
            }
        }
        Ok(())
    }
}
