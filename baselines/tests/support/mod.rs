//! Test pairs shared by the integration tests: the synthetic hinge with an exact, a noisy
//! or a corrupted flow, a planted two-part "lamp" with distinctive geometry, degenerate
//! inputs with the error each must give, and checks of predictions and errors.

#![allow(dead_code)]

use baselines::descriptors::FpfhError;
use baselines::geometry::InputError;
use baselines::jlinkage::JLinkageError;
use baselines::ransac::SeqRansacError;
use baselines::registration::{EdError, IcpError, NearestError, NrrError};
use baselines::spectral::SpectralError;
use pairs::math::{Point3, Real, Vector3};
use pairs::metrics::{epe, matched_iou};
use pairs::synthetic::hinge_pair;
use pairs::transform::rotation_error_deg;
use pairs::{MethodError, Pair, PairInput, Prediction};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The two-part hinge used by the tests: 12 x 12 grid per part (288 points), the second
/// part turned by 0.8 rad.
pub fn hinge() -> Pair {
    hinge_pair("hinge", 12, 0.8)
}

/// Points on the surface of the axis-aligned box `lo..hi`: the boundary nodes of a grid of
/// spacing about `step`.
pub fn box_surface(lo: Point3, hi: Point3, step: Real) -> Vec<Point3> {
    let cells = |a: Real, b: Real| (((b - a) / step).round() as usize).max(1);
    let n = [cells(lo.x, hi.x), cells(lo.y, hi.y), cells(lo.z, hi.z)];
    let at = |axis: usize, i: usize| lo[axis] + (hi[axis] - lo[axis]) * i as Real / n[axis] as Real;
    let mut points = Vec::new();
    for i in 0..=n[0] {
        for j in 0..=n[1] {
            for k in 0..=n[2] {
                if i == 0 || i == n[0] || j == 0 || j == n[1] || k == 0 || k == n[2] {
                    points.push(Point3::new(at(0, i), at(1, j), at(2, k)));
                }
            }
        }
    }
    points
}

/// A planted articulated "desk lamp" (800 points): a 1 x 0.6 x 0.3 box base with an upright
/// 0.2 x 0.2 x 0.86 arm standing off-centre on it, the arm turned by `angle` about `axis`
/// through the foot of the arm. Unlike the hinge's two flat, nearly interchangeable squares,
/// nothing in this shape is symmetric: edges and corners give descriptors to match and
/// closest points only one way to fit.
pub fn lamp(axis: Vector3, angle: Real) -> Pair {
    let base = box_surface(Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.6, 0.3), 0.06);
    let arm = box_surface(Point3::new(0.75, 0.2, 0.34), Point3::new(0.95, 0.4, 1.2), 0.06);
    let pivot = Point3::new(0.85, 0.3, 0.34);
    pairs::synthetic::two_part_pair("lamp", "lamp", &base, &arm, pivot, axis, angle)
}

/// EPE of a flow method's prediction against the pair's true flow.
pub fn epe_to_truth(pair: &Pair, prediction: &Prediction) -> f64 {
    let flow = prediction.flow.as_ref().expect("a flow method reports its flow");
    epe(flow, pair.truth().flow.as_deref().expect("a flow"))
        .expect("one finite vector per point of P")
}

/// A standard normal sample (Box-Muller), so the tests need no distribution crate.
pub fn gaussian(rng: &mut ChaCha8Rng) -> Real {
    let (u, v): (Real, Real) = (rng.random_range(1e-7..1.0), rng.random());
    (-2.0 * u.ln()).sqrt() * (std::f32::consts::TAU * v).cos()
}

/// The ground-truth flow corrupted as the robustness test states it:
/// - noise: every component gets Gaussian noise with sigma `noise` times the mean norm of
///   the ground-truth flow (noise = 0.05 is "5% flow noise");
/// - outliers: a fraction `outliers` of the points (chosen at random) get a flow drawn
///   uniformly from the cube [-0.5, 0.5]^3 (half the cloud's diagonal) instead.
pub fn corrupt_flow(flow: &[Vector3], noise: Real, outliers: Real, seed: u64) -> Vec<Vector3> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mean = flow.iter().map(|f| f.norm()).sum::<Real>() / flow.len() as Real;
    let sigma = noise * mean;
    flow.iter()
        .map(|f| {
            if rng.random::<Real>() < outliers {
                Vector3::new(rng.random(), rng.random(), rng.random()) - Vector3::repeat(0.5)
            } else {
                f + Vector3::new(gaussian(&mut rng), gaussian(&mut rng), gaussian(&mut rng)) * sigma
            }
        })
        .collect()
}

/// Smallest IoU over the ground-truth parts after Hungarian matching.
pub fn min_iou(prediction: &Prediction, truth: &[u8]) -> f64 {
    let matching = matched_iou(&prediction.segments_p, truth).expect("lengths agree");
    matching.iou.iter().copied().fold(1.0, f64::min)
}

/// Largest rotation error (degrees) between each ground-truth part's motion and its matched
/// segment's motion.
pub fn max_rotation_error(prediction: &Prediction, pair: &Pair) -> Real {
    let truth = pair.truth();
    let matching = matched_iou(&prediction.segments_p, &truth.part_p).expect("lengths agree");
    matching
        .segment
        .iter()
        .zip(&truth.motions)
        .map(|(segment, gt)| {
            let segment = segment.expect("every part is matched") as usize;
            rotation_error_deg(&prediction.motions[segment].rotation, &gt.rotation)
        })
        .fold(0.0, Real::max)
}

/// The input error that a method (which sees P and Q only, `with_flow` false) or a segmenter
/// (`with_flow` true) must give on the degenerate case `case` of [`degenerate_inputs`];
/// `None` where it must predict.
pub fn expected_input_error(case: &str, with_flow: bool) -> Option<InputError> {
    let points = base_input().p.len();
    match case {
        "collinear" | "zero flow" | "three points" | "repeated point" => None,
        "two points" => Some(InputError::TooFewPoints { cloud: "P", points: 2 }),
        "empty" => Some(InputError::TooFewPoints { cloud: "P", points: 0 }),
        "short flow" => with_flow.then_some(InputError::FlowLength { flow: 3, points }),
        "nan flow" => with_flow.then_some(InputError::NotFinite { what: "flow", index: 3 }),
        "nan point" => Some(InputError::NotFinite { what: "P", index: 5 }),
        other => panic!("no expectation for degenerate case {other:?}"),
    }
}

/// The baseline's input error inside `error`, whichever baseline's error type wraps it.
pub fn input_error(error: &MethodError) -> Option<&InputError> {
    let source = error.source.as_ref();
    macro_rules! unwrap_input {
        ($($kind:ident),*) => {$(
            if let Some($kind::Input(inner)) = source.downcast_ref::<$kind>() {
                return Some(inner);
            }
        )*};
    }
    unwrap_input!(
        NrrError,
        NearestError,
        IcpError,
        EdError,
        FpfhError,
        SeqRansacError,
        SpectralError,
        JLinkageError
    );
    None
}

/// Checks `result` of `method` on the degenerate `input`: a valid prediction where
/// `expected` is `None`, else exactly that input error, wrapped with the method's name and
/// the pair's id.
pub fn assert_outcome(
    name: &str,
    method: &str,
    input: &PairInput,
    result: Result<Prediction, MethodError>,
    expected: Option<InputError>,
) {
    match (result, expected) {
        (Ok(prediction), None) => assert_valid(name, input, &prediction),
        (Ok(_), Some(expected)) => panic!("{name}: predicted, but {expected:?} was expected"),
        (Err(e), None) => panic!("{name}: must predict, but failed: {e}"),
        (Err(e), Some(expected)) => {
            assert_eq!((e.method.as_str(), e.pair.as_str()), (method, input.id.as_str()), "{name}");
            assert_eq!(input_error(&e), Some(&expected), "{name}: {e}");
            let message = format!("method {method} failed on pair {}: {expected}", input.id);
            assert_eq!(e.to_string(), message, "{name}");
        }
    }
}

/// The hinge input that the degenerate cases start from (32 points).
fn base_input() -> PairInput {
    hinge_pair("degenerate", 4, 0.5).input().clone()
}

/// Degenerate inputs with a flow each: every method must return a valid prediction or the
/// error of [`expected_input_error`] on them, never panic or NaN. Names say which.
pub fn degenerate_inputs() -> Vec<(&'static str, PairInput, Vec<Vector3>)> {
    let base = base_input();
    let with_points = |points: Vec<Point3>, q: Vec<Point3>| {
        let mut input = base.clone();
        input.p.points = points;
        input.q.points = q;
        input
    };
    let line: Vec<Point3> =
        (0..40).map(|i| Point3::new(i as Real / 40.0 - 0.5, 0.0, 0.0)).collect();
    let line_q: Vec<Point3> = line.iter().map(|p| Point3::new(p.y, p.x, 0.0)).collect();
    let line_flow: Vec<Vector3> = line.iter().zip(&line_q).map(|(a, b)| b - a).collect();
    let three =
        vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.5, 0.0, 0.0), Point3::new(0.0, 0.5, 0.0)];
    let same = vec![Point3::new(0.1, 0.1, 0.1); 30];
    let mut nan_flow = vec![Vector3::zeros(); base.p.len()];
    nan_flow[3].x = Real::NAN;
    let mut nan_points = base.clone();
    nan_points.p.points[5].z = Real::NAN;
    vec![
        ("collinear", with_points(line.clone(), line_q), line_flow),
        ("zero flow", base.clone(), vec![Vector3::zeros(); base.p.len()]),
        ("three points", with_points(three.clone(), three), vec![Vector3::new(0.1, 0.0, 0.0); 3]),
        ("repeated point", with_points(same.clone(), same), vec![Vector3::zeros(); 30]),
        (
            "two points",
            with_points(line[..2].to_vec(), line[..2].to_vec()),
            vec![Vector3::zeros(); 2],
        ),
        ("empty", with_points(Vec::new(), Vec::new()), Vec::new()),
        ("short flow", base.clone(), vec![Vector3::zeros(); 3]),
        ("nan flow", base.clone(), nan_flow),
        ("nan point", nan_points, vec![Vector3::zeros(); base.p.len()]),
    ]
}

/// Checks a prediction is complete and finite for `input`.
pub fn assert_valid(name: &str, input: &PairInput, prediction: &Prediction) {
    assert_eq!(prediction.segments_p.len(), input.p.len(), "{name}: segments_p");
    assert_eq!(prediction.segments_q.len(), input.q.len(), "{name}: segments_q");
    let segments = prediction.segments_p.iter().max().map_or(0, |&m| m as usize + 1);
    assert_eq!(prediction.motions.len(), segments, "{name}: one motion per segment");
    assert!(prediction.motions.iter().all(|m| m.is_finite()), "{name}: motions finite");
    if let Some(flow) = &prediction.flow {
        assert_eq!(flow.len(), input.p.len(), "{name}: flow length");
        assert!(flow.iter().all(|f| f.iter().all(|c| c.is_finite())), "{name}: flow finite");
    }
}
