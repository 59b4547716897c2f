//! Arm segments of chains whose hinges are all parallel to x (lamp arms, robot arms,
//! excavator booms): bars with round knuckles at their joints, each in a slab of x.
//!
//! A bar in the inner slab `|x| <= half` and a fork whose two cheeks fill the outer slabs
//! `half <= |x| <= half + cheek` touch through their knuckles' flat faces at every hinge
//! angle and never overlap, so a chain alternating bars and forks stays connected without
//! neighbours passing through each other, however its joints turn.

use pairs::math::{Point3, Real, Vector3};

use crate::mesh::Mesh;

/// Segments of knuckle cylinders: round enough, and few triangles.
const KNUCKLE_SEGMENTS: u32 = 12;

/// The cross-section of an arm chain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    /// Half width (along x) of the single bars.
    pub half: Real,
    /// Thickness (along x) of each cheek of a fork.
    pub cheek: Real,
    /// Depth of bars and cheeks across the plane of motion; knuckles are this wide.
    pub depth: Real,
}

impl Section {
    /// Half width of the chain, cheeks included.
    pub fn outer(&self) -> Real {
        self.half + self.cheek
    }

    /// A single bar from joint centre `a` to joint centre `b` (their x is ignored).
    pub fn bar(&self, a: Point3, b: Point3) -> Mesh {
        slab_bar(a, b, (-self.half, self.half), self.depth)
    }

    /// A fork from `a` to `b`: two cheeks that clasp the single bars.
    pub fn fork(&self, a: Point3, b: Point3) -> Mesh {
        let side = slab_bar(a, b, (self.half, self.outer()), self.depth);
        Mesh::union([side.clone().mirrored_x(), side])
    }

    /// A fork if `forked`, else a single bar.
    pub fn segment(&self, a: Point3, b: Point3, forked: bool) -> Mesh {
        if forked {
            self.fork(a, b)
        } else {
            self.bar(a, b)
        }
    }

    /// A link that starts as a fork round the previous bar at `a` and ends as a bar at `b`,
    /// with a block bridging the two a third of the way along: a forearm or a digger's
    /// stick, clasping one neighbour and clasped by the next.
    pub fn fork_to_bar(&self, a: Point3, b: Point3) -> Mesh {
        let mid = a + (b - a) * 0.35;
        // A zero-length link bridges back along x.
        let back = mid - pairs::math::unit_or(&(b - a), Vector3::x()) * (0.5 * self.depth);
        let bridge = Mesh::beam(back, mid, 0.9 * self.depth, 2.0 * self.outer(), Vector3::x());
        Mesh::union([self.fork(a, mid), bridge, self.bar(mid, b)])
    }
}

/// The unit direction in the yz plane (the plane of motion) `angle` radians from straight
/// up towards the front (+z).
pub fn heading(angle: Real) -> Vector3 {
    Vector3::new(0.0, angle.cos(), angle.sin())
}

/// A bar from `a` to `b` spanning x over `xs`, `depth` across, with a knuckle (a cylinder
/// along x of radius `depth / 2`) round each end.
fn slab_bar(a: Point3, b: Point3, xs: (Real, Real), depth: Real) -> Mesh {
    let at = |p: Point3, x: Real| Point3::new(x, p.y, p.z);
    let mid = 0.5 * (xs.0 + xs.1);
    let knuckle =
        |p: Point3| Mesh::cylinder(at(p, xs.0), at(p, xs.1), 0.5 * depth, KNUCKLE_SEGMENTS);
    Mesh::union([
        Mesh::beam(at(a, mid), at(b, mid), depth, xs.1 - xs.0, Vector3::x()),
        knuckle(a),
        knuckle(b),
    ])
}
