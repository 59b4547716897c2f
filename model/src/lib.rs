//! The network of Yi et al. 2018, "Deep Part Induction from Articulated Object Pairs", in
//! burn (the flex CPU backend by default; GPU backends are opt-in features).
//!
//! This first layer holds the PointNet++ building blocks every module of the paper is made
//! of: [`sampling`] computes farthest-point samples, ball neighbourhoods and 3-NN weights as
//! plain indices (no gradient), and [`pointnet`] turns them into differentiable layers
//! ([`pointnet::SharedMlp`], [`pointnet::SetAbstraction`], [`pointnet::FeaturePropagation`])
//! that group features by gather, so gradients flow to every point that was picked.
//! [`rotation`] projects matrices onto rotations differentiably, for the hypothesis
//! generator, and [`losses`] holds the paper's training losses as pure tensor functions.
//! [`norm`] runs a shared-MLP layer's bias, layer norm and ReLU as one operation with its
//! own backward pass when training on the CPU.
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
