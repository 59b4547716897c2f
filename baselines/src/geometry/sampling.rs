//! Per-pair seeding and the samplers shared by the randomised baselines.

use pairs::math::Point3;
use rand::Rng;

/// A seed for one pair: a stable FNV-1a hash of the pair's id mixed with the method's seed,
/// so results never depend on thread order, time, or the standard library's hasher.
pub fn seed_for_pair(seed: u64, pair_id: &str) -> u64 {
    const OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    let hash = pair_id.bytes().fold(OFFSET, |h, b| (h ^ u64::from(b)).wrapping_mul(PRIME));
    hash ^ seed.wrapping_mul(0x9e37_79b9_7f4a_7c15)
}

/// A minimal sample of three distinct points of `pool`: the first uniform, the other two
/// among its `neighbours` that are still in the pool (points of one part are near each
/// other, so local samples hit a single part far more often), or uniform from the pool when
/// fewer than two neighbours remain. `None` when the pool has fewer than three points.
pub fn sample_local_triplet<R: Rng>(
    rng: &mut R,
    pool: &[usize],
    in_pool: &[bool],
    neighbours: &[Vec<usize>],
) -> Option<[usize; 3]> {
    if pool.len() < 3 {
        return None;
    }
    let first = pool[rng.random_range(0..pool.len())];
    let near: Vec<usize> = neighbours[first].iter().copied().filter(|&j| in_pool[j]).collect();
    let (a, b) = if near.len() >= 2 {
        let a = rng.random_range(0..near.len());
        let b = (a + 1 + rng.random_range(0..near.len() - 1)) % near.len();
        (near[a], near[b])
    } else {
        let others: Vec<usize> = pool.iter().copied().filter(|&j| j != first).collect();
        let a = rng.random_range(0..others.len());
        let b = (a + 1 + rng.random_range(0..others.len() - 1)) % others.len();
        (others[a], others[b])
    };
    Some([first, a, b])
}

/// Indices of `count` points spread over the cloud by farthest point sampling
/// ([`pairs::sampling::farthest_point_sampling`]) from point 0; all points, in index order,
/// when `count >= points.len()`.
pub fn sample_farthest_points(points: &[Point3], count: usize) -> Vec<usize> {
    if count >= points.len() {
        return (0..points.len()).collect();
    }
    pairs::sampling::farthest_point_sampling(points, count, 0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn seeds_are_stable_and_distinct() {
        assert_eq!(seed_for_pair(0, ""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(seed_for_pair(7, "a"), seed_for_pair(7, "a"));
        assert_ne!(seed_for_pair(7, "a"), seed_for_pair(7, "b"));
        assert_ne!(seed_for_pair(7, "a"), seed_for_pair(8, "a"));
    }

    #[test]
    fn triplets_are_distinct_pool_members() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let neighbours = vec![vec![1, 2, 3], vec![0, 2], vec![0, 1], vec![0, 4], vec![3]];
        let in_pool = [true, true, false, true, true];
        let pool = [0, 1, 3, 4];
        for _ in 0..100 {
            let [a, b, c] =
                sample_local_triplet(&mut rng, &pool, &in_pool, &neighbours).expect("pool of 4");
            assert!(a != b && b != c && a != c);
            assert!([a, b, c].iter().all(|i| in_pool[*i]));
        }
        assert!(sample_local_triplet(&mut rng, &pool[..2], &in_pool, &neighbours).is_none());
    }

    #[test]
    fn farthest_points_are_distinct_and_spread() {
        let points: Vec<Point3> =
            (0..50).map(|i| Point3::new(i as pairs::math::Real, 0.0, 0.0)).collect();
        let chosen = sample_farthest_points(&points, 3);
        assert_eq!(chosen[..2], [0, 49]);
        assert!(chosen[2] == 24 || chosen[2] == 25);
        assert_eq!(sample_farthest_points(&points[..2], 5), vec![0, 1]);
    }
}
