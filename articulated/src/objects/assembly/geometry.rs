//! Axis-aligned geometry of an assembly at rest: the six faces of a box and boxes.

use pairs::math::{Point3, Real, Vector3};

/// Interiors closer than this (object units) do not count as overlapping.
pub(super) const EPS: Real = 1e-4;

/// One of the six axis-aligned faces of a segment.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Face {
    /// Coordinate axis of the face's normal.
    pub axis: usize,
    /// Whether the normal points along the axis rather than against it.
    pub positive: bool,
}

impl Face {
    /// Face `index` of 0..6: +x, -x, +y, -y, +z, -z.
    pub fn from_index(index: usize) -> Self {
        Self { axis: index / 2, positive: index.is_multiple_of(2) }
    }

    /// This face's bit in a set of faces.
    pub fn bit(self) -> u8 {
        1 << (2 * self.axis + usize::from(!self.positive))
    }

    /// +1 or -1.
    pub fn sign(self) -> Real {
        if self.positive {
            1.0
        } else {
            -1.0
        }
    }

    /// The outward unit normal.
    pub fn normal(self) -> Vector3 {
        unit(self.axis) * self.sign()
    }

    /// The two coordinate axes in the face's plane.
    pub fn plane_axes(self) -> [usize; 2] {
        [(self.axis + 1) % 3, (self.axis + 2) % 3]
    }
}

/// The unit vector along coordinate `axis`.
pub(super) fn unit(axis: usize) -> Vector3 {
    Vector3::ith(axis, 1.0)
}

/// An axis-aligned box at rest: a segment, a sleeve wall, or the room a segment keeps free.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Block {
    /// Lowest corner.
    pub min: Point3,
    /// Highest corner.
    pub max: Point3,
}

impl Block {
    /// The box spanning two opposite corners given in any order.
    pub fn spanning(a: Point3, b: Point3) -> Self {
        Self { min: a.inf(&b), max: a.sup(&b) }
    }

    /// Centre point.
    pub fn centre(&self) -> Point3 {
        nalgebra::center(&self.min, &self.max)
    }

    /// Half extents.
    pub fn half(&self) -> Vector3 {
        (self.max - self.min) * 0.5
    }

    /// Surface area.
    pub fn area(&self) -> Real {
        let d = self.max - self.min;
        2.0 * (d.x * d.y + d.y * d.z + d.z * d.x)
    }

    /// The smallest box holding both.
    pub fn union(&self, other: &Block) -> Block {
        Block { min: self.min.inf(&other.min), max: self.max.sup(&other.max) }
    }

    /// Whether the interiors overlap by more than `EPS` along every axis.
    pub fn overlaps(&self, other: &Block) -> bool {
        (0..3).all(|k| self.min[k].max(other.min[k]) + EPS < self.max[k].min(other.max[k]))
    }

    /// The lowest and highest value of `face.normal() . x` over the box.
    pub fn span(&self, face: Face) -> (Real, Real) {
        let (lo, hi) = (self.min[face.axis], self.max[face.axis]);
        if face.positive {
            (lo, hi)
        } else {
            (-hi, -lo)
        }
    }
}
