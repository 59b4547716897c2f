//! Hard labels from soft segment probabilities (the paper's graph cut), fragment merging,
//! per-segment motions and Q-side labels.

mod expansion;
mod fragments;
mod graph;
mod hard;
pub mod maxflow;
mod motions;

pub use expansion::{alpha_expansion, potts_energy};
pub use fragments::merge_fragments;
pub use graph::KnnGraph;
pub use hard::{argmax, hard_labels, label_q, segment_pair, HardLabelParams, HardSegmentation};
pub use motions::fit_motions_shared_scale;
