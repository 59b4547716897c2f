//! Maximum flow and minimum s-t cut by Dinic's algorithm (blocking flows on BFS level
//! graphs), for the binary cuts inside alpha-expansion.
//!
//! Why not a crate: the Rust max-flow implementations on crates.io that are maintained
//! (`pathfinding`'s Edmonds–Karp) need `Ord` capacities, so real-valued energies would have
//! to be quantised; the graphs here are small (one node per point, about ten edges each),
//! where Dinic's `O(V² E)` bound is never approached and its code is short enough to test
//! exhaustively against brute force.

/// Capacities below this count as saturated (f32 energies accumulate rounding).
const EPSILON: f32 = 1e-7;

#[derive(Debug, Clone, Copy)]
struct Edge {
    to: usize,
    capacity: f32,
}

/// A directed graph with a source and a sink, built edge by edge, then cut once.
#[derive(Debug, Clone)]
pub struct FlowGraph {
    nodes: usize,
    /// Edges in pairs: `2k` forward, `2k + 1` its residual reverse.
    edges: Vec<Edge>,
    adjacency: Vec<Vec<usize>>,
}

/// The result of [`FlowGraph::min_cut`].
#[derive(Debug, Clone, PartialEq)]
pub struct Cut {
    /// The maximum flow value, equal to the capacity of the minimum cut.
    pub value: f32,
    /// Per node, whether it stays on the source side of the minimum cut.
    pub source_side: Vec<bool>,
}

impl FlowGraph {
    /// A graph of `nodes` inner nodes; the source and sink are extra nodes.
    pub fn new(nodes: usize) -> Self {
        Self { nodes, edges: Vec::new(), adjacency: vec![Vec::new(); nodes + 2] }
    }

    fn source(&self) -> usize {
        self.nodes
    }

    fn sink(&self) -> usize {
        self.nodes + 1
    }

    fn push(&mut self, from: usize, to: usize, forward: f32, backward: f32) {
        self.adjacency[from].push(self.edges.len());
        self.edges.push(Edge { to, capacity: forward.max(0.0) });
        self.adjacency[to].push(self.edges.len());
        self.edges.push(Edge { to: from, capacity: backward.max(0.0) });
    }

    /// Adds terminal capacities of node `i`: `to_source` is paid when `i` ends on the sink
    /// side, `to_sink` when it ends on the source side. Negative values count as 0.
    pub fn add_terminal(&mut self, i: usize, to_source: f32, to_sink: f32) {
        let (s, t) = (self.source(), self.sink());
        if to_source > 0.0 {
            self.push(s, i, to_source, 0.0);
        }
        if to_sink > 0.0 {
            self.push(i, t, to_sink, 0.0);
        }
    }

    /// Adds an edge `i -> j` of capacity `forward` (paid when `i` is on the source side and
    /// `j` on the sink side) and `j -> i` of capacity `backward`.
    pub fn add_edge(&mut self, i: usize, j: usize, forward: f32, backward: f32) {
        if forward > 0.0 || backward > 0.0 {
            self.push(i, j, forward, backward);
        }
    }

    /// BFS levels from the source over unsaturated edges; `None` where unreachable.
    fn levels(&self) -> Vec<Option<usize>> {
        let mut level = vec![None; self.nodes + 2];
        let mut queue = std::collections::VecDeque::from([self.source()]);
        level[self.source()] = Some(0);
        while let Some(u) = queue.pop_front() {
            for &e in &self.adjacency[u] {
                let Edge { to, capacity } = self.edges[e];
                if capacity > EPSILON && level[to].is_none() {
                    level[to] = level[u].map(|l| l + 1);
                    queue.push_back(to);
                }
            }
        }
        level
    }

    /// Sends up to `limit` along level-increasing paths from `u` (iterative DFS would be
    /// longer; recursion depth is bounded by the number of levels, at most the node count).
    fn augment(
        &mut self,
        u: usize,
        limit: f32,
        level: &[Option<usize>],
        next: &mut [usize],
    ) -> f32 {
        if u == self.sink() {
            return limit;
        }
        while next[u] < self.adjacency[u].len() {
            let e = self.adjacency[u][next[u]];
            let Edge { to, capacity } = self.edges[e];
            let deeper = matches!((level[u], level[to]), (Some(a), Some(b)) if b == a + 1);
            if capacity > EPSILON && deeper {
                let pushed = self.augment(to, limit.min(capacity), level, next);
                if pushed > 0.0 {
                    self.edges[e].capacity -= pushed;
                    self.edges[e ^ 1].capacity += pushed;
                    return pushed;
                }
            }
            next[u] += 1;
        }
        0.0
    }

    /// Runs max-flow to completion and returns the minimum cut (the graph's residual
    /// capacities are consumed).
    pub fn min_cut(mut self) -> Cut {
        let mut value = 0.0f32;
        loop {
            let level = self.levels();
            if level[self.sink()].is_none() {
                let source_side = level[..self.nodes].iter().map(Option::is_some).collect();
                return Cut { value, source_side };
            }
            let mut next = vec![0; self.nodes + 2];
            loop {
                let pushed = self.augment(self.source(), f32::INFINITY, &level, &mut next);
                if pushed <= 0.0 {
                    break;
                }
                value += pushed;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// The cost of a labelling (true = source side) of a graph given as lists.
    fn cut_cost(
        terminals: &[(f32, f32)],
        edges: &[(usize, usize, f32, f32)],
        side: &[bool],
    ) -> f32 {
        let t: f32 = terminals
            .iter()
            .zip(side)
            .map(|(&(s, k), &on_source)| if on_source { k } else { s })
            .sum();
        let e: f32 = edges
            .iter()
            .map(|&(i, j, f, b)| match (side[i], side[j]) {
                (true, false) => f,
                (false, true) => b,
                _ => 0.0,
            })
            .sum();
        t + e
    }

    #[test]
    fn textbook_network() {
        // CLRS figure 26.1 with node 0 = s and 5 = t mapped to terminals: max flow 23.
        let mut g = FlowGraph::new(4);
        g.add_terminal(0, 16.0, 0.0);
        g.add_terminal(1, 13.0, 0.0);
        g.add_edge(0, 1, 10.0, 4.0);
        g.add_edge(0, 2, 12.0, 0.0);
        g.add_edge(2, 1, 9.0, 0.0);
        g.add_edge(1, 3, 14.0, 0.0);
        g.add_edge(3, 2, 7.0, 0.0);
        g.add_terminal(2, 0.0, 20.0);
        g.add_terminal(3, 0.0, 4.0);
        let cut = g.min_cut();
        assert!((cut.value - 23.0).abs() < 1e-4, "{}", cut.value);
    }

    #[test]
    fn matches_brute_force_on_random_graphs() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        for _ in 0..200 {
            let n = rng.random_range(1..8);
            let terminals: Vec<(f32, f32)> =
                (0..n).map(|_| (rng.random_range(0.0..2.0), rng.random_range(0.0..2.0))).collect();
            let edges: Vec<(usize, usize, f32, f32)> = (0..rng.random_range(0..12))
                .map(|_| {
                    let (i, j) = (rng.random_range(0..n), rng.random_range(0..n));
                    (i, j, rng.random_range(0.0..1.5), rng.random_range(0.0..1.5))
                })
                .filter(|e| e.0 != e.1)
                .collect();
            let mut g = FlowGraph::new(n);
            for (i, &(s, t)) in terminals.iter().enumerate() {
                g.add_terminal(i, s, t);
            }
            for &(i, j, f, b) in &edges {
                g.add_edge(i, j, f, b);
            }
            let best = (0..1u32 << n)
                .map(|mask| {
                    let side: Vec<bool> = (0..n).map(|i| mask >> i & 1 == 1).collect();
                    cut_cost(&terminals, &edges, &side)
                })
                .fold(f32::INFINITY, f32::min);
            let cut = g.min_cut();
            assert!((cut.value - best).abs() < 1e-3, "flow {} vs cut {best}", cut.value);
            let achieved = cut_cost(&terminals, &edges, &cut.source_side);
            assert!((achieved - best).abs() < 1e-3, "labelling costs {achieved}, best {best}");
        }
    }
}
