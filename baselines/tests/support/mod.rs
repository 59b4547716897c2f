//! Test pairs shared by the integration tests: the synthetic hinge with an exact, a noisy
//! or a corrupted flow, and degenerate inputs.

#![allow(dead_code)]

use pairs::math::{Point3, Real, Vector3};
use pairs::metrics::matched_iou;
use pairs::synthetic::hinge_pair;
use pairs::transform::rotation_error_deg;
use pairs::{Pair, PairInput, Prediction};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The two-part hinge used by the tests: 12 x 12 grid per part (288 points), the second
/// part turned by 0.8 rad.
pub fn hinge() -> Pair {
    hinge_pair("hinge", 12, 0.8)
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

/// Degenerate inputs with a flow each: every method must return a valid prediction or an
/// error on them, never panic or NaN. Names say which.
pub fn degenerate_inputs() -> Vec<(&'static str, PairInput, Vec<Vector3>)> {
    let base = hinge_pair("degenerate", 4, 0.5).input().clone();
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
