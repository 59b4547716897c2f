//! Methods on sets of K views: the [`SetMethod`] trait, and [`PairsToSet`], which lifts
//! any pair [`Method`] to sets by a fixed rule (docs/METRICS.md, "Sets").

use crate::method::{Method, MethodError, Prediction};
use crate::pair::PairInput;
use crate::parts::SegmentId;
use crate::set::SetInput;
use crate::transform::Similarity;

/// What a set method returns: one segment id per point of every view, an id naming the
/// same part in every view (the multi-scan scores need that).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SetPrediction {
    /// `segments[k]`: the segment of every point of view k.
    pub segments: Vec<Vec<SegmentId>>,
    /// `motions[k][s]`: segment s's motion from view 0's normalised frame to view k's (the
    /// identity for k = 0); a non-finite motion, a missing entry or an empty `motions[k]`
    /// means none (not scored). Empty when the method estimates no motion.
    pub motions: Vec<Vec<Similarity>>,
}

/// A method that segments K views of one object at once (MultiBodySync's setting).
pub trait SetMethod: Send + Sync {
    /// Short stable name used in leaderboards.
    fn name(&self) -> &str;

    /// Segments every view of one set.
    fn predict_set(&self, input: &SetInput) -> Result<SetPrediction, MethodError>;
}

/// A pair method lifted to sets: it runs on the pairs (view 0, view k), k = 1 .. K-1;
/// view 0 takes the segments the pair (0, 1) gives P; view k takes the segments the pair
/// (0, k) gives Q, each renamed to the view-0 segment it overlaps most on view 0 (the pair's
/// own segments of P against view 0's; ties go to the smaller id), so that the labels are
/// carried from view 0 through each pair's correspondence of segments. A segment of Q with
/// no point in P keeps an id of its own, past every view-0 id. A method that does not
/// segment Q carries view 0's labels along its flow instead (each point of view k takes the
/// segment of the nearest point of view 0 moved by the flow); one with neither is an error.
#[derive(Debug, Clone)]
pub struct PairsToSet<M> {
    method: M,
    name: String,
}

impl<M: Method> PairsToSet<M> {
    /// Lifts `method`; the set row keeps its name.
    pub fn new(method: M) -> Self {
        let name = method.name().to_string();
        Self { method, name }
    }
}

impl<M: Method> SetMethod for PairsToSet<M> {
    fn name(&self) -> &str {
        &self.name
    }

    fn predict_set(&self, input: &SetInput) -> Result<SetPrediction, MethodError> {
        let fail = |reason: String| MethodError::new(&self.name, &input.id, reason);
        let mut predictions = Vec::with_capacity(input.views.len().saturating_sub(1));
        for view in 1..input.views.len() {
            let pair = pair_input(input, 0, view)
                .ok_or_else(|| fail(format!("views 0 and {view} make no pair")))?;
            predictions.push(self.method.predict(&pair)?);
        }
        lift_pairs(input, &predictions).map_err(fail)
    }
}

/// The [`PairsToSet`] rule on predictions already made: `predictions[k - 1]` is the
/// prediction for the pair (view 0, view k) ([`pair_input`]), k = 1 .. K-1. An error says
/// which pair's prediction cannot be lifted (a length that is not its views', or neither
/// Q's segments nor a flow).
pub fn lift_pairs(input: &SetInput, predictions: &[Prediction]) -> Result<SetPrediction, String> {
    let k = input.views.len();
    if predictions.len() + 1 != k || k < 2 {
        return Err(format!("{} pair predictions for a set of {k} views", predictions.len()));
    }
    let mut segments: Vec<Vec<SegmentId>> = Vec::with_capacity(k);
    let mut motions: Vec<Vec<Similarity>> = Vec::with_capacity(k);
    for (view, prediction) in (1..k).zip(predictions) {
        let id = format!("{}-0-{view}", input.id);
        let (p, q) = (&input.views[0].cloud.points, &input.views[view].cloud.points);
        if prediction.segments_p.len() != p.len() {
            return Err(format!(
                "pair {id}: {} segments for P's {} points",
                prediction.segments_p.len(),
                p.len()
            ));
        }
        if view == 1 {
            segments.push(prediction.segments_p.clone());
            let labels = segments[0].iter().copied().max().map_or(0, |m| m as usize + 1);
            motions.push(vec![Similarity::identity(); labels]);
        }
        let base = &segments[0];
        motions.push(carried_motions(&prediction.segments_p, &prediction.motions, base));
        let carried = if prediction.segments_q.len() == q.len() {
            rename(&prediction.segments_p, &prediction.segments_q, base)
        } else if let Some(flow) = prediction.flow.as_ref().filter(|f| f.len() == p.len()) {
            let moved: Vec<_> = p.iter().zip(flow).map(|(x, f)| x + f).collect();
            q.iter()
                .map(|y| {
                    let nearest = moved
                        .iter()
                        .enumerate()
                        .min_by(|a, b| {
                            (a.1 - y).norm_squared().total_cmp(&(b.1 - y).norm_squared())
                        })
                        .map_or(0, |(i, _)| i);
                    base[nearest]
                })
                .collect()
        } else {
            return Err(format!("pair {id}: the method neither segments Q nor gives a flow on P"));
        };
        segments.push(carried);
    }
    if motions[1..].iter().all(Vec::is_empty) {
        motions.clear();
    }
    Ok(SetPrediction { segments, motions })
}

/// The motion of each view-0 label `b` in one pair (0, k): the motion of the pair's
/// P-segment that overlaps `b` most on view 0 (ties to the smaller id); NaN where that
/// segment has none. Empty when the pair's prediction has no motions.
fn carried_motions(
    pair_p: &[SegmentId],
    motions: &[Similarity],
    base: &[SegmentId],
) -> Vec<Similarity> {
    use std::collections::BTreeMap;
    if motions.is_empty() {
        return Vec::new();
    }
    let mut overlap: BTreeMap<SegmentId, BTreeMap<SegmentId, usize>> = BTreeMap::new();
    for (&s, &b) in pair_p.iter().zip(base) {
        *overlap.entry(b).or_default().entry(s).or_default() += 1;
    }
    let none = Similarity {
        rotation: crate::math::Matrix3::from_element(f32::NAN),
        translation: crate::math::Vector3::from_element(f32::NAN),
        scale: f32::NAN,
    };
    let labels = base.iter().copied().max().map_or(0, |m| m as usize + 1);
    (0..labels as SegmentId)
        .map(|b| {
            let segment = overlap
                .get(&b)
                .and_then(|counts| counts.iter().rev().max_by_key(|(_, &c)| c).map(|(&s, _)| s));
            segment.and_then(|s| motions.get(s as usize)).copied().unwrap_or(none)
        })
        .collect()
}

/// Q's segments renamed to the view-0 labels their P-side counterparts overlap most.
fn rename(pair_p: &[SegmentId], pair_q: &[SegmentId], base: &[SegmentId]) -> Vec<SegmentId> {
    use std::collections::BTreeMap;
    let mut overlap: BTreeMap<SegmentId, BTreeMap<SegmentId, usize>> = BTreeMap::new();
    for (&s, &b) in pair_p.iter().zip(base) {
        *overlap.entry(s).or_default().entry(b).or_default() += 1;
    }
    let fresh = base.iter().copied().max().map_or(0, |m| m.saturating_add(1));
    let name = |s: SegmentId| match overlap.get(&s) {
        // The largest overlap; among equal ones the smaller id (max_by_key keeps the last).
        Some(counts) => counts.iter().rev().max_by_key(|(_, &c)| c).map_or(fresh, |(&b, _)| b),
        None => fresh.saturating_add(s),
    };
    pair_q.iter().map(|&s| name(s)).collect()
}

/// What a method may see of the pair of views i (as P) and j (as Q) of a set: the
/// [`crate::Set::pair`] input without its ground truth; `None` when the two views make no
/// pair (the same view, an index out of range, or a scan as P with a full Q).
pub fn pair_input(input: &SetInput, i: usize, j: usize) -> Option<PairInput> {
    let (vi, vj) = (input.views.get(i)?, input.views.get(j)?);
    let kind = crate::set::pair_kind(vi.kind, vj.kind).filter(|_| i != j)?;
    Some(PairInput {
        id: format!("{}-{i}-{j}", input.id),
        kind,
        p: vi.cloud.clone(),
        q: vj.cloud.clone(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::method::Prediction;
    use crate::metrics::score_set;
    use crate::synthetic;

    /// A pair method that knows a set's parts and answers each pair (0, k) with them under
    /// its own renaming of ids (segment `(part + k) % 3 + 10 k`), as methods do.
    struct Renaming(crate::Set);

    impl Method for Renaming {
        fn name(&self) -> &str {
            "renaming"
        }

        fn predict(&self, input: &PairInput) -> Result<Prediction, MethodError> {
            let k: usize = input.id.rsplit('-').next().and_then(|s| s.parse().ok()).unwrap_or(0);
            let ids = |view: usize| -> Vec<SegmentId> {
                let parts = &self.0.truth().parts[view];
                parts.iter().map(|&p| (u32::from(p) + k as u32) % 3 + 10 * k as u32).collect()
            };
            // Each segment's motion is its part's, at the renamed id (NaN elsewhere).
            let truth = self.0.truth();
            let nan = Similarity {
                rotation: crate::math::Matrix3::from_element(f32::NAN),
                ..Similarity::identity()
            };
            let mut motions = vec![nan; 10 * k + 3];
            for (part, motion) in truth.motions[k].iter().enumerate() {
                motions[(part + k) % 3 + 10 * k] = *motion;
            }
            Ok(Prediction { segments_p: ids(0), segments_q: ids(k), motions, ..Default::default() })
        }
    }

    #[test]
    fn lifted_labels_are_consistent_across_views() {
        let set = synthetic::hinge_set("h", 4, &[0.0, 0.5, -0.4, 0.9]);
        let lifted = PairsToSet::new(Renaming(set.clone()));
        let prediction = lifted.predict_set(set.input()).expect("predicts");
        assert_eq!(prediction.segments.len(), 4);
        let scores = score_set(&prediction.segments, &set.truth().parts).expect("scores");
        assert_eq!(scores.multi_scan_iou, 1.0, "{scores:?}");
        // The motions follow the labels: every part's motion to every view k >= 1 is exact.
        assert_eq!(prediction.motions.len(), 4);
        let score = crate::metrics::score_set_prediction(&prediction, set.truth()).expect("scores");
        assert_eq!(score.motions.rotation_deg.len(), 2 * 3, "{score:?}");
        assert!(score.motions.rotation_deg.iter().all(|&e| e < 1e-2), "{score:?}");
        assert!(score.motions.translation.iter().all(|&e| e < 1e-6), "{score:?}");
        // Without motions, none are scored.
        let bare = SetPrediction { motions: Vec::new(), ..prediction.clone() };
        let score = crate::metrics::score_set_prediction(&bare, set.truth()).expect("scores");
        assert!(score.motions.rotation_deg.is_empty());
        // The pairs' own ids, not renamed, are right per view but not across views.
        let raw: Vec<Vec<SegmentId>> = (0..4)
            .map(|k| {
                let pair = pair_input(set.input(), 0, k.max(1)).expect("a pair");
                let p = Renaming(set.clone()).predict(&pair).expect("predicts");
                if k == 0 {
                    p.segments_p
                } else {
                    p.segments_q
                }
            })
            .collect();
        let unrenamed = score_set(&raw, &set.truth().parts).expect("scores");
        assert_eq!(unrenamed.per_scan_iou, 1.0);
        assert!(unrenamed.multi_scan_iou <= 0.5, "{unrenamed:?}");
    }

    #[test]
    fn renaming_takes_the_largest_overlap_and_the_smaller_id_on_ties() {
        // Pair segment 7 covers base labels 1, 1, 2; segment 8 covers 3 and 4 once each.
        let renamed = rename(&[7, 7, 7, 8, 8], &[8, 7, 9], &[1, 1, 2, 3, 4]);
        assert_eq!(renamed, vec![3, 1, 5 + 9]);
    }
}
