//! Motion hypotheses from local minimal samples, and every point's binary preference set:
//! the hypotheses that explain its flow within the inlier threshold (Toldo & Fusiello 2008,
//! "Robust multiple structures estimation with J-Linkage", section 2).

use pairs::math::{Point3, Real};
use pairs::transform::Similarity;
use rand::Rng;

use crate::geometry::{fit_motion_indices, fit_motion_sample, residual, sample_local_triplet};

/// Up to `count` motion hypotheses, each fitted to three points drawn by
/// [`sample_local_triplet`] (neighbours much more likely, as J-Linkage's sampling is) and
/// then refitted once on the points it explains within `threshold` (a minimal sample of a
/// noisy flow fixes the rotation poorly; the refit keeps hypotheses from fitting only their
/// sample's neighbourhood). Degenerate samples are skipped, with at most `4 * count` draws.
pub fn sample_hypotheses<R: Rng>(
    p: &[Point3],
    moved: &[Point3],
    neighbours: &[Vec<usize>],
    count: usize,
    threshold: Real,
    rng: &mut R,
) -> Vec<Similarity> {
    let pool: Vec<usize> = (0..p.len()).collect();
    let in_pool = vec![true; p.len()];
    let mut hypotheses = Vec::with_capacity(count);
    for _ in 0..4 * count {
        if hypotheses.len() == count {
            break;
        }
        let Some(sample) = sample_local_triplet(rng, &pool, &in_pool, neighbours) else { break };
        let Some(motion) = fit_motion_sample(p, moved, sample) else { continue };
        let support: Vec<usize> =
            (0..p.len()).filter(|&i| residual(&motion, &p[i], &moved[i]) < threshold).collect();
        hypotheses.push(fit_motion_indices(p, moved, &support).unwrap_or(motion));
    }
    hypotheses
}

/// Binary preference sets, one bit per hypothesis, packed in 64-bit words per point.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Preferences {
    /// Words per set.
    pub words: usize,
    /// `points x words` bits, row-major.
    pub bits: Vec<u64>,
}

impl Preferences {
    /// Each point's set of hypotheses with residual under `threshold` at it.
    pub fn of_points(
        p: &[Point3],
        moved: &[Point3],
        hypotheses: &[Similarity],
        threshold: Real,
    ) -> Self {
        let words = hypotheses.len().div_ceil(64).max(1);
        let mut bits = vec![0u64; p.len() * words];
        for (i, (x, y)) in p.iter().zip(moved).enumerate() {
            for (h, motion) in hypotheses.iter().enumerate() {
                if residual(motion, x, y) < threshold {
                    bits[i * words + h / 64] |= 1 << (h % 64);
                }
            }
        }
        Self { words, bits }
    }

    /// The preference set of point `i`.
    pub fn set(&self, i: usize) -> &[u64] {
        &self.bits[i * self.words..(i + 1) * self.words]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use pairs::math::Vector3;

    #[test]
    fn preference_bits_mark_explaining_hypotheses() {
        let p = [Point3::origin(), Point3::new(1.0, 0.0, 0.0)];
        let moved = [Point3::origin(), Point3::new(1.0, 0.5, 0.0)];
        let shift =
            Similarity { translation: Vector3::new(0.0, 0.5, 0.0), ..Similarity::identity() };
        let mut hypotheses = vec![Similarity::identity(); 65];
        hypotheses[64] = shift;
        let prefs = Preferences::of_points(&p, &moved, &hypotheses, 0.1);
        assert_eq!(prefs.words, 2);
        assert_eq!(prefs.set(0), &[u64::MAX, 0]);
        assert_eq!(prefs.set(1), &[0, 1]);
    }
}
