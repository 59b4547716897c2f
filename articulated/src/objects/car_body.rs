//! Car bodies: a cabin between a nose and a tail block, each one convex piece so that little
//! hidden surface lies between them; doors and window frames that lean on the cabin's
//! sides; lids on the end blocks; wheels, lamps and bumpers.

use pairs::math::{Point3, Real, Vector3};

use super::articulated::Joint;
use crate::mesh::Mesh;

/// Thickness of the bonnet and boot lid.
pub const LID: Real = 0.05;
/// Thickness of the door windows' frames and the pillars between them.
const GLASS: Real = 0.04;
/// Thickness of a door's sheet-metal skins.
const SKIN: Real = 0.015;

/// A car's proportions: lengths along z (front is +z), heights along y, x is across.
pub struct CarShape {
    /// Half length.
    pub hl: Real,
    /// Half width.
    pub hw: Real,
    /// Underside, belt line, roof.
    pub ys: [Real; 3],
    /// Door thickness.
    pub t: Real,
    /// How far the cabin's sides lean in at the roof.
    pub tumble: Real,
    /// The cabin along z at the belt line, from the rear window's base to the windscreen's
    /// (the front of the door opening).
    pub base: (Real, Real),
    /// The cabin along z at the roof.
    pub roof: (Real, Real),
}

impl CarShape {
    /// The cabin's side, front and rear at height `y` above the belt line.
    pub fn cabin_at(&self, y: Real) -> (Real, Real, Real) {
        let [_, belt, roof] = self.ys;
        let s = (y - belt) / (roof - belt);
        let lerp = |a: Real, b: Real| a + (b - a) * s;
        (
            self.hw - self.t - self.tumble * s,
            lerp(self.base.1, self.roof.1),
            lerp(self.base.0, self.roof.0),
        )
    }

    /// The nose (`end` = `hl`) or the tail (`end` = `-hl`) block from the cabin's end
    /// `from`, its top at `tops` (at the cabin, at the end), chamfered below the end.
    pub fn end_block(&self, from: Real, end: Real, tops: (Real, Real)) -> Mesh {
        let (hw, bottom) = (self.hw, self.ys[0]);
        let chin = end - 0.25 * end.signum();
        let points = [
            (hw, bottom, from),
            (hw, tops.0, from),
            (hw, bottom, chin),
            (hw - 0.06, bottom + 0.12, end),
            (hw - 0.06, tops.1, end),
        ];
        let all: Vec<Point3> = points
            .iter()
            .flat_map(|&(x, y, z)| [Point3::new(x, y, z), Point3::new(-x, y, z)])
            .collect();
        Mesh::hull(&all)
    }

    /// A lid lying on an end block's top from `from` to `end`, tops as for `end_block`.
    pub fn lid(&self, from: Real, end: Real, tops: (Real, Real)) -> Mesh {
        let hw = self.hw;
        let points = [(hw, tops.0, from), (hw - 0.06, tops.1, end)];
        let all: Vec<Point3> = points
            .iter()
            .flat_map(|&(x, y, z)| {
                [-x, x].map(|x| [Point3::new(x, y, z), Point3::new(x, y - LID, z)])
            })
            .flatten()
            .collect();
        Mesh::hull(&all)
    }

    /// The cabin: upright sides inside the doors below the belt line, leaning in above it,
    /// with windscreen and rear window sloping to the roof.
    pub fn cabin(&self) -> Mesh {
        let [bottom, belt, roof] = self.ys;
        let inner = self.hw - self.t;
        let (side_r, _, _) = self.cabin_at(roof);
        let rows =
            [(inner, bottom, self.base), (inner, belt, self.base), (side_r, roof, self.roof)];
        let all: Vec<Point3> = rows
            .iter()
            .flat_map(|&(x, y, (z0, z1))| {
                [(-x, z0), (x, z0), (-x, z1), (x, z1)].map(|(x, z)| Point3::new(x, y, z))
            })
            .collect();
        Mesh::hull(&all)
    }

    /// A window frame or pillar leaning on the cabin's right side over `z0..z1` (clipped to
    /// the cabin's outline), from the belt line to `top`.
    pub fn on_cabin_side(&self, (z0, z1): (Real, Real), top: Real, margin: Real) -> Mesh {
        let points: Vec<Point3> = [self.ys[1], top]
            .into_iter()
            .flat_map(|y| {
                let (side, front, rear) = self.cabin_at(y);
                let (za, zb) = (z0.max(rear + margin), z1.min(front - margin));
                [(side, za), (side, zb), (side + GLASS, za), (side + GLASS, zb)]
                    .map(|(x, z)| Point3::new(x, y, z))
            })
            .collect();
        Mesh::hull(&points)
    }

    /// A right-hand door over `z0..z1`, hinged at `z1`: below the belt line a hollow shell
    /// as pressed-steel doors are built (an outer skin and a trim panel joined round their
    /// edges, a structural panel between them) with an armrest and a pocket on the trim; a
    /// window frame above it, a handle, and a mirror on front doors. All of it stays within
    /// the door's thickness.
    pub fn door(&self, (z0, z1): (Real, Real), mirror: bool, max_angle: Real) -> (Mesh, Joint) {
        let (hw, t, s) = (self.hw, self.t, SKIN);
        let [bottom, belt, roof] = self.ys;
        let y0 = bottom + 0.02;
        let (trim, xi, xo) = (hw - t + 0.03, hw - t + 0.03 + s, hw - s);
        let inside = |(ya, yb): (Real, Real), (za, zb): (Real, Real)| {
            Mesh::cuboid(Point3::new(hw - t, ya, za), Point3::new(trim, yb, zb))
        };
        let mut door = Mesh::union([
            Mesh::cuboid(Point3::new(xo, y0, z0), Point3::new(hw, belt, z1)),
            Mesh::cuboid(Point3::new(trim, y0, z0), Point3::new(xi, belt, z1)),
            Mesh::cuboid(
                Point3::new(0.5 * (xi + xo) - 0.5 * s, y0 + s, z0 + s),
                Point3::new(0.5 * (xi + xo) + 0.5 * s, belt - s, z1 - s),
            ),
            inside((belt - 0.3, belt - 0.24), (z0 + 0.1, z1 - 0.15)),
            inside((y0 + 0.08, y0 + 0.2), (z0 + 0.15, z1 - 0.25)),
            Mesh::cuboid(Point3::new(xi, y0, z0), Point3::new(xo, y0 + s, z1)),
            Mesh::cuboid(Point3::new(xi, belt - s, z0), Point3::new(xo, belt, z1)),
            Mesh::cuboid(Point3::new(xi, y0 + s, z0), Point3::new(xo, belt - s, z0 + s)),
            Mesh::cuboid(Point3::new(xi, y0 + s, z1 - s), Point3::new(xo, belt - s, z1)),
            self.on_cabin_side((z0 + 0.03, z1 - 0.03), roof - 0.04, 0.02),
            Mesh::cuboid(
                Point3::new(hw, belt - 0.1, z0 + 0.08),
                Point3::new(hw + 0.025, belt - 0.07, z0 + 0.25),
            ),
        ]);
        if mirror {
            door.append(Mesh::cuboid(
                Point3::new(hw, belt, z1 - 0.25),
                Point3::new(hw + 0.16, belt + 0.1, z1 - 0.1),
            ));
        }
        // The rear edge swings out (+x) about the front edge's outer corner.
        let joint = Joint::hinge(Point3::new(hw, belt, z1), -Vector3::y(), max_angle);
        (door, joint)
    }
}

/// Wheels of radius `r` set into the sides of `car` at the two `axles`, lamps and bumpers.
pub fn running_gear(car: &CarShape, r: Real, axles: [Real; 2]) -> Mesh {
    let (hw, hl, bottom) = (car.hw, car.hl, car.ys[0]);
    let mut mesh = Mesh::default();
    for sx in [-1.0, 1.0] {
        for z in axles {
            let at = |x: Real| Point3::new(sx * x, r, z);
            mesh.append(Mesh::cylinder(at(hw - 0.05), at(hw + 0.03), r, 14));
            mesh.append(Mesh::cylinder(at(hw + 0.03), at(hw + 0.045), 0.55 * r, 10));
        }
        let x = sx * (hw - 0.25);
        let lamp = |z: Real, y: Real| {
            Mesh::cuboid(
                Point3::new(x - 0.14, y, z.min(z + 0.015 * z.signum())),
                Point3::new(x + 0.14, y + 0.08, z.max(z + 0.015 * z.signum())),
            )
        };
        mesh.append(lamp(hl, bottom + 0.3));
        mesh.append(lamp(-hl, bottom + 0.33));
    }
    for z in [hl, -hl] {
        let (z0, z1) = (z.min(z + 0.03 * z.signum()), z.max(z + 0.03 * z.signum()));
        mesh.append(Mesh::cuboid(
            Point3::new(-hw + 0.08, bottom + 0.14, z0),
            Point3::new(hw - 0.08, bottom + 0.24, z1),
        ));
    }
    mesh
}
