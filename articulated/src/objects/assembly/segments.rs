//! The segments of a random assembly: a root primitive and boxes, each standing on a
//! rectangle inside one face of its parent, all axis-aligned at rest, so that a segment's
//! contact region is that rectangle and its contact normal the face's.

use pairs::math::{Isometry3, Point3, Real, Translation3, Vector3};

use super::geometry::{unit, Block, Face};
use super::shape::Shape;
use crate::mesh::Mesh;

/// One primitive of the assembly.
#[derive(Debug, Clone)]
pub(super) struct Segment {
    /// Index of the segment it stands on; `None` for the root.
    pub parent: Option<usize>,
    /// Its shape.
    pub shape: Shape,
    /// Its boxes at rest (the root's bounding box for the root).
    pub pieces: Vec<Block>,
    /// The bounding box of its pieces.
    pub block: Block,
    /// The parent's face it stands on; `None` for the root.
    pub face: Option<Face>,
    /// Centre of its footprint on that face (the contact region's centre).
    pub contact: Point3,
    /// Half extents of the footprint along the face's plane axes.
    pub footprint: [Real; 2],
    /// Thickness of the walls of a sleeve around its first piece.
    pub wall: Real,
    /// How deep its first piece sinks into its parent: a sliver of overlap that keeps the
    /// two in contact for convex distance queries, which can report a false gap between a
    /// box hinged on an edge and the face it turns on.
    pub sink: Real,
    /// Its surface area.
    pub area: Real,
    /// Whether it was grown to slide: a shaft in a sleeve under a wider head.
    pub slider: bool,
    /// A slider's longest travel.
    pub travel: Real,
    /// Faces it may not grow children on.
    pub closed: u8,
    /// Faces that already carry a child.
    pub used: u8,
}

impl Segment {
    /// A segment of `shape` made of `pieces` (a root primitive fills its one block), on no
    /// face yet.
    pub fn new(parent: Option<usize>, shape: Shape, pieces: Vec<Block>) -> Self {
        let block = pieces
            .iter()
            .copied()
            .reduce(|a, b| a.union(&b))
            .unwrap_or(Block { min: Point3::origin(), max: Point3::origin() });
        let area = shape.area(&block).unwrap_or_else(|| pieces.iter().map(Block::area).sum());
        Self {
            parent,
            shape,
            block,
            pieces,
            face: None,
            contact: block.centre(),
            footprint: [0.0; 2],
            wall: 0.0,
            sink: 0.0,
            area,
            slider: false,
            travel: 0.0,
            closed: 0,
            used: 0,
        }
    }

    /// Half extents, along `face.plane_axes()`, of the flat rectangle centred on `face` that
    /// children may stand on.
    pub fn face_half(&self, face: Face) -> [Real; 2] {
        self.shape.face_half(&self.block, face)
    }

    /// Centre of `face`.
    pub fn face_centre(&self, face: Face) -> Point3 {
        self.block.centre() + face.normal() * self.block.half()[face.axis]
    }

    /// Its block widened sideways by its sleeve wall: the room it keeps free of every
    /// segment but its parent and children, so that a sleeve always fits around it.
    pub fn room(&self) -> Block {
        let grow = self.face.map_or(Vector3::zeros(), |f| {
            let [a, b] = f.plane_axes();
            (unit(a) + unit(b)) * self.wall
        });
        Block { min: self.block.min - grow, max: self.block.max + grow }
    }

    /// The motion of a slider sliding `fraction` of its travel out of its sleeve.
    pub fn slide(&self, fraction: Real) -> Isometry3 {
        let normal = self.face.map_or(Vector3::zeros(), |f| f.normal());
        Isometry3::from(Translation3::from(normal * (fraction * self.travel)))
    }

    /// The four walls of the sleeve around a slider's shaft, as long as the shaft so that
    /// the head rests on its rim; none for other segments.
    pub fn sleeve_walls(&self) -> Vec<Block> {
        let (Some(face), Some(shaft), true) = (self.face, self.pieces.first(), self.slider) else {
            return Vec::new();
        };
        let (base, top) = shaft.span(face);
        let [ua, ub] = face.plane_axes().map(unit);
        let ([fa, fb], w) = (self.footprint, self.wall);
        let wall = |a0: Real, a1: Real, b0: Real, b1: Real| {
            Block::spanning(
                self.contact + ua * a0 + ub * b0,
                self.contact + ua * a1 + ub * b1 + face.normal() * (top - base),
            )
        };
        vec![
            wall(-fa - w, fa + w, fb, fb + w),
            wall(-fa - w, fa + w, -fb - w, -fb),
            wall(fa, fa + w, -fb, fb),
            wall(-fa - w, -fa, -fb, fb),
        ]
    }

    /// Its boxes as built: the first sunk into the parent by `sink`.
    pub fn bodies(&self) -> Vec<Block> {
        let mut bodies = self.pieces.clone();
        if let (Some(face), Some(first)) = (self.face, bodies.first_mut()) {
            let k = face.axis;
            if face.positive {
                first.min[k] -= self.sink;
            } else {
                first.max[k] += self.sink;
            }
        }
        bodies
    }

    /// Its triangles.
    pub fn mesh(&self) -> Mesh {
        match self.shape.corners(&self.block) {
            Some(corners) => Mesh::hull(&corners),
            None => Mesh::union(self.bodies().iter().map(|p| Mesh::cuboid(p.min, p.max))),
        }
    }

    /// The faces that may still carry a child.
    pub fn free_faces(&self) -> impl Iterator<Item = Face> + '_ {
        (0..6).map(Face::from_index).filter(|f| (self.closed | self.used) & f.bit() == 0)
    }
}
