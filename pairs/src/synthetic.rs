//! Small hand-built pairs with exact ground truth, for tests, doctests and examples of every
//! crate (a two-part hinge whose answer is known in closed form).

use crate::cloud::Cloud;
use crate::ground_truth::GroundTruth;
use crate::joints::{JointKind, JointTruth};
use crate::math::{Isometry3, Point3, Real, Vector3};
use crate::pair::{Pair, PairInput, PairKind, Provenance};
use crate::parts::PartId;
use crate::set::{
    Set, SetInput, SetJoint, SetProvenance, SetTruth, View, ViewKind, ViewProvenance,
};
use crate::transform::{rotation_about, Similarity};

/// A two-part "book": two unit squares sampled on an `side x side` grid each, hinged along
/// the line x = 1 (axis y); in Q the second square is turned by `angle` radians. Q holds the
/// same surface samples as P, in the same order, so `corr_index[i] == i`.
pub fn hinge_pair(id: &str, side: usize, angle: Real) -> Pair {
    let step = 1.0 / side.max(2).saturating_sub(1) as Real;
    let square = |part: u8| -> Vec<Point3> {
        let mut points = Vec::with_capacity(side * side);
        for i in 0..side {
            for j in 0..side {
                let (u, v) = (i as Real * step, j as Real * step);
                // Part 1 starts just past the hinge so that no point sits on both parts.
                let x = if part == 0 { u * 0.98 } else { 1.0 + 0.02 + u * 0.98 };
                points.push(Point3::new(x, v, 0.1 * u * v));
            }
        }
        points
    };
    let pivot = Point3::new(1.0, 0.0, 0.0);
    two_part_pair(id, "hinge", &square(0), &square(1), pivot, Vector3::y(), angle)
}

/// A two-part pair with exact ground truth: part 0 (`base`) stays, part 1 (`moving`) turns
/// by `angle` radians about `axis` (a zero axis reads as z) through `pivot`, in object
/// units; Q holds the same samples as P in the same order (`corr_index[i] == i`), and each
/// cloud is normalised on its own. The pair's category is `category`.
///
/// # Panics
/// If the points do not span a box (all equal), which no test shape does.
pub fn two_part_pair(
    id: &str,
    category: &str,
    base: &[Point3],
    moving: &[Point3],
    pivot: Point3,
    axis: Vector3,
    angle: Real,
) -> Pair {
    let hinge = rotation_about(&pivot, &axis, angle);
    let axis = crate::math::unit_or(&axis, Vector3::z());
    let parts: Vec<PartId> = [(0, base.len()), (1, moving.len())]
        .into_iter()
        .flat_map(|(part, n)| std::iter::repeat_n(part, n))
        .collect();
    let motions_obj = [Isometry3::identity(), hinge];
    let object_p: Vec<Point3> = base.iter().chain(moving).copied().collect();
    let object_q: Vec<Point3> =
        object_p.iter().zip(&parts).map(|(x, &k)| motions_obj[usize::from(k)] * x).collect();
    let p = Cloud::normalise(&object_p).expect("the parts span a box");
    let q = Cloud::normalise(&object_q).expect("the parts span a box");
    let motions: Vec<Similarity> = motions_obj
        .iter()
        .map(|m| Similarity::between_normalised(m, &p.normalisation, &q.normalisation))
        .collect();
    let flow =
        p.points.iter().zip(&parts).map(|(x, &k)| motions[usize::from(k)].apply(x) - x).collect();
    let n = object_p.len();
    let joint = JointTruth {
        part: 1,
        kind: JointKind::Revolute,
        axis_p: axis,
        pivot_p: p.normalisation.apply(&pivot),
        axis_q: axis,
        pivot_q: q.normalisation.apply(&pivot),
        value_p: 0.0,
        value_q: angle,
    };
    let truth = GroundTruth {
        part_p: parts.clone(),
        part_q: parts,
        motions,
        flow: Some(flow),
        corr_mask: vec![true; n],
        corr_index: (0..n as i32).collect(),
        joints: vec![joint],
    };
    let provenance = Provenance {
        category: category.into(),
        object_id: 0,
        articulation_p: 0,
        articulation_q: 1,
        seed: 0,
        generator_version: env!("CARGO_PKG_VERSION").into(),
        ..Default::default()
    };
    Pair::new(PairInput { id: id.into(), kind: PairKind::Sf2f, p, q }, truth, provenance)
        .expect("the two-part pair satisfies every invariant by construction")
}

/// The cross-instance (XF2F) rendition of `pair`: Q's cloud stretched by `stretch` along x
/// before normalisation stands for a second object of the category, so the record keeps the
/// part ids, motions and joints, and has no flow and no point correspondences.
///
/// # Panics
/// If the stretched cloud does not span a box, which no test shape does.
pub fn cross_instance(pair: Pair, stretch: Real) -> Pair {
    let (mut input, mut truth, mut provenance) = pair.into_parts();
    let object_q: Vec<Point3> = input
        .q
        .points
        .iter()
        .map(|x| {
            let x = input.q.normalisation.invert(x);
            Point3::new(x.x * stretch, x.y, x.z)
        })
        .collect();
    input.q = Cloud::normalise(&object_q).expect("the stretched cloud spans a box");
    input.kind = PairKind::Xf2f;
    let n = input.p.len();
    truth.flow = None;
    truth.corr_mask = vec![false; n];
    truth.corr_index = vec![-1; n];
    provenance.seed_q = Some(provenance.seed + 1);
    Pair::new(input, truth, provenance).expect("a cross-instance pair without flow is valid")
}

/// A set of the [`hinge_pair`] "book" in `angles.len()` states: view k turns the second
/// square by `angles[k]` radians about the hinge. Every view is a full shape holding the
/// same samples in the same order, normalised on its own; set part 1 is the moving square
/// (at least two angles must differ). Pairs of views with equal angles have one part.
///
/// # Panics
/// With fewer than two angles, or all angles equal.
pub fn hinge_set(id: &str, side: usize, angles: &[Real]) -> Set {
    let pair = hinge_pair(id, side, 0.0);
    let (input, truth, _) = pair.into_parts();
    let object: Vec<Point3> =
        input.p.points.iter().map(|x| input.p.normalisation.invert(x)).collect();
    let parts = truth.part_p;
    let (pivot, axis) = (Point3::new(1.0, 0.0, 0.0), Vector3::y());
    let posed = |angle: Real| -> Vec<Point3> {
        let hinge = rotation_about(&pivot, &axis, angle);
        object.iter().zip(&parts).map(|(x, &k)| if k == 0 { *x } else { hinge * x }).collect()
    };
    let views: Vec<View> = angles
        .iter()
        .map(|&a| View {
            kind: ViewKind::Full,
            cloud: Cloud::normalise(&posed(a)).expect("the parts span a box"),
        })
        .collect();
    let norm0 = views[0].cloud.normalisation;
    let motions: Vec<Vec<Similarity>> = views
        .iter()
        .zip(angles)
        .map(|(v, &a)| {
            [Isometry3::identity(), rotation_about(&pivot, &axis, a - angles[0])]
                .iter()
                .map(|m| Similarity::between_normalised(m, &norm0, &v.cloud.normalisation))
                .collect()
        })
        .collect();
    let flows = motions
        .iter()
        .map(|m| {
            views[0]
                .cloud
                .points
                .iter()
                .zip(&parts)
                .map(|(x, &k)| m[usize::from(k)].apply(x) - x)
                .collect()
        })
        .collect();
    let k = angles.len();
    let n = parts.len();
    let pair_parts = angles
        .iter()
        .map(|a| angles.iter().map(|b| if a == b { vec![0, 0] } else { vec![0, 1] }).collect())
        .collect::<Vec<Vec<Vec<PartId>>>>();
    let mut pair_parts = pair_parts;
    for (i, row) in pair_parts.iter_mut().enumerate() {
        row[i] = vec![0, 1];
    }
    let joint = SetJoint {
        name: "hinge".into(),
        part: 1,
        parent: 0,
        kind: JointKind::Revolute,
        axis: vec![axis; k],
        pivot: views.iter().map(|v| v.cloud.normalisation.apply(&pivot)).collect(),
        value: angles.to_vec(),
    };
    let truth = SetTruth {
        parts: vec![parts; k],
        motions,
        flows,
        presence: vec![vec![vec![true; n]; k]; k],
        pair_parts,
        joints: vec![joint],
    };
    let provenance = SetProvenance {
        category: "hinge".into(),
        generator_version: env!("CARGO_PKG_VERSION").into(),
        views: angles
            .iter()
            .enumerate()
            .map(|(i, &a)| ViewProvenance {
                articulation: i as u32,
                joints: [("hinge".to_string(), a)].into(),
                pose: None,
            })
            .collect(),
        ..Default::default()
    };
    Set::new(SetInput { id: id.into(), views }, truth, provenance, vec![None; k])
        .expect("the hinge set satisfies every invariant by construction")
}
