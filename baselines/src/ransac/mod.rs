//! Sequential RANSAC over a flow (the paper's SeqRANSAC baseline).

pub mod sequential;

pub use sequential::{segment_ransac, SeqRansac, SeqRansacError, SeqRansacParams};
