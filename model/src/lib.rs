//! The network of Yi et al. 2018, "Deep Part Induction from Articulated Object Pairs", in
//! burn (the flex CPU backend by default; GPU backends are opt-in features).
//!
//! Its modules, by job (the paper's sections in brackets):
//!
//! - **The network.** [`sampling`] (farthest-point samples, ball neighbourhoods and 3-NN
//!   weights as plain indices) and [`pointnet`] (the PointNet++ layers that gather by those
//!   indices, [`norm`] fusing a layer's bias, layer norm and ReLU when training on the CPU)
//!   build the [`backbone`]; [`correspondence`] and [`flow`] are the correspondence proposal
//!   and flow modules (4.1, 4.2), [`hypotheses`], [`support`] and [`rpen`] the
//!   segmentation module's hypothesis generation, verification and recurrent proposal
//!   network (4.3), [`rotation`] their differentiable projection onto rotations;
//!   [`network`] puts them together as `PartNet`, and [`predict`] is its single forward
//!   pass. [`config`] holds every size.
//! - **Training** (5). [`batch`] (pairs to tensors, the ground truth on the subsets), [`losses`]
//!   and [`objective`] (each stage's terms and weights), [`train`] (the stage-wise trainer
//!   and its data-parallel step), [`validation`] (the fixed validation set and its scores),
//!   [`checkpoint`], [`log`] and [`plot`] (what a run writes).
//! - **Inference.** [`inference`] (the iterative procedure, 4.4), [`rotation_search`] (the
//!   48 initial orientations), [`labels`] (hard labels by graph cut, fragment merging,
//!   per-segment motions, Q's labels), and [`method`], the network as the evaluator's
//!   method and segmenter.
//! - **Applications and files.** [`apps`] (what `model infer` and `model animate` do),
//!   [`pointfile`] (a user's PLY and OBJ files) and [`animation`] (the animated glTF).
//!
//! ```
//! use burn::prelude::*;
//! use model::pointnet::{SetAbstractionConfig, FeaturePropagation};
//!
//! let device = Device::flex();
//! let xyz = Tensor::<3>::random([1, 64, 3], burn::tensor::Distribution::Default, &device);
//! let sa = SetAbstractionConfig::single(16, 0.4, 8, vec![32, 32]).init(0, &device);
//! let (centres, features) = sa.forward(xyz.clone(), None).expect("64 points");
//! assert_eq!(features.dims(), [1, 16, 32]);
//! let fp = FeaturePropagation::new(32, &[16], &device);
//! assert_eq!(fp.forward(xyz, centres, None, features).expect("3 neighbours").dims(), [1, 64, 16]);
//! ```
#![deny(missing_docs)]

pub mod animation;
pub mod apps;
pub mod backbone;
pub mod batch;
pub mod checkpoint;
pub mod config;
pub mod correspondence;
pub mod flow;
pub mod hypotheses;
pub mod inference;
pub mod labels;
pub mod log;
pub mod losses;
pub mod method;
pub mod network;
pub mod norm;
pub mod objective;
pub mod plot;
pub mod pointfile;
pub mod pointnet;
pub mod predict;
pub mod rotation;
pub mod rotation_search;
pub mod rpen;
pub mod sampling;
pub mod support;
pub mod train;
pub mod validation;
