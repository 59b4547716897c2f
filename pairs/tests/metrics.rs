//! The segmentation metrics against brute force on seeded random labels: the Rand index
//! against an O(N^2) count over all point pairs, and the pruned Hungarian matching of
//! `matched_iou` against the best matching over the full parts x segments IoU table.

use pairs::metrics::{matched_iou, max_assignment, rand_index, MetricError};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The Rand index by definition: agreements over all C(N, 2) unordered pairs of points.
fn rand_index_brute_force(predicted: &[u32], truth: &[u8]) -> f64 {
    let n = predicted.len();
    let (mut agree, mut pairs) = (0u64, 0u64);
    for i in 0..n {
        for j in i + 1..n {
            pairs += 1;
            agree += u64::from((predicted[i] == predicted[j]) == (truth[i] == truth[j]));
        }
    }
    // One point has no pairs: the metric's convention is a perfect score.
    if pairs == 0 {
        1.0
    } else {
        agree as f64 / pairs as f64
    }
}

/// Labels of `n` points: truth parts among `parts` ids (some possibly unused), predicted
/// segment ids drawn from `segments` arbitrary (large, non-contiguous) ids.
fn random_labels(rng: &mut ChaCha8Rng, n: usize, parts: u8, segments: u32) -> (Vec<u32>, Vec<u8>) {
    let ids: Vec<u32> = (0..segments).map(|_| rng.random_range(0..1_000_000)).collect();
    let truth = (0..n).map(|_| rng.random_range(0..parts)).collect();
    let predicted = (0..n).map(|_| ids[rng.random_range(0..ids.len())]).collect();
    (predicted, truth)
}

#[test]
fn rand_index_equals_the_count_over_all_point_pairs() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for n in [1, 2, 3, 4, 7, 16, 61, 250] {
        for _ in 0..20 {
            let parts = rng.random_range(1..=6);
            let segments = rng.random_range(1..=12);
            let (predicted, truth) = random_labels(&mut rng, n, parts, segments);
            let ri = rand_index(&predicted, &truth).expect("equal, non-zero lengths");
            // Both are a ratio of the same two integers, so they agree to the last bit.
            assert_eq!(
                ri,
                rand_index_brute_force(&predicted, &truth),
                "{predicted:?} vs {truth:?}"
            );
            assert!((0.0..=1.0).contains(&ri));
        }
    }
    assert_eq!(rand_index(&[], &[]), Err(MetricError::Empty("segments")));
    assert_eq!(
        rand_index(&[0, 1], &[0]),
        Err(MetricError::LengthMismatch { what: "segments", predicted: 2, truth: 1 })
    );
}

/// The IoU table of ground-truth parts `0..K` (K the largest id plus one) against every
/// distinct predicted segment (sorted ids), computed directly from the point sets.
fn iou_table(predicted: &[u32], truth: &[u8]) -> (Vec<u32>, Vec<Vec<f64>>) {
    let parts = usize::from(*truth.iter().max().expect("points")) + 1;
    let mut segments = predicted.to_vec();
    segments.sort_unstable();
    segments.dedup();
    let table = (0..parts)
        .map(|part| {
            segments
                .iter()
                .map(|&segment| {
                    let in_part = |i: usize| usize::from(truth[i]) == part;
                    let in_segment = |i: usize| predicted[i] == segment;
                    let inter = (0..truth.len()).filter(|&i| in_part(i) && in_segment(i)).count();
                    let union = (0..truth.len()).filter(|&i| in_part(i) || in_segment(i)).count();
                    if union == 0 {
                        0.0
                    } else {
                        inter as f64 / union as f64
                    }
                })
                .collect()
        })
        .collect();
    (segments, table)
}

/// The largest total IoU of any one-to-one matching of parts to segments over the whole
/// table, by dynamic programming over the segments and the set of parts already matched
/// (every matching is considered; parts may stay unmatched).
fn best_total_brute_force(table: &[Vec<f64>]) -> f64 {
    let parts = table.len();
    let columns = table.first().map_or(0, Vec::len);
    let mut best = vec![f64::NEG_INFINITY; 1 << parts];
    best[0] = 0.0;
    for col in 0..columns {
        let mut next = best.clone();
        for (used, &so_far) in best.iter().enumerate() {
            if so_far == f64::NEG_INFINITY {
                continue;
            }
            for (part, row) in table.iter().enumerate().filter(|&(part, _)| used & (1 << part) == 0)
            {
                let with = used | 1 << part;
                next[with] = next[with].max(so_far + row[col]);
            }
        }
        best = next;
    }
    best.into_iter().fold(f64::NEG_INFINITY, f64::max)
}

/// Checks `matched_iou` on one labelling against the full table: a valid one-to-one
/// matching whose IoUs are the table's, with the best total (to 1e-12) of both the brute
/// force and the Hungarian algorithm run on the unpruned table.
fn check_matching(predicted: &[u32], truth: &[u8], case: &str) {
    let matching = matched_iou(predicted, truth).expect("equal, non-zero lengths");
    let (segments, table) = iou_table(predicted, truth);
    assert_eq!(matching.segment.len(), table.len(), "{case}: one entry per part");
    assert_eq!(matching.iou.len(), table.len(), "{case}: one IoU per part");
    let mut used = std::collections::BTreeSet::new();
    for (part, (segment, &iou)) in matching.segment.iter().zip(&matching.iou).enumerate() {
        match segment {
            Some(id) => {
                assert!(used.insert(*id), "{case}: segment {id} matched twice");
                let col = segments.binary_search(id).expect("a predicted segment");
                assert_eq!(iou, table[part][col], "{case}: part {part}'s IoU with {id}");
                assert!(iou > 0.0, "{case}: part {part} matched to a disjoint segment");
            }
            None => assert_eq!(iou, 0.0, "{case}: unmatched part {part}"),
        }
    }
    let total: f64 = matching.iou.iter().sum();
    let best = best_total_brute_force(&table);
    assert!((total - best).abs() < 1e-12, "{case}: total IoU {total}, best matching {best}");
    let flat: Vec<f64> = table.iter().flatten().copied().collect();
    let full = max_assignment(&flat, table.len(), segments.len());
    let full_total: f64 =
        full.iter().enumerate().filter_map(|(row, col)| col.map(|c| table[row][c])).sum();
    assert!((total - full_total).abs() < 1e-12, "{case}: pruned {total}, unpruned {full_total}");
}

/// Uniform random labels with many segments: every part overlaps most segments, so each
/// part's K best segments are a small fraction of them and the pruning drops most columns.
#[test]
fn pruned_matching_equals_the_full_matching_on_random_labels() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for case in 0..300 {
        let parts = rng.random_range(2..=6);
        let segments = rng.random_range(20..=50);
        let n = rng.random_range(30..=400);
        let (predicted, truth) = random_labels(&mut rng, n, parts, segments);
        check_matching(&predicted, &truth, &format!("uniform case {case}"));
    }
}

/// Labels where the matching matters: each part is split over a few segments of its own
/// and a few shared with other parts (so parts compete for their best segments), plus
/// scattered noise segments, and some part ids are never used.
#[test]
fn pruned_matching_equals_the_full_matching_on_competing_segments() {
    let mut rng = ChaCha8Rng::seed_from_u64(17);
    for case in 0..300 {
        let parts = rng.random_range(2..=6u8);
        let segments = rng.random_range(20..=50u32);
        let n = rng.random_range(30..=400);
        let noise = rng.random_range(0.0..0.5);
        // Per part, the segments its points mostly fall in (drawn from a small shared pool
        // of the first ids, so they overlap between parts); the rest are noise segments.
        let pool = (u32::from(parts) * 2).min(segments);
        let own: Vec<Vec<u32>> = (0..parts)
            .map(|_| (0..rng.random_range(1..=3)).map(|_| rng.random_range(0..pool)).collect())
            .collect();
        let present: Vec<u8> = (0..parts).filter(|_| rng.random_bool(0.85)).collect();
        let present = if present.is_empty() { vec![parts - 1] } else { present };
        let truth: Vec<u8> = (0..n).map(|_| present[rng.random_range(0..present.len())]).collect();
        let predicted: Vec<u32> = truth
            .iter()
            .map(|&t| {
                if rng.random_bool(noise) {
                    rng.random_range(0..segments)
                } else {
                    let mine = &own[usize::from(t)];
                    mine[rng.random_range(0..mine.len())]
                }
            })
            .map(|s| 7 * s + 3)
            .collect();
        check_matching(&predicted, &truth, &format!("competing case {case}"));
    }
}

/// One segment per point, or one segment for everything: the extremes of the pruning.
#[test]
fn pruned_matching_equals_the_full_matching_on_extreme_segmentations() {
    let mut rng = ChaCha8Rng::seed_from_u64(23);
    for case in 0..50 {
        let parts = rng.random_range(2..=6u8);
        let n = rng.random_range(1..=120);
        let truth: Vec<u8> = (0..n).map(|_| rng.random_range(0..parts)).collect();
        let singletons: Vec<u32> = (0..n as u32).rev().collect();
        check_matching(&singletons, &truth, &format!("singletons case {case}"));
        check_matching(&vec![9; n], &truth, &format!("one segment case {case}"));
    }
}
