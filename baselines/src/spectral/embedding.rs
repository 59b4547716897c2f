//! The normalised spectral embedding (Ng, Jordan & Weiss 2001) with the number of clusters
//! from the eigengap, on a regularised affinity (Amini et al. 2013): a small constant added
//! to every affinity keeps isolated points (flow outliers) from each producing an
//! eigenvalue near 1, which would make the eigengap count them as clusters.

use nalgebra::{DMatrix, SymmetricEigen};

/// Rows of the spectral embedding and the number of clusters it was cut at.
#[derive(Debug, Clone, PartialEq)]
pub struct Embedding {
    /// Number of clusters `k` from the eigengap.
    pub clusters: usize,
    /// One unit-length row of `k` coordinates per point.
    pub rows: Vec<Vec<f64>>,
    /// Eigenvalues of the normalised affinity, largest first.
    pub eigenvalues: Vec<f64>,
}

/// The embedding of affinity `w` (symmetric, non-negative): `D^-1/2 (W + tau) D^-1/2` with
/// `tau = regularisation * mean degree / n`, its top eigenvectors, `k` maximising the gap
/// `lambda_k - lambda_(k+1)` for `k` in `1..=max_clusters`, rows normalised to unit length.
pub fn embed_spectral(w: &DMatrix<f64>, max_clusters: usize, regularisation: f64) -> Embedding {
    let n = w.nrows();
    if n == 0 {
        return Embedding { clusters: 0, rows: Vec::new(), eigenvalues: Vec::new() };
    }
    let mean_degree = w.sum() / n as f64;
    let tau = regularisation * mean_degree / n as f64;
    let regularised = w.map(|v| v + tau);
    let inv_sqrt: Vec<f64> = regularised
        .row_iter()
        .map(|row| {
            let d = row.sum();
            if d > 0.0 {
                1.0 / d.sqrt()
            } else {
                0.0
            }
        })
        .collect();
    let normalised = DMatrix::from_fn(n, n, |i, j| regularised[(i, j)] * inv_sqrt[i] * inv_sqrt[j]);
    let eigen = SymmetricEigen::new(normalised);
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| eigen.eigenvalues[b].total_cmp(&eigen.eigenvalues[a]));
    let eigenvalues: Vec<f64> = order.iter().map(|&i| eigen.eigenvalues[i]).collect();
    let top = max_clusters.clamp(1, n.saturating_sub(1).max(1));
    let clusters = (1..=top)
        .max_by(|&a, &b| {
            let gap = |k: usize| eigenvalues[k - 1] - eigenvalues.get(k).copied().unwrap_or(0.0);
            gap(a).total_cmp(&gap(b)).then(b.cmp(&a))
        })
        .unwrap_or(1);
    let rows = (0..n)
        .map(|i| {
            let row: Vec<f64> =
                order[..clusters].iter().map(|&c| eigen.eigenvectors[(i, c)]).collect();
            let norm = row.iter().map(|v| v * v).sum::<f64>().sqrt();
            if norm > 1e-12 && norm.is_finite() {
                row.iter().map(|v| v / norm).collect()
            } else {
                vec![0.0; clusters]
            }
        })
        .collect();
    Embedding { clusters, rows, eigenvalues }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn block_affinity_gives_its_block_count() {
        // Three blocks of 4 points each, weakly linked.
        let block = |i: usize| i / 4;
        let w = DMatrix::from_fn(12, 12, |i, j| if block(i) == block(j) { 1.0 } else { 0.01 });
        let e = embed_spectral(&w, 10, 0.05);
        assert_eq!(e.clusters, 3);
        let same = e.rows[0].iter().zip(&e.rows[1]).map(|(a, b)| a * b).sum::<f64>();
        let other = e.rows[0].iter().zip(&e.rows[4]).map(|(a, b)| a * b).sum::<f64>();
        assert!(same > 0.99 && other.abs() < 0.2);
        assert_eq!(embed_spectral(&DMatrix::from_element(5, 5, 1.0), 10, 0.05).clusters, 1);
    }
}
