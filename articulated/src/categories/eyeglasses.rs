//! Eyeglasses: a front frame of two lens rims with lenses, a bridge and hinge lugs; two
//! temples, each revolute about its own hinge from folded behind the lenses to open. The
//! hinges sit at slightly different heights so that the folded temples pass each other.

use pairs::math::{Point3, Real, Vector3};
use rand::Rng as _;

use super::catalog::{Category, TEST};
use crate::mesh::Mesh;
use crate::objects::contact::contact_pads;
use crate::objects::profile::{block, prism, superellipse};
use crate::objects::{ArticulatedObject, Joint, Link};
use crate::seed::Rng;

/// The eyeglasses category.
pub const CATEGORY: Category = Category {
    name: "eyeglasses",
    description: "front frame with two rimmed lenses and a bridge; two temples, each revolute \
                  about its hinge from folded to open",
    splits: TEST,
    build,
};

/// A lens rim around `centre` (in the plane z = 0): boxes along a superellipse.
fn rim(centre: Point3, half: (Real, Real), exponent: Real, width: Real, depth: Real) -> Mesh {
    let line = superellipse(half.0 + 0.5 * width, half.1 + 0.5 * width, exponent, 20);
    Mesh::union((0..line.len()).map(|i| {
        let ([ax, ay], [bx, by]) = (line[i], line[(i + 1) % line.len()]);
        let (a, b) = (centre + Vector3::new(ax, ay, 0.0), centre + Vector3::new(bx, by, 0.0));
        // Overlapping the next box closes the rim's outer corners.
        // A repeated rim point (none is) extends along x.
        let run = pairs::math::unit_or(&(b - a), Vector3::x()) * 0.5 * width;
        Mesh::beam(a - run, b + run, width, depth, Vector3::z())
    }))
}

/// How a temple hangs: its hinge, the height band it folds in, and its size.
struct Temple {
    /// Hinge axis position in x and z.
    hinge: (Real, Real),
    /// Side of the frame: -1 left, +1 right; the folded temple points towards -side.
    side: Real,
    band: (Real, Real),
    length: Real,
    thickness: Real,
    knuckle: Real,
}

impl Temple {
    /// The temple's mesh (folded along x behind the lenses) and its joint.
    fn build(&self, max_open: Real) -> (Mesh, Joint) {
        let (x, z) = self.hinge;
        let (y0, y1) = self.band;
        let (mid, h) = (0.5 * (y0 + y1), y1 - y0);
        let p = |u: Real, v: Real, w: Real| Point3::new(x - self.side * u, mid + v, z + w);
        let t = 0.5 * self.thickness;
        let bar: Vec<Point3> = [(0.0, 0.5 * h), (self.length, 0.3 * h)]
            .iter()
            .flat_map(|&(u, hv)| [p(u, -hv, -t), p(u, hv, -t), p(u, -hv, t), p(u, hv, t)])
            .collect();
        let tip = Mesh::beam(
            p(0.7 * self.length, 0.0, 0.0),
            p(self.length, 0.0, 0.0),
            1.3 * self.thickness,
            0.6 * h,
            Vector3::y(),
        );
        let barrel = Mesh::cylinder(Point3::new(x, y0, z), Point3::new(x, y1, z), self.knuckle, 10);
        // Turning about -side * y swings the free end backwards (-z), past straight back.
        let joint = Joint::hinge(Point3::new(x, mid, z), -self.side * Vector3::y(), max_open);
        (Mesh::union([Mesh::hull(&bar), tip, barrel]), joint)
    }

    /// The frame's lug from the rim's outer edge at `rim_x` back to the hinge, with its own
    /// knuckle stacked on the temple's barrel: above it if `above`, else below.
    fn lug(&self, rim_x: Real, above: bool) -> (Mesh, Mesh) {
        let (x, z) = self.hinge;
        let (y0, y1) = self.band;
        let h = y1 - y0;
        let (k0, k1, plane, axis) = if above {
            (y1, y1 + 0.6 * h, y1, -Vector3::y())
        } else {
            (y0 - 0.6 * h, y0, y0, Vector3::y())
        };
        let ym = 0.5 * (y0.min(k0) + y1.max(k1));
        let span = y1.max(k1) - y0.min(k0);
        let (pad_frame, pad_temple) =
            contact_pads(Point3::new(x, plane, z), axis, 0.8 * self.knuckle);
        // The lug runs straight back from the rim and ends on top of the knuckles.
        let lug = Mesh::union([
            block(
                Point3::new(rim_x, ym - 0.5 * span, 0.0),
                Point3::new(x + self.side * 0.0015, ym + 0.5 * span, z + self.knuckle),
            ),
            Mesh::cylinder(Point3::new(x, k0, z), Point3::new(x, k1, z), self.knuckle, 10),
            pad_frame,
        ]);
        (lug, pad_temple)
    }
}

fn build(rng: &mut Rng) -> ArticulatedObject {
    let a = rng.random_range(0.022..0.029);
    let b = a * rng.random_range(0.6..0.85);
    let exponent = rng.random_range(2.0..4.5);
    let bridge = rng.random_range(0.014..0.022);
    let metal = rng.random_bool(0.5);
    let rim_w =
        if metal { rng.random_range(0.0015..0.0025) } else { rng.random_range(0.003..0.005) };
    let rim_d = if metal { rng.random_range(0.002..0.003) } else { rng.random_range(0.004..0.006) };
    let top_bar = metal && rng.random_bool(0.4);
    let band_h = rng.random_range(0.005..0.008);
    let thickness = rng.random_range(0.0025..0.0035);
    let length = rng.random_range(0.95..1.05);
    let left_above = rng.random_bool(0.5);
    let max_open = [rng.random_range(88.0f32..100.0), rng.random_range(88.0f32..100.0)];
    let cx = 0.5 * bridge + a + rim_w;
    // Temples about as long as the frame is wide: folded, each reaches the other hinge.
    let hinge_x = cx + a + rim_w + 0.003;
    let length = length * 2.0 * hinge_x;
    let mut frame = Vec::new();
    for s in [-1.0, 1.0] {
        let centre = Point3::new(s * cx, 0.0, 0.0);
        frame.push(rim(centre, (a, b), exponent, rim_w, rim_d));
        let lens = superellipse(a + 0.3 * rim_w, b + 0.3 * rim_w, exponent, 20);
        frame.push(prism(&lens, (-0.001, 0.001), |u, v, d| centre + Vector3::new(u, v, d)));
    }
    let reach = (0.5 * bridge + rim_w) / 20f32.to_radians().cos();
    let arch = Point3::new(0.0, 0.3 * b - reach * 20f32.to_radians().sin(), 0.0);
    frame.push(Mesh::arc(
        arch,
        reach,
        0.5 * rim_w.max(0.002),
        (20f32.to_radians(), 160f32.to_radians()),
        6,
    ));
    if top_bar {
        let y = b + 0.3 * rim_w;
        frame.push(Mesh::beam(
            Point3::new(-cx, y, 0.0),
            Point3::new(cx, y, 0.0),
            rim_w,
            rim_w,
            Vector3::z(),
        ));
    }
    // The folded temples lie just behind the rims, one band above the hinge line, one below.
    let z_hinge = -(0.5 * rim_d + 0.65 * thickness + 0.0008);
    let y_hinge = 0.35 * b;
    let upper = (y_hinge + 0.0004, y_hinge + 0.0004 + band_h);
    let lower = (y_hinge - 0.0004 - band_h, y_hinge - 0.0004);
    if metal {
        // Nose pads on short arms, below both temple bands.
        let top = (-0.3 * b).min(lower.0 - 0.6 * band_h - 0.002);
        for s in [-1.0, 1.0] {
            let x = s * (0.5 * bridge + rim_w);
            let pad = Point3::new(x + s * 0.002, top - 0.004, -0.5 * rim_d - 0.005);
            frame.push(Mesh::beam(Point3::new(x, top, 0.0), pad, 0.0012, 0.0012, Vector3::x()));
            frame.push(Mesh::oriented_cuboid(
                &pairs::math::Isometry3::new(pad.coords, Vector3::y() * s * 0.5),
                Vector3::new(0.004, 0.006, 0.0008),
            ));
        }
    }
    let mut links = Vec::new();
    for (k, s) in [-1.0f32, 1.0].into_iter().enumerate() {
        let above = (s < 0.0) == left_above;
        let temple = Temple {
            hinge: (s * hinge_x, z_hinge),
            side: s,
            band: if above { upper } else { lower },
            length,
            thickness,
            knuckle: 0.65 * thickness,
        };
        let (lug, pad) = temple.lug(s * (cx + a + 0.5 * rim_w), above);
        frame.push(lug);
        let (mesh, joint) = temple.build(max_open[k].to_radians());
        let name = if s < 0.0 { "left temple" } else { "right temple" };
        links.push((Link { name: name.into(), mesh: Mesh::union([mesh, pad]) }, joint));
    }
    let mut object = ArticulatedObject::new(
        "eyeglasses",
        Link { name: "frame".into(), mesh: Mesh::union(frame) },
    );
    for (link, joint) in links {
        object.attach(0, link, joint);
    }
    object
}
