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
//! Methods ([`pairs::Method`]: P and Q in, a flow on P and its segments out):
//! - [`Nrr`] (`"nrr"`): non-rigid registration under local rigidity with part clustering,
//!   after Huang et al. 2008; it reports its own flow and its own segments;
//! - flow methods, each reporting one segment: [`NearestFlow`] (`"nn"`), [`IcpFlow`]
//!   (`"icp"`, trimmed rigid ICP), [`EmbeddedDeformation`] (`"ed"`, Sumner et al. 2007)
//!   and [`FpfhFlow`] (`"fpfh"`, hand-crafted descriptor matching standing in for the
//!   paper's 3DMatch and LMVCNN rows).
//!
//! Every algorithm is seeded per pair from its parameters' seed and the pair's id
//! ([`geometry::seed_for_pair`]), refuses unusable input with a typed error (wrapped in
//! [`pairs::MethodError`]) and never returns NaN. Every threshold is a `…Params` field with
//! a documented `Default`; the inlier thresholds, SC's scales, ICP's trimming and NRR's
//! part threshold were chosen on the validation split by `examples/sweep.rs`
//! (`reports/baselines_sweep.csv`). Those are starting points: the evaluator's leaderboards
//! cross-validate the segmenters' thresholds and NRR's part threshold on the validation
//! sets for each flow source they are scored on (`evaluator::tuning`, `reports/tuning/`).
//!
//! Modules follow the math: [`geometry`] (k-d tree neighbours, local-PCA normals, sample
//! motion fits, seeding and sampling, input checks), [`labels`] (label post-processing
//! shared by the segmenters), [`ransac`], [`spectral`], [`jlinkage`], [`registration`]
//! (correspondences, deformation graph, ICP, ED, NRR) and [`descriptors`] (FPFH);
//! [`predict`] wraps an algorithm into the `pairs` traits.
//!
//! ```
//! use baselines::SeqRansac;
//! use pairs::metrics::matched_iou;
//! use pairs::{synthetic, Segmenter};
//!
//! // A two-part hinge with its exact flow: SeqRANSAC finds both parts.
//! let pair = synthetic::hinge_pair("demo", 8, 0.8);
//! let flow = pair.truth().flow.as_deref().ok_or("a pair of one object has a flow")?;
//! let prediction = SeqRansac::default().segment(pair.input(), flow)?;
//! let matching = matched_iou(&prediction.segments_p, &pair.truth().part_p)?;
//! assert!(matching.mean_iou() > 0.95);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![deny(missing_docs)]

pub mod descriptors;
pub mod geometry;
pub mod jlinkage;
pub mod labels;
pub mod predict;
pub mod ransac;
pub mod registration;
pub mod spectral;

pub use descriptors::{FpfhFlow, FpfhParams};
pub use jlinkage::{JLinkage, JLinkageParams};
pub use ransac::{SeqRansac, SeqRansacParams};
pub use registration::{
    EdParams, EmbeddedDeformation, IcpFlow, IcpParams, NearestFlow, Nrr, NrrParams,
};
pub use spectral::{Spectral, SpectralParams};

/// Every segmenter with its default parameters.
pub fn segmenters() -> Vec<Box<dyn pairs::Segmenter>> {
    vec![
        Box::new(SeqRansac::default()),
        Box::new(Spectral::default()),
        Box::new(JLinkage::default()),
    ]
}

/// Every method that estimates its own flow, with its default parameters: NRR (flow and
/// segments), then the flow methods (one segment each).
pub fn methods() -> Vec<Box<dyn pairs::Method>> {
    vec![
        Box::new(Nrr::default()),
        Box::new(NearestFlow),
        Box::new(IcpFlow::default()),
        Box::new(EmbeddedDeformation::default()),
        Box::new(FpfhFlow::default()),
    ]
}
