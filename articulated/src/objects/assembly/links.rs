//! Links and joints of a planned segment tree: each moving segment starts a link, every
//! other segment is welded into its parent's link, and a sleeve joins its parent's link.

use pairs::math::Real;
use pairs::JointKind;

use super::geometry::{Block, Face};
use super::motions::Motion;
use super::segments::Segment;
use crate::mesh::Mesh;
use crate::objects::{ArticulatedObject, Joint, Link};

/// An assembly as an articulated object, with each link's boxes for fast checks (the root's
/// primitive by its bounding box).
#[derive(Debug, Clone)]
pub(super) struct Assembly {
    /// The object.
    pub object: ArticulatedObject,
    /// The boxes of every link, at rest.
    pub blocks: Vec<Vec<Block>>,
}

/// Builds the object of `segments` moving by `motions` (one entry per segment).
pub(super) fn assemble(
    category: &str,
    segments: &[Segment],
    motions: &[Option<Motion>],
) -> Assembly {
    let mut link_of = vec![0; segments.len()];
    let mut meshes: Vec<Vec<Mesh>> = vec![Vec::new()];
    let mut blocks: Vec<Vec<Block>> = vec![Vec::new()];
    let mut joints: Vec<(String, Joint)> = Vec::new();
    for (i, segment) in segments.iter().enumerate() {
        let parent = segment.parent.map_or(0, |p| link_of[p]);
        link_of[i] = match (motions[i], segment.face) {
            (Some(motion), Some(face)) => {
                if let Motion::Slide { .. } = motion {
                    for wall in segment.sleeve_walls() {
                        meshes[parent].push(Mesh::cuboid(wall.min, wall.max));
                        blocks[parent].push(wall);
                    }
                }
                joints.push(joint(i, segment, face, motion, parent));
                meshes.push(Vec::new());
                blocks.push(Vec::new());
                meshes.len() - 1
            }
            _ => parent,
        };
        meshes[link_of[i]].push(segment.mesh());
        blocks[link_of[i]].extend(segment.bodies());
    }
    let mut meshes = meshes.into_iter().map(Mesh::union);
    let root = Link { name: "root".into(), mesh: meshes.next().unwrap_or_default() };
    let mut object = ArticulatedObject::new(category, root);
    for ((name, joint), mesh) in joints.into_iter().zip(meshes) {
        object.attach(joint.parent, Link { name, mesh }, joint);
    }
    Assembly { object, blocks }
}

/// The link name and the joint of moving segment `index`, whose parent is in link `parent`.
fn joint(
    index: usize,
    segment: &Segment,
    face: Face,
    motion: Motion,
    parent: usize,
) -> (String, Joint) {
    let normal = face.normal();
    let joint = |kind, pivot, axis, limits: (Real, Real)| Joint {
        name: String::new(),
        kind,
        parent,
        child: 0,
        pivot,
        axis,
        limits,
        rest: 0.0,
    };
    match motion {
        Motion::Hinge { out, max } => {
            // About the edge's midpoint; turning inward x normal lifts the far side away.
            let pivot = segment.contact + out * segment.block.half()[out.iamax()];
            let axis = (-out).cross(&normal);
            (format!("hinged box {index}"), joint(JointKind::Revolute, pivot, axis, (0.0, max)))
        }
        Motion::Twist { pivot, limits } => {
            (format!("swivelling box {index}"), joint(JointKind::Revolute, pivot, normal, limits))
        }
        Motion::Slide { travel, .. } => (
            format!("sliding box {index}"),
            joint(JointKind::Prismatic, segment.contact, normal, (0.0, travel)),
        ),
    }
}
