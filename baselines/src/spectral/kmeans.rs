//! k-means with k-means++ seeding and restarts (Arthur & Vassilvitskii 2007), for the rows
//! of a spectral embedding.

use rand::Rng;

fn distance2(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

/// One k-means run from k-means++ seeds: labels and total squared distance.
fn run_once<R: Rng>(
    rows: &[Vec<f64>],
    k: usize,
    iterations: usize,
    rng: &mut R,
) -> (Vec<u32>, f64) {
    let mut centres: Vec<Vec<f64>> = vec![rows[rng.random_range(0..rows.len())].clone()];
    while centres.len() < k {
        let weights: Vec<f64> = rows
            .iter()
            .map(|r| centres.iter().map(|c| distance2(r, c)).fold(f64::MAX, f64::min))
            .collect();
        let total: f64 = weights.iter().sum();
        let pick = if total > 0.0 {
            let mut target = rng.random::<f64>() * total;
            weights.iter().position(|&w| {
                target -= w;
                target <= 0.0
            })
        } else {
            None
        };
        centres.push(rows[pick.unwrap_or_else(|| rng.random_range(0..rows.len()))].clone());
    }
    let mut labels = vec![0u32; rows.len()];
    for _ in 0..iterations {
        let next: Vec<u32> = rows
            .iter()
            .map(|r| {
                (0..k)
                    .min_by(|&a, &b| {
                        distance2(r, &centres[a]).total_cmp(&distance2(r, &centres[b]))
                    })
                    .unwrap_or(0) as u32
            })
            .collect();
        let converged = next == labels;
        labels = next;
        for (c, centre) in centres.iter_mut().enumerate() {
            let members: Vec<&Vec<f64>> = rows
                .iter()
                .zip(&labels)
                .filter(|(_, &l)| l as usize == c)
                .map(|(r, _)| r)
                .collect();
            if !members.is_empty() {
                for (d, v) in centre.iter_mut().enumerate() {
                    *v = members.iter().map(|m| m[d]).sum::<f64>() / members.len() as f64;
                }
            }
        }
        if converged {
            break;
        }
    }
    let cost = rows.iter().zip(&labels).map(|(r, &l)| distance2(r, &centres[l as usize])).sum();
    (labels, cost)
}

/// Labels `0..k` of `rows` from the best (lowest cost) of `restarts` k-means runs; all 0
/// when `k <= 1` or there are no rows.
pub fn cluster_kmeans<R: Rng>(
    rows: &[Vec<f64>],
    k: usize,
    restarts: usize,
    iterations: usize,
    rng: &mut R,
) -> Vec<u32> {
    if k <= 1 || rows.is_empty() {
        return vec![0; rows.len()];
    }
    (0..restarts.max(1))
        .map(|_| run_once(rows, k.min(rows.len()), iterations, rng))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(labels, _)| labels)
        .unwrap_or_else(|| vec![0; rows.len()])
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn separated_blobs_are_found() {
        let rows: Vec<Vec<f64>> =
            (0..30).map(|i| vec![(i / 10) as f64 * 5.0 + (i % 10) as f64 * 0.01, 1.0]).collect();
        let labels = cluster_kmeans(&rows, 3, 4, 50, &mut ChaCha8Rng::seed_from_u64(3));
        for i in 0..30 {
            assert_eq!(labels[i], labels[(i / 10) * 10]);
            assert_ne!(labels[i], labels[(i + 10) % 30]);
        }
        assert_eq!(cluster_kmeans(&rows, 1, 4, 50, &mut ChaCha8Rng::seed_from_u64(3)), vec![0; 30]);
    }
}
