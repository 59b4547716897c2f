//! The network of the paper, [`PartInductionNet`] ([`net`]): correspondence proposal
//! ([`correspondence`], 4.1), flow ([`flow`], 4.2) and the [`segmentation`] module
//! (hypotheses, support, RPEN; 4.3), as one burn module with one forward per training stage;
//! [`predict`] is its single forward pass on a pair, on the clouds and subsets of [`input`].
//! Below them: [`sampling`] (farthest-point samples, ball neighbourhoods and 3-NN weights as
//! plain indices), [`mlp`] (shared MLPs: `Linear`, norm and ReLU layers, [`norm`] fusing
//! them into one operation when training on the CPU, with its kernel in [`fused`]),
//! [`pointnet`] (the PointNet++ layers that gather by those indices, [`pool`] their max pool),
//! the [`backbone`] they build, and [`rotation`], the differentiable projection onto
//! rotations. [`config`] holds every size; [`rng`] keeps seeded initialisation independent
//! of other threads.

pub mod backbone;
pub mod config;
pub mod correspondence;
pub mod flow;
pub mod fused;
pub mod input;
pub mod mlp;
pub mod net;
pub mod norm;
pub mod pointnet;
pub mod pool;
pub mod predict;
pub mod rng;
pub mod rotation;
pub mod sampling;
pub mod segmentation;

pub use net::{Detached, FlowOutput, NetModule, PartInductionNet, SegmentationOutput};
