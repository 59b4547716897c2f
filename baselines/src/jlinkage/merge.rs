//! J-Linkage's agglomerative clustering: start from one cluster per point, repeatedly merge
//! the two clusters whose preference sets are closest in Jaccard distance (the merged set
//! is their intersection), and stop when every remaining pair is at distance 1 (no shared
//! hypothesis). Nearest-neighbour chains per cluster keep it near O(N^2) set operations.

use super::preference::Preferences;

/// `1 - |a ∩ b| / |a ∪ b|`; 1 when both sets are empty.
pub fn jaccard_distance(a: &[u64], b: &[u64]) -> f32 {
    let (mut inter, mut union) = (0u32, 0u32);
    for (x, y) in a.iter().zip(b) {
        inter += (x & y).count_ones();
        union += (x | y).count_ones();
    }
    if union == 0 {
        1.0
    } else {
        1.0 - inter as f32 / union as f32
    }
}

/// The nearest other active cluster of `i` and its distance (distance 1 when none).
fn nearest(i: usize, active: &[bool], distance: &[f32], n: usize) -> (usize, f32) {
    (0..n)
        .filter(|&j| j != i && active[j])
        .map(|j| (j, distance[i * n + j]))
        .fold((i, 1.0), |best, c| if c.1 < best.1 { c } else { best })
}

/// Cluster id of every point after J-Linkage's merging (ids are cluster representatives;
/// compact them with `pairs::segments::compact_labels`).
pub fn cluster_jaccard(prefs: &Preferences, n: usize) -> Vec<u32> {
    let mut sets: Vec<Vec<u64>> = (0..n).map(|i| prefs.set(i).to_vec()).collect();
    let mut distance = vec![1.0f32; n * n];
    for i in 0..n {
        for j in i + 1..n {
            let d = jaccard_distance(&sets[i], &sets[j]);
            distance[i * n + j] = d;
            distance[j * n + i] = d;
        }
    }
    let mut active = vec![true; n];
    let mut owner: Vec<u32> = (0..n as u32).collect();
    let mut best: Vec<(usize, f32)> = (0..n).map(|i| nearest(i, &active, &distance, n)).collect();
    while let Some(i) = (0..n)
        .filter(|&i| active[i])
        .min_by(|&a, &b| best[a].1.total_cmp(&best[b].1).then(a.cmp(&b)))
    {
        let (j, d) = best[i];
        if d >= 1.0 || j == i {
            break;
        }
        // Merge j into i: the intersection of their preference sets.
        let merged: Vec<u64> = sets[i].iter().zip(&sets[j]).map(|(a, b)| a & b).collect();
        sets[i] = merged;
        active[j] = false;
        for o in owner.iter_mut().filter(|o| **o == j as u32) {
            *o = i as u32;
        }
        for k in (0..n).filter(|&k| active[k] && k != i) {
            let d = jaccard_distance(&sets[i], &sets[k]);
            distance[i * n + k] = d;
            distance[k * n + i] = d;
        }
        for k in (0..n).filter(|&k| active[k]) {
            if k == i || best[k].0 == i || best[k].0 == j {
                best[k] = nearest(k, &active, &distance, n);
            } else if distance[k * n + i] < best[k].1 {
                best[k] = (i, distance[k * n + i]);
            }
        }
    }
    owner
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jaccard_hand_computed() {
        assert_eq!(jaccard_distance(&[0b1100], &[0b0110]), 1.0 - 1.0 / 3.0);
        assert_eq!(jaccard_distance(&[0], &[0]), 1.0);
        assert_eq!(jaccard_distance(&[0b1], &[0b1]), 0.0);
    }

    #[test]
    fn points_sharing_hypotheses_merge_and_outliers_stay_alone() {
        // Points 0-2 prefer hypotheses {0, 1}, points 3-4 prefer {2, 3}, point 5 nothing.
        let bits = vec![0b0011, 0b0011, 0b0111, 0b1100, 0b1100, 0];
        let prefs = Preferences { words: 1, bits };
        let owner = cluster_jaccard(&prefs, 6);
        assert_eq!(owner[0], owner[1]);
        assert_eq!(owner[1], owner[2]);
        assert_eq!(owner[3], owner[4]);
        assert_ne!(owner[0], owner[3]);
        assert!(owner[..5].iter().all(|&o| o != owner[5]));
    }
}
