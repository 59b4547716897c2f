//! Segmentation metrics: the Rand index over point pairs, and per-part IoU after Hungarian
//! matching of ground-truth parts to predicted segments.

use std::collections::BTreeMap;

use pathfinding::kuhn_munkres::kuhn_munkres;
use pathfinding::matrix::Matrix;

use super::{check_lengths, MetricError};

/// Rand index: the fraction of the C(N, 2) unordered point pairs on which the prediction and
/// the ground truth agree (both same segment, or both different). Unweighted, higher is
/// better, 1 for any relabelling of the truth (the paper's convention).
pub fn rand_index(predicted: &[u32], truth: &[u8]) -> Result<f64, MetricError> {
    check_lengths("segments", predicted.len(), truth.len())?;
    let n = predicted.len() as u64;
    if n < 2 {
        return Ok(1.0);
    }
    let pairs = |k: u64| k * k.saturating_sub(1) / 2;
    let mut joint: BTreeMap<(u32, u8), u64> = BTreeMap::new();
    let mut rows: BTreeMap<u32, u64> = BTreeMap::new();
    let mut cols: BTreeMap<u8, u64> = BTreeMap::new();
    for (&p, &t) in predicted.iter().zip(truth) {
        *joint.entry((p, t)).or_default() += 1;
        *rows.entry(p).or_default() += 1;
        *cols.entry(t).or_default() += 1;
    }
    let both: u64 = joint.values().map(|&c| pairs(c)).sum();
    let same_p: u64 = rows.values().map(|&c| pairs(c)).sum();
    let same_t: u64 = cols.values().map(|&c| pairs(c)).sum();
    // Agreements = pairs together in both + pairs apart in both.
    let agree = pairs(n) + 2 * both - same_p - same_t;
    Ok(agree as f64 / pairs(n) as f64)
}

/// The Hungarian matching of ground-truth parts to predicted segments that maximises the
/// summed IoU; each segment matches at most one part.
#[derive(Debug, Clone, PartialEq)]
pub struct PartMatching {
    /// Per ground-truth part 0..K, its matched segment id, `None` if none is left.
    pub segment: Vec<Option<u32>>,
    /// Per ground-truth part, the IoU with its matched segment (0 when unmatched).
    pub iou: Vec<f64>,
}

impl PartMatching {
    /// Mean IoU over the pair's ground-truth parts.
    pub fn mean_iou(&self) -> f64 {
        self.iou.iter().sum::<f64>() / self.iou.len().max(1) as f64
    }
}

/// The one-to-one assignment of rows to columns of a `rows x cols` row-major score
/// matrix (scores in [0, 1]) that maximises the total score (Hungarian algorithm); per row
/// its column, `None` for rows left over when there are more rows than columns.
pub fn max_assignment(scores: &[f64], rows: usize, cols: usize) -> Vec<Option<usize>> {
    // kuhn_munkres wants integer weights and no more rows than columns: scale the scores
    // and pad the matrix square with zero-score dummy rows and columns.
    const SCALE: f64 = 1e9;
    let side = rows.max(cols);
    let weights = Matrix::from_fn(side, side, |(row, col)| {
        if row < rows && col < cols {
            (scores[row * cols + col] * SCALE).round() as i64
        } else {
            0
        }
    });
    let (_, assignment) = kuhn_munkres(&weights);
    assignment.into_iter().take(rows).map(|col| (col < cols).then_some(col)).collect()
}

/// Matches ground-truth parts (ids `0..K`, `K` the largest id plus one) to predicted
/// segments, maximising the total IoU.
pub fn matched_iou(predicted: &[u32], truth: &[u8]) -> Result<PartMatching, MetricError> {
    check_lengths("segments", predicted.len(), truth.len())?;
    let parts = usize::from(truth.iter().copied().max().unwrap_or(0)) + 1;
    let segments: Vec<u32> = {
        let mut ids = predicted.to_vec();
        ids.sort_unstable();
        ids.dedup();
        ids
    };
    let column = |id: u32| segments.binary_search(&id).expect("every id is listed");
    let mut overlap = vec![vec![0u64; segments.len()]; parts];
    let mut part_size = vec![0u64; parts];
    let mut segment_size = vec![0u64; segments.len()];
    for (&p, &t) in predicted.iter().zip(truth) {
        let (row, col) = (usize::from(t), column(p));
        overlap[row][col] += 1;
        part_size[row] += 1;
        segment_size[col] += 1;
    }
    let iou = |row: usize, col: usize| {
        let inter = overlap[row][col];
        let union = part_size[row] + segment_size[col] - inter;
        if union == 0 {
            0.0
        } else {
            inter as f64 / union as f64
        }
    };
    // Only each part's `parts` best segments can be in an optimal matching (any other
    // match could be swapped for one of them that no other part uses), so the Hungarian
    // table stays K x K^2 even when a method returns one segment per point.
    let mut candidates: Vec<usize> = (0..parts)
        .flat_map(|row| {
            let mut cols: Vec<usize> =
                (0..segments.len()).filter(|&col| overlap[row][col] > 0).collect();
            cols.sort_by(|&a, &b| iou(row, b).total_cmp(&iou(row, a)).then(a.cmp(&b)));
            cols.truncate(parts);
            cols
        })
        .collect();
    candidates.sort_unstable();
    candidates.dedup();
    let scores: Vec<f64> = (0..parts)
        .flat_map(|row| candidates.iter().map(move |&col| (row, col)))
        .map(|(r, c)| iou(r, c))
        .collect();
    let assignment = max_assignment(&scores, parts, candidates.len());
    let mut matching = PartMatching { segment: vec![None; parts], iou: vec![0.0; parts] };
    for (row, col) in assignment.into_iter().enumerate() {
        if let Some(col) = col.map(|c| candidates[c]).filter(|&col| overlap[row][col] > 0) {
            matching.segment[row] = Some(segments[col]);
            matching.iou[row] = iou(row, col);
        }
    }
    Ok(matching)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rand_index_hand_computed() {
        // Truth {0,1},{2,3}; prediction {0},{1,2,3}: of the 6 pairs, (0,1) and (1,2), (1,3)
        // disagree; (0,2), (0,3), (2,3) agree.
        assert_eq!(rand_index(&[5, 7, 7, 7], &[0, 0, 1, 1]).expect("ri"), 0.5);
        assert_eq!(rand_index(&[9, 9, 4, 4], &[0, 0, 1, 1]).expect("ri"), 1.0);
        assert_eq!(rand_index(&[0, 0, 0, 0], &[0, 0, 1, 1]).expect("ri"), 2.0 / 6.0);
    }

    #[test]
    fn one_segment_per_point_is_matched_quickly_and_correctly() {
        // 2048 singleton segments: every part matches one of its points, IoU 1 / size.
        let truth: Vec<u8> = (0..2048).map(|i| (i % 4) as u8).collect();
        let predicted: Vec<u32> = (0..2048).collect();
        let m = matched_iou(&predicted, &truth).expect("iou");
        assert_eq!(m.iou, vec![1.0 / 512.0; 4]);
    }

    #[test]
    fn matched_iou_hand_computed() {
        // Part 0 = {0,1,2}, part 1 = {3,4}, part 2 = {5}. Segment 8 = {0,1}, 3 = {2,3,4,5}.
        let m = matched_iou(&[8, 8, 3, 3, 3, 3], &[0, 0, 0, 1, 1, 2]).expect("iou");
        // Best total: part 0 <-> 8 (2/3) and part 1 <-> 3 (2/4); part 2 unmatched.
        assert_eq!(m.segment, vec![Some(8), Some(3), None]);
        assert_eq!(m.iou, vec![2.0 / 3.0, 0.5, 0.0]);
        assert!((m.mean_iou() - (2.0 / 3.0 + 0.5) / 3.0).abs() < 1e-12);
        let perfect = matched_iou(&[1, 1, 0], &[0, 0, 1]).expect("iou");
        assert_eq!(perfect.iou, vec![1.0, 1.0]);
    }

    #[test]
    fn more_segments_than_parts_and_length_errors() {
        let m = matched_iou(&[0, 1, 2, 3], &[0, 0, 1, 1]).expect("iou");
        assert_eq!(m.iou, vec![0.5, 0.5]);
        assert!(matches!(
            matched_iou(&[0], &[0, 1]),
            Err(MetricError::LengthMismatch { what: "segments", .. })
        ));
        assert!(matches!(rand_index(&[], &[]), Err(MetricError::Empty(_))));
    }
}
