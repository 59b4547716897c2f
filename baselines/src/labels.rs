//! Post-processing of segment labels shared by the clustering baselines: segments too small
//! to be a part are dissolved, points no motion explains (flow outliers) take the label of
//! their nearest explained neighbour in P, and segments and motions can be refined by a few
//! rounds of refit-and-reassign.

use pairs::math::{Point3, Real};
use pairs::segments::compact_labels;

use crate::geometry::{fit_motion_trimmed, residual, Neighbours};

/// Labels of the points not `known`, copied from their nearest `known` point of P; every
/// label 0 when no point is known. Ids are compacted to `0..K`.
pub fn fill_from_nearest(p: &[Point3], labels: &[u32], known: &[bool]) -> Vec<u32> {
    let anchors: Vec<usize> = (0..p.len()).filter(|&i| known[i]).collect();
    if anchors.is_empty() {
        return vec![0; p.len()];
    }
    let anchor_points: Vec<Point3> = anchors.iter().map(|&i| p[i]).collect();
    let tree = Neighbours::build(&anchor_points);
    let filled: Vec<u32> = (0..p.len())
        .map(|i| match known[i] {
            true => labels[i],
            false => tree.nearest(&p[i]).map_or(0, |(j, _)| labels[anchors[j]]),
        })
        .collect();
    compact_labels(&filled)
}

/// Dissolves segments with fewer than `min_size` points: their points take the label of the
/// nearest point of a large segment (every label 0 if no segment is large). Also returns
/// which points were in a large segment (the ones the labels are sure of).
pub fn absorb_small_segments(
    p: &[Point3],
    labels: &[u32],
    min_size: usize,
) -> (Vec<u32>, Vec<bool>) {
    let labels = compact_labels(labels);
    let mut sizes = vec![0usize; labels.iter().max().map_or(0, |&m| m as usize + 1)];
    for &l in &labels {
        sizes[l as usize] += 1;
    }
    let known: Vec<bool> = labels.iter().map(|&l| sizes[l as usize] >= min_size).collect();
    (fill_from_nearest(p, &labels, &known), known)
}

/// `rounds` rounds of: fit every segment's motion on its explained points (trimmed once), give every point
/// the segment of smallest residual if that residual is under `threshold`, and mark it
/// unexplained otherwise (a k-means over motions that ignores outliers); then unexplained
/// points take their nearest explained neighbour's label. `explained` says which points the
/// input labels are sure of. Segments left without a valid fit drop out.
pub fn reassign_by_motion(
    p: &[Point3],
    moved: &[Point3],
    labels: &[u32],
    explained: &[bool],
    threshold: Real,
    rounds: usize,
) -> Vec<u32> {
    let mut labels = compact_labels(labels);
    let mut explained = explained.to_vec();
    for _ in 0..rounds {
        let count = labels.iter().max().map_or(0, |&m| m as usize + 1);
        let mut members = vec![Vec::new(); count];
        for (i, &l) in labels.iter().enumerate() {
            if explained[i] {
                members[l as usize].push(i);
            }
        }
        let fits: Vec<_> = members
            .iter()
            .enumerate()
            .filter_map(|(k, m)| Some((k as u32, fit_motion_trimmed(p, moved, m, threshold)?)))
            .collect();
        if fits.is_empty() {
            break;
        }
        for i in 0..p.len() {
            let best = fits
                .iter()
                .map(|(k, m)| (*k, residual(m, &p[i], &moved[i])))
                .min_by(|a, b| a.1.total_cmp(&b.1));
            if let Some((k, r)) = best {
                explained[i] = r < threshold;
                if explained[i] {
                    labels[i] = k;
                }
            }
        }
    }
    fill_from_nearest(p, &labels, &explained)
}

#[cfg(test)]
mod tests {
    use super::*;
    use pairs::math::Vector3;

    fn grid() -> Vec<Point3> {
        (0..12)
            .map(|i| Point3::new((i % 6) as f32 * 0.1, (i / 6) as f32 * 0.1, (i % 3) as f32 * 0.05))
            .collect()
    }

    #[test]
    fn small_segments_join_their_nearest_large_neighbour() {
        let p = grid();
        // Point 3 (alone in segment 7) is nearest to point 4 of segment 1.
        let labels = [0, 0, 0, 7, 1, 1, 0, 0, 0, 1, 1, 1];
        let (merged, known) = absorb_small_segments(&p, &labels, 3);
        assert_eq!(merged, vec![0, 0, 0, 1, 1, 1, 0, 0, 0, 1, 1, 1]);
        assert_eq!(known.iter().filter(|k| !**k).count(), 1);
        assert_eq!(absorb_small_segments(&p, &labels, 50).0, vec![0; 12]);
    }

    #[test]
    fn reassignment_fixes_greedy_labels_and_ignores_outliers() {
        let p = grid();
        let shift = Vector3::new(0.0, 0.0, 0.3);
        let mut moved: Vec<Point3> =
            p.iter().map(|x| if x.x > 0.25 { x + shift } else { *x }).collect();
        // Point 3 is an outlier of the moving side; point 2 was greedily given segment 1.
        moved[3] += Vector3::new(1.0, 0.0, 0.0);
        let labels = [0, 0, 1, 1, 1, 1, 0, 0, 0, 1, 1, 1];
        let explained = [true, true, true, false, true, true, true, true, true, true, true, true];
        let fixed = reassign_by_motion(&p, &moved, &labels, &explained, 0.1, 2);
        assert_eq!(fixed, vec![0, 0, 0, 1, 1, 1, 0, 0, 0, 1, 1, 1]);
    }
}
