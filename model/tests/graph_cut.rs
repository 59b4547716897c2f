//! Properties of the hard-label step on random clouds and random soft assignments: the graph
//! cut only uses the soft assignment's segments and never has more segments than its argmax
//! labelling. It does not always leave fewer connected fragments: on scattered random
//! clouds a cut can split a label's region (found by this test; e.g. 6 fragments before, 7
//! after), so that property is checked on a noisy hinge in `labels/hard.rs` instead.

use model::inference::labels::{argmax, hard_labels, HardLabelParams};
use pairs::math::{Point3, Vector3};
use proptest::prelude::*;

fn distinct(labels: &[u32]) -> usize {
    let mut v = labels.to_vec();
    v.sort_unstable();
    v.dedup();
    v.len()
}

/// A cloud of `n` points in the unit cube with `k`-column probabilities and a small flow.
fn case() -> impl Strategy<Value = (Vec<Point3>, Vec<Vec<f32>>, Vec<Vector3>)> {
    (20usize..90, 2usize..6).prop_flat_map(|(n, k)| {
        (
            prop::collection::vec((0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0), n),
            prop::collection::vec(prop::collection::vec(0.01f32..1.0, k), n),
            prop::collection::vec((-0.1f32..0.1, -0.1f32..0.1, -0.1f32..0.1), n),
        )
            .prop_map(|(points, probs, flow)| {
                (
                    points.into_iter().map(|(x, y, z)| Point3::new(x, y, z)).collect(),
                    probs,
                    flow.into_iter().map(|(x, y, z)| Vector3::new(x, y, z)).collect(),
                )
            })
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn the_cut_never_adds_segments((points, probs, flow) in case()) {
        let params = HardLabelParams::default();
        let columns = probs[0].len() as u32;
        let before = argmax(&probs);
        let after = hard_labels(&points, &probs, &flow, &params);
        prop_assert_eq!(after.len(), points.len());
        prop_assert!(after.iter().all(|&l| l < columns));
        prop_assert!(distinct(&after) <= distinct(&before));
    }
}
