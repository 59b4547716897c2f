//! J-Linkage clustering of rigid motion hypotheses (the paper's JLC baseline).

pub mod merge;
pub mod preference;
pub mod segmenter;

pub use merge::{cluster_jaccard, jaccard_distance};
pub use preference::{sample_hypotheses, Preferences};
pub use segmenter::{segment_jlinkage, JLinkage, JLinkageError, JLinkageParams};
