//! The shared data model of articulated part induction.
//!
//! The central type is [`Pair`]: a source cloud P and a target cloud Q ([`PairInput`], what
//! a method may see), with their [`GroundTruth`] (part ids, per-part [`Similarity`] motions,
//! flow, correspondences, joints) and their [`Provenance`]. Every [`Cloud`] is normalised on
//! its own (bounding box centred at the origin, diagonal 1) and keeps its [`Normalisation`].
//! A [`Method`] maps a [`PairInput`] to a [`Prediction`]. The [`transform`] module holds the
//! motion math every crate shares, and [`dataset`] reads and writes dataset folders
//! (`pairs.mcap`, `index.csv`, `manifest.json`; see docs/FORMAT.md), and [`predictions`]
//! reads and writes one method's predictions for a dataset (`predictions.mcap`). Every file
//! any crate writes goes through [`atomic`]: whole or not at all. [`sampling`] holds the one
//! farthest point sampling and the one area-weighted surface sampler every crate uses.
//!
//! ```
//! use pairs::{synthetic, Pair};
//!
//! // A two-part hinge whose second part turns by 0.5 rad between P and Q.
//! let pair: Pair = synthetic::hinge_pair("demo", 4, 0.5);
//! let (input, truth) = (pair.input(), pair.truth());
//! assert_eq!(truth.num_parts(), 2);
//! // Ground truth maps every point of P onto its correspondence in Q.
//! for (i, p) in input.p.points.iter().enumerate() {
//!     let moved = truth.motions[truth.part_p[i] as usize].apply(p);
//!     let target = input.q.points[truth.corr_index[i] as usize];
//!     assert!((moved - target).norm() < 1e-5);
//! }
//! // Rebuilding it with a broken field is refused, naming the pair and the field.
//! let (input, mut truth, provenance) = pair.into_parts();
//! truth.part_q.pop();
//! let err = Pair::new(input, truth, provenance).unwrap_err();
//! assert!(err.to_string().contains("part_q"));
//! ```
#![deny(missing_docs)]

pub mod atomic;
pub mod cloud;
pub mod dataset;
pub mod error;
pub mod fuzz;
pub mod ground_truth;
pub mod input;
pub mod joint_estimate;
pub mod joints;
pub mod math;
pub mod mcap_files;
pub mod method;
pub mod metrics;
pub mod pair;
pub mod parts;
pub mod predictions;
pub mod renders;
pub mod sampling;
pub mod scan;
pub mod screw;
pub mod segments;
pub mod set;
pub mod set_method;
pub mod synthetic;
pub mod transform;
mod validate;

pub use cloud::{Cloud, Normalisation};
pub use error::{DatasetError, PairError, PredictionsError, SetError};
pub use ground_truth::GroundTruth;
pub use input::{PairInput, PairKind, Pose, Provenance};
pub use joints::{JointKind, JointTruth};
pub use method::{Method, MethodError, Prediction, Segmenter};
pub use pair::Pair;
pub use parts::{PartId, SegmentId};
pub use scan::{Intrinsics, Scan, Scans};
pub use set::{Set, SetInput, SetMode, SetTruth, View, ViewKind};
pub use set_method::{lift_pairs, PairsToSet, SetMethod, SetPrediction};
pub use transform::Similarity;
