//! Joints of a render scored in every family's convention (docs/METRICS.md, "Joints of a
//! render"): the same predicted and true joints ([`crate::renders`], the layout's world
//! frame) read as this project, PARIS, DigitalTwinArt and ArtGS would report them.
//!
//! | variant | matching of several joints | axis angle | axis line distance (revolute) | state |
//! |---|---|---|---|---|
//! | `ours` | same type only, least summed error | `min(θ, 180° − θ)` | skew-line distance over the object's diagonal | `abs(abs(Δθ̂) − abs(Δθ))` degrees, `abs(abs(Δd̂) − abs(Δd))` over the diagonal; none across types |
//! | `paris` | any, least summed error | [`axis_angle_deg`] PARIS | [`axis_distance`] PARIS (0 when exactly parallel) | geodesic angle of `R̂ Rᵀ`, `‖t̂ − t‖` |
//! | `dta` | any, least summed error | [`axis_angle_deg`] DigitalTwinArt | [`axis_distance`] DigitalTwinArt (× 10) | geodesic angle, `‖t̂ − t‖` |
//! | `artgs` | same type only, least summed error (`utils/metrics.py`) | as `dta` | as `dta` | as `dta` |
//!
//! `R̂` and `t̂` are the predicted joint's motion (identity rotation for a prismatic joint,
//! zero translation for a revolute one), so a wrong type still gets a state error in the
//! image-based conventions, as theirs do. "Least summed error" is ArtGS's rule (the sum of
//! angle, distance and state of the matched joints; DigitalTwinArt prints every
//! permutation); every assignment of true joints to distinct predicted joints (or none)
//! that matches the most true joints is tried. Distances are in the layout's world units.

use nalgebra::{Matrix3, Rotation3, Vector3};

use super::conventions::{axis_angle_deg, axis_distance, rotation_state_deg, translation_state};
use super::conventions::{AxisLine, JointConvention};
use crate::joints::JointKind;
use crate::renders::RenderJoint;

/// Whose reading of the joint errors.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Variant {
    /// This project's (Ditto-like; scale-free distances).
    Ours,
    /// PARIS's.
    Paris,
    /// DigitalTwinArt's.
    Dta,
    /// ArtGS's.
    Artgs,
}

impl Variant {
    /// Every variant, in board order.
    pub const ALL: [Variant; 4] = [Variant::Ours, Variant::Paris, Variant::Dta, Variant::Artgs];

    /// The name on the board.
    pub fn as_str(self) -> &'static str {
        match self {
            Variant::Ours => "ours",
            Variant::Paris => "paris",
            Variant::Dta => "dta",
            Variant::Artgs => "artgs",
        }
    }

    fn same_type_only(self) -> bool {
        matches!(self, Variant::Ours | Variant::Artgs)
    }
}

/// One true joint's errors under a variant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointError {
    /// The true joint's type.
    pub truth: JointKind,
    /// Whether the matched prediction has its type.
    pub type_correct: bool,
    /// Axis angle, degrees.
    pub angle_deg: f64,
    /// Axis line distance (revolute truth only).
    pub distance: Option<f64>,
    /// State error: degrees (revolute truth) or distance units (prismatic); `None` for
    /// `ours` across types.
    pub state: Option<f64>,
}

impl JointError {
    fn cost(&self) -> f64 {
        self.angle_deg + self.distance.unwrap_or(0.0) + self.state.unwrap_or(0.0)
    }
}

fn vector(a: &[f64; 3]) -> Vector3<f64> {
    Vector3::new(a[0], a[1], a[2])
}

/// The rotation and translation a joint applies from start to end (about an axis through
/// its pivot; the translation is of the pivot's frame, `(I - R) o` for a revolute joint).
fn motion(j: &RenderJoint) -> (Matrix3<f64>, Vector3<f64>) {
    let axis = vector(&j.axis);
    let axis = axis / axis.norm().max(f64::MIN_POSITIVE);
    match j.kind {
        JointKind::Revolute => (*Rotation3::new(axis * j.state).matrix(), Vector3::zeros()),
        JointKind::Prismatic => (Matrix3::identity(), axis * j.state),
    }
}

/// The errors of one true joint against one predicted joint; `diagonal` is the object's
/// bounding-box diagonal in world units (for `ours`).
pub fn joint_error(
    variant: Variant,
    predicted: &RenderJoint,
    truth: &RenderJoint,
    diagonal: f64,
) -> JointError {
    let (pa, ta) = (vector(&predicted.axis), vector(&truth.axis));
    let line = |j: &RenderJoint| AxisLine { origin: vector(&j.pivot), direction: vector(&j.axis) };
    let type_correct = predicted.kind == truth.kind;
    let revolute = truth.kind == JointKind::Revolute;
    let convention = match variant {
        Variant::Paris => JointConvention::Paris,
        _ => JointConvention::DigitalTwinArt,
    };
    let angle_deg = axis_angle_deg(convention, &pa, &ta);
    let (distance, state) = match variant {
        Variant::Ours => {
            let scale = diagonal.max(1e-12);
            let distance = revolute.then(|| {
                let (a, b) = (line(predicted), line(truth));
                super::joints::line_to_line_distance(
                    &a.origin.cast::<f32>().into(),
                    &a.direction.cast::<f32>(),
                    &b.origin.cast::<f32>().into(),
                    &b.direction.cast::<f32>(),
                ) / scale
            });
            let state = type_correct.then(|| {
                let gap = (predicted.state.abs() - truth.state.abs()).abs();
                if revolute {
                    gap.to_degrees()
                } else {
                    gap / scale
                }
            });
            (distance, state)
        }
        _ => {
            let distance =
                revolute.then(|| axis_distance(convention, &line(predicted), &line(truth)));
            let ((pr, pt), (tr, tt)) = (motion(predicted), motion(truth));
            let state =
                if revolute { rotation_state_deg(&pr, &tr) } else { translation_state(&pt, &tt) };
            (distance, Some(state))
        }
    };
    JointError { truth: truth.kind, type_correct, angle_deg, distance, state }
}

/// Every true joint's errors under `variant`, `None` for a joint no prediction is matched
/// to: the assignment of true joints to distinct predictions that matches the most joints
/// (of the same type only, for `ours` and `artgs`), then has the least summed error.
pub fn score_object(
    variant: Variant,
    predicted: &[RenderJoint],
    truth: &[RenderJoint],
    diagonal: f64,
) -> Vec<Option<JointError>> {
    let table: Vec<Vec<Option<JointError>>> = truth
        .iter()
        .map(|t| {
            predicted
                .iter()
                .map(|p| {
                    let allowed = !variant.same_type_only() || p.kind == t.kind;
                    allowed.then(|| joint_error(variant, p, t, diagonal))
                })
                .collect()
        })
        .collect();
    let mut best: Option<(usize, f64, Vec<Option<usize>>)> = None;
    let mut current = Vec::with_capacity(truth.len());
    let mut used = vec![false; predicted.len()];
    search(&table, &mut current, &mut used, &mut best);
    let assignment = best.map(|b| b.2).unwrap_or_default();
    assignment.iter().enumerate().map(|(t, p)| p.and_then(|p| table[t][p])).collect()
}

/// Depth-first over assignments of true joint `current.len()` onwards.
fn search(
    table: &[Vec<Option<JointError>>],
    current: &mut Vec<Option<usize>>,
    used: &mut [bool],
    best: &mut Option<(usize, f64, Vec<Option<usize>>)>,
) {
    let t = current.len();
    if t == table.len() {
        let matched = current.iter().filter(|p| p.is_some()).count();
        let cost: f64 = current
            .iter()
            .enumerate()
            .filter_map(|(t, p)| p.and_then(|p| table[t][p]).map(|e| e.cost()))
            .sum();
        let better = match best {
            None => true,
            Some((m, c, _)) => matched > *m || (matched == *m && cost < *c),
        };
        if better {
            *best = Some((matched, cost, current.clone()));
        }
        return;
    }
    for p in 0..used.len() {
        if !used[p] && table[t][p].is_some() {
            used[p] = true;
            current.push(Some(p));
            search(table, current, used, best);
            current.pop();
            used[p] = false;
        }
    }
    current.push(None);
    search(table, current, used, best);
    current.pop();
}

/// Joint errors summed over objects, for the board: means are over the joints that have
/// the value (distances over revolute joints, states per type).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct VariantScores {
    /// True joints seen.
    pub joints: usize,
    /// Of those, matched to a prediction.
    pub matched: usize,
    /// Of those, with the right type.
    pub type_correct: usize,
    /// Sum of axis angles (matched joints).
    pub angle_sum: f64,
    /// Sum and count of axis line distances.
    pub distance_sum: f64,
    #[allow(missing_docs)]
    pub distances: usize,
    /// Sum and count of revolute state errors, degrees.
    pub revolute_state_sum: f64,
    #[allow(missing_docs)]
    pub revolute_states: usize,
    /// Sum and count of prismatic state errors.
    pub prismatic_state_sum: f64,
    #[allow(missing_docs)]
    pub prismatic_states: usize,
}

impl VariantScores {
    /// Adds one object's errors.
    pub fn add(&mut self, errors: &[Option<JointError>]) {
        for e in errors {
            self.joints += 1;
            let Some(e) = e else { continue };
            self.matched += 1;
            self.type_correct += usize::from(e.type_correct);
            self.angle_sum += e.angle_deg;
            if let Some(d) = e.distance {
                self.distance_sum += d;
                self.distances += 1;
            }
            match (e.truth, e.state) {
                (JointKind::Revolute, Some(s)) => {
                    self.revolute_state_sum += s;
                    self.revolute_states += 1;
                }
                (JointKind::Prismatic, Some(s)) => {
                    self.prismatic_state_sum += s;
                    self.prismatic_states += 1;
                }
                (_, None) => {}
            }
        }
    }

    fn mean(sum: f64, n: usize) -> f64 {
        if n == 0 {
            f64::NAN
        } else {
            sum / n as f64
        }
    }

    /// Fraction of true joints matched with the right type.
    pub fn type_accuracy(&self) -> f64 {
        Self::mean(self.type_correct as f64, self.joints)
    }
    /// Mean axis angle, degrees.
    pub fn angle(&self) -> f64 {
        Self::mean(self.angle_sum, self.matched)
    }
    /// Mean axis line distance.
    pub fn distance(&self) -> f64 {
        Self::mean(self.distance_sum, self.distances)
    }
    /// Mean revolute state error, degrees.
    pub fn revolute_state(&self) -> f64 {
        Self::mean(self.revolute_state_sum, self.revolute_states)
    }
    /// Mean prismatic state error.
    pub fn prismatic_state(&self) -> f64 {
        Self::mean(self.prismatic_state_sum, self.prismatic_states)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hinge(pivot: [f64; 3], state: f64) -> RenderJoint {
        RenderJoint { kind: JointKind::Revolute, axis: [0.0, 1.0, 0.0], pivot, state }
    }

    #[test]
    fn hand_computed_errors_in_each_variant() {
        // Parallel axes 0.5 apart, 30 degrees too far.
        let truth = hinge([0.0, 0.0, 0.0], 0.5);
        let predicted = hinge([0.3, 0.0, 0.4], 0.5 + 30f64.to_radians());
        let ours = joint_error(Variant::Ours, &predicted, &truth, 2.0);
        assert_eq!(ours.angle_deg, 0.0);
        assert!((ours.distance.expect("revolute") - 0.25).abs() < 1e-6, "0.5 over a diagonal of 2");
        assert!((ours.state.expect("same type") - 30.0).abs() < 1e-9);
        let paris = joint_error(Variant::Paris, &predicted, &truth, 2.0);
        assert_eq!(paris.distance, Some(0.0), "PARIS: parallel axes are 0 apart");
        assert!((paris.state.expect("geodesic") - 30.0).abs() < 1e-6);
        let dta = joint_error(Variant::Dta, &predicted, &truth, 2.0);
        assert!((dta.distance.expect("revolute") - 5.0).abs() < 1e-9, "0.5 x 10");
        // A flipped axis with a flipped angle is the same joint in every variant.
        let flipped = RenderJoint { axis: [0.0, -1.0, 0.0], state: -0.5, ..truth.clone() };
        for v in Variant::ALL {
            let e = joint_error(v, &flipped, &truth, 2.0);
            assert!(e.angle_deg < 1e-6 && e.state.expect("same type") < 1e-4, "{v:?}: {e:?}");
        }
        // A slide guessed as a hinge: no state for ours, its translation missed in the others.
        let slide = RenderJoint {
            kind: JointKind::Prismatic,
            axis: [1.0, 0.0, 0.0],
            pivot: [0.0; 3],
            state: 0.2,
        };
        let wrong = RenderJoint { kind: JointKind::Revolute, ..slide.clone() };
        assert_eq!(joint_error(Variant::Ours, &wrong, &slide, 1.0).state, None);
        let dta = joint_error(Variant::Dta, &wrong, &slide, 1.0);
        assert!(!dta.type_correct && (dta.state.expect("always") - 0.2).abs() < 1e-12);
    }

    #[test]
    fn matching_pairs_each_truth_with_its_nearest_prediction() {
        let door = hinge([0.0, 0.0, 0.0], 1.0);
        let drawer = RenderJoint {
            kind: JointKind::Prismatic,
            axis: [0.0, 0.0, 1.0],
            pivot: [0.0; 3],
            state: 0.3,
        };
        let truth = [door.clone(), drawer.clone()];
        let predicted = [drawer.clone(), hinge([0.01, 0.0, 0.0], 1.0)];
        for v in Variant::ALL {
            let errors = score_object(v, &predicted, &truth, 1.0);
            assert!(errors.iter().all(|e| e.is_some_and(|e| e.type_correct)), "{v:?}: {errors:?}");
        }
        // One prediction for two joints: one is missed.
        let errors = score_object(Variant::Artgs, &predicted[..1], &truth, 1.0);
        assert!(errors[0].is_none() && errors[1].is_some());
        // The same type only, for ours and ArtGS: a lone hinge guess leaves the drawer missed.
        let errors = score_object(
            Variant::Ours,
            std::slice::from_ref(&door),
            std::slice::from_ref(&drawer),
            1.0,
        );
        assert_eq!(errors, vec![None]);
        assert!(score_object(Variant::Paris, &[door], &[drawer], 1.0)[0].is_some());
        let mut scores = VariantScores::default();
        scores.add(&score_object(Variant::Dta, &predicted[..1], &truth, 1.0));
        assert_eq!((scores.joints, scores.matched, scores.type_correct), (2, 1, 1));
        assert_eq!(scores.prismatic_state(), 0.0);
        assert!(scores.revolute_state().is_nan());
    }
}
