//! Classical baselines of articulated part induction, as compared in Yi et al. 2018
//! ("Deep Part Induction from Articulated Object Pairs", sections "Segmentation" and
//! "Deformation Flow").
//!
//! Segmenters ([`pairs::Segmenter`]: P, Q and a flow on P in; segments of P, one motion
//! per segment and Q's segments by transfer out):
//! - [`SeqRansac`] (`"seqransac"`): sequential RANSAC of rigid motion modes;
//! - [`Spectral`] (`"sc"`): spectral clustering of rigidity affinities;
//! - [`JLinkage`] (`"jlc"`): J-Linkage clustering of motion hypotheses.
//!
//! Every algorithm is seeded per pair from its parameters' seed and the pair's id
//! ([`geometry::seed_for_pair`]), refuses unusable input with a typed error (wrapped in
//! [`pairs::MethodError`]) and never returns NaN. Thresholds are `…Params` fields whose
//! defaults were chosen on the validation split by `examples/sweep.rs`.
//!
//! ```
//! use baselines::SeqRansac;
//! use pairs::metrics::matched_iou;
//! use pairs::{synthetic, Segmenter};
//!
//! // A two-part hinge with its exact flow: SeqRANSAC finds both parts.
//! let pair = synthetic::hinge_pair("demo", 8, 0.8);
//! let prediction = SeqRansac::default().segment(pair.input(), &pair.truth().flow)?;
//! let matching = matched_iou(&prediction.segments_p, &pair.truth().part_p)?;
//! assert!(matching.mean_iou() > 0.95);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![deny(missing_docs)]

pub mod geometry;
pub mod jlinkage;
pub mod labels;
pub mod predict;
pub mod ransac;
pub mod spectral;

pub use jlinkage::{JLinkage, JLinkageParams};
pub use ransac::{SeqRansac, SeqRansacParams};
pub use spectral::{Spectral, SpectralParams};

/// Every segmenter with its default parameters.
pub fn segmenters() -> Vec<Box<dyn pairs::Segmenter>> {
    vec![
        Box::new(SeqRansac::default()),
        Box::new(Spectral::default()),
        Box::new(JLinkage::default()),
    ]
}
