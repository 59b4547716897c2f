//! The paper's inference procedure ("Iterative Segmentation and Motion Estimation"): a first
//! pass gives a flow, soft segments, hard labels and one rigid motion per segment; then P is
//! deformed piecewise rigidly by those motions into P', the correspondence and flow modules
//! run on (P', Q) for a residual flow f', the refined flow `P' - P + f'` is segmented again,
//! and so on until the flow changes by less than a tolerance or after 10 iterations. An
//! optional rotation search ([`rotation_search`]) picks P's initial orientation. [`labels`]
//! turns soft segments into hard labels (graph cut, fragment merging, per-segment motions,
//! Q's labels), and [`method`] is the network as the evaluator's method and segmenter.

pub mod labels;
pub mod method;
pub mod params;
pub mod procedure;
pub mod rotation_search;
pub mod subproblems;

pub use params::InferenceParams;
pub(crate) use procedure::nearest;
pub use procedure::{align_globally, Inference, Iteration};
