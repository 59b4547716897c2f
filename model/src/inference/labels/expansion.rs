//! Alpha-expansion (Boykov, Veksler and Zabih 2001) for the Potts energy
//! `E(l) = Σ_i D_i(l_i) + λ Σ_{(i,j)} w_ij [l_i ≠ l_j]` over a [`KnnGraph`]: each move lets
//! every point either keep its label or switch to one label α, solved exactly by one minimum
//! cut (the Potts term is a metric, so every move's binary energy is submodular). Cycles over
//! the labels stop when no move lowers the energy. Only labels `0..K` of the cost table can
//! appear, so the result never has more segments than the soft assignment.

use super::graph::KnnGraph;
use super::maxflow::FlowGraph;

/// The energy of `labels` under unary `costs` (`costs[i][k]`) and Potts weight `smoothness`.
pub fn potts_energy(costs: &[Vec<f32>], graph: &KnnGraph, smoothness: f32, labels: &[u32]) -> f64 {
    let unary: f64 = labels.iter().zip(costs).map(|(&l, c)| f64::from(c[l as usize])).sum();
    let pairwise: f64 = graph
        .edges
        .iter()
        .filter(|&&(i, j, _)| labels[i] != labels[j])
        .map(|&(_, _, w)| f64::from(smoothness * w))
        .sum();
    unary + pairwise
}

/// The labels after the expansion move for `alpha` from `labels` (optimal among all moves
/// that switch any subset of points to `alpha`).
fn expand(
    costs: &[Vec<f32>],
    graph: &KnnGraph,
    smoothness: f32,
    labels: &[u32],
    alpha: u32,
) -> Vec<u32> {
    let n = labels.len();
    // Binary variable x_i: source side = keep l_i (x = 0), sink side = take alpha (x = 1).
    // Unary costs of x = 0 and x = 1 per node, accumulated, then turned into terminal edges.
    let keep: Vec<f32> = (0..n).map(|i| costs[i][labels[i] as usize]).collect();
    let mut take: Vec<f32> = (0..n).map(|i| costs[i][alpha as usize]).collect();
    let mut g = FlowGraph::new(n);
    for &(i, j, w) in &graph.edges {
        let w = smoothness * w;
        let differ = |a: u32, b: u32| if a == b { 0.0 } else { w };
        // E(x_i, x_j) as A, B = E(0, 1), C = E(1, 0), D = E(1, 1) = 0.
        let a = differ(labels[i], labels[j]);
        let b = differ(labels[i], alpha);
        let c = differ(alpha, labels[j]);
        // E = A + (C - A) x_i - C x_j + (B + C - A) (1 - x_i) x_j; the constant A does not
        // change the minimiser, and B + C >= A because the Potts term is a metric.
        take[i] += c - a;
        take[j] -= c;
        g.add_edge(i, j, b + c - a, 0.0);
    }
    for i in 0..n {
        let d = take[i] - keep[i];
        // Paying `d` for x = 1: a source edge if positive (cut when i is on the sink side),
        // a sink edge of -d otherwise.
        if d > 0.0 {
            g.add_terminal(i, d, 0.0);
        } else {
            g.add_terminal(i, 0.0, -d);
        }
    }
    let cut = g.min_cut();
    labels.iter().zip(&cut.source_side).map(|(&l, &keep)| if keep { l } else { alpha }).collect()
}

/// Minimises the Potts energy from `initial` by alpha-expansion over the labels `0..K`
/// (`K` = columns of `costs`), at most `max_cycles` sweeps.
pub fn alpha_expansion(
    costs: &[Vec<f32>],
    graph: &KnnGraph,
    smoothness: f32,
    initial: &[u32],
    max_cycles: usize,
) -> Vec<u32> {
    let k = costs.first().map_or(0, Vec::len) as u32;
    let mut labels = initial.to_vec();
    let mut energy = potts_energy(costs, graph, smoothness, &labels);
    for _ in 0..max_cycles {
        let mut improved = false;
        for alpha in 0..k {
            let candidate = expand(costs, graph, smoothness, &labels, alpha);
            let e = potts_energy(costs, graph, smoothness, &candidate);
            if e < energy - 1e-6 * energy.abs().max(1.0) {
                labels = candidate;
                energy = e;
                improved = true;
            }
        }
        if !improved {
            break;
        }
    }
    labels
}

#[cfg(test)]
mod tests {
    use super::*;
    use pairs::math::Point3;
    use rand::{Rng, SeedableRng};

    fn random_problem(
        rng: &mut rand_chacha::ChaCha8Rng,
        n: usize,
        k: usize,
    ) -> (Vec<Vec<f32>>, KnnGraph) {
        let points: Vec<Point3> = (0..n)
            .map(|_| Point3::new(rng.random_range(0.0..0.2), rng.random_range(0.0..0.2), 0.0))
            .collect();
        let costs = (0..n).map(|_| (0..k).map(|_| rng.random_range(0.0..2.0)).collect()).collect();
        (costs, KnnGraph::build(&points, 3, 0.1))
    }

    fn all_labellings(n: usize, k: u32) -> impl Iterator<Item = Vec<u32>> {
        (0..k.pow(n as u32)).map(move |mut code| {
            (0..n)
                .map(|_| {
                    let l = code % k;
                    code /= k;
                    l
                })
                .collect()
        })
    }

    #[test]
    fn each_move_is_the_best_expansion() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        for _ in 0..60 {
            let n = rng.random_range(2..8);
            let (costs, graph) = random_problem(&mut rng, n, 3);
            let labels: Vec<u32> = (0..n).map(|_| rng.random_range(0..3)).collect();
            let alpha = rng.random_range(0..3);
            let moved = expand(&costs, &graph, 1.5, &labels, alpha);
            let best = (0..1u32 << n)
                .map(|mask| {
                    let l: Vec<u32> = (0..n)
                        .map(|i| if mask >> i & 1 == 1 { alpha } else { labels[i] })
                        .collect();
                    potts_energy(&costs, &graph, 1.5, &l)
                })
                .fold(f64::INFINITY, f64::min);
            assert!((potts_energy(&costs, &graph, 1.5, &moved) - best).abs() < 1e-4);
        }
    }

    #[test]
    fn two_labels_reach_the_global_minimum() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(9);
        for _ in 0..40 {
            let n = rng.random_range(2..9);
            let (costs, graph) = random_problem(&mut rng, n, 2);
            let initial = vec![0; n];
            let found = alpha_expansion(&costs, &graph, 1.0, &initial, 5);
            let best = all_labellings(n, 2)
                .map(|l| potts_energy(&costs, &graph, 1.0, &l))
                .fold(f64::INFINITY, f64::min);
            assert!((potts_energy(&costs, &graph, 1.0, &found) - best).abs() < 1e-4);
        }
    }

    #[test]
    fn never_raises_the_energy_and_uses_only_known_labels() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(2);
        for _ in 0..20 {
            let (costs, graph) = random_problem(&mut rng, 40, 4);
            let initial: Vec<u32> = (0..40).map(|_| rng.random_range(0..4)).collect();
            let found = alpha_expansion(&costs, &graph, 2.0, &initial, 5);
            assert!(
                potts_energy(&costs, &graph, 2.0, &found)
                    <= potts_energy(&costs, &graph, 2.0, &initial) + 1e-6
            );
            assert!(found.iter().all(|&l| l < 4));
        }
    }
}
