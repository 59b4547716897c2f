//! The network of Yi et al. 2018, "Deep Part Induction from Articulated Object Pairs", in
//! burn (the flex CPU backend by default; GPU backends are opt-in features).
//!
//! Its modules, by job (the paper's sections in brackets):
//!
//! - [`network`]: the network itself, [`network::PartInductionNet`] — the PointNet++
//!   building blocks, the correspondence proposal and flow modules (4.1, 4.2), the
//!   [`network::segmentation`] module (hypotheses, support, RPEN; 4.3), the single forward
//!   pass ([`network::predict`]), every size ([`network::config`]) and [`network::rng`], the
//!   one way to draw from burn's process-wide random number generator.
//! - [`train`] (5): the stage-wise trainer and its data-parallel step, with the pairs as
//!   tensors with their truth ([`train::batch`]), the losses and each stage's objective, the fixed
//!   validation set, the training config ([`train::config`]), checkpoints, the log, the
//!   loss plot and the mean of several checkpoints' weights ([`train::average`]).
//! - [`inference`] (4.4): the iterative procedure, the rotation search over 48 initial
//!   orientations, the release's per-segment sub-problems ([`inference::subproblems`]), hard labels by graph cut ([`inference::labels`]), and
//!   [`inference::method`], the network as the evaluator's method and segmenter.
//! - [`diagnose`]: where the network loses accuracy, by oracle substitution stage by
//!   stage (`model diagnose`).
//! - [`procedures`]: the iterative procedure's variants (the paper's, the authors'
//!   release's global alignments, per-segment sub-problems and full-Q matching) scored
//!   side by side (`model procedures`).
//! - [`weights`]: weights folders (`config.toml` and `model.bpk`), the one way trained
//!   weights are loaded and saved, checkpoint folders included.
//! - [`io`]: a user's PLY and OBJ files and the animated glTF.
//! - [`commands`]: the `model` binary's commands, arguments beside bodies.
//!
//! ```
//! use burn::prelude::*;
//! use model::network::pointnet::{SetAbstractionConfig, FeaturePropagation};
//! use model::network::rng;
//!
//! let device = Device::flex();
//! let xyz = rng::random(&device, 7, [1, 64, 3], burn::tensor::Distribution::Default);
//! let sa = SetAbstractionConfig::single(16, 0.4, 8, vec![32, 32]).init(0, false, &device);
//! let (centres, features) = sa.forward(xyz.clone(), None).expect("64 points");
//! assert_eq!(features.dims(), [1, 16, 32]);
//! let fp = FeaturePropagation::new(32, &[16], &device);
//! assert_eq!(fp.forward(xyz, centres, None, features).expect("3 neighbours").dims(), [1, 64, 16]);
//! ```
#![deny(missing_docs)]

pub mod commands;
pub mod diagnose;
pub mod inference;
pub mod io;
pub mod network;
pub mod procedures;
pub mod train;
pub mod weights;
