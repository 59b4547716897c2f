//! Geometry shared by every baseline: nearest-neighbour queries, local-PCA normals, motion
//! fits of samples, per-pair seeding and sampling, and input checks.

pub mod input;
pub mod motion;
pub mod neighbours;
pub mod normals;
pub mod sampling;

pub use input::{check_flow, check_pair, check_prediction, InputError};
pub use motion::{
    assign_by_residual, fit_motion_indices, fit_motion_sample, fit_motion_svd, fit_motion_trimmed,
    moved_points, residual, SCALE_RANGE,
};
pub use neighbours::Neighbours;
pub use normals::estimate_normals_pca;
pub use sampling::{sample_farthest_points, sample_local_triplet, seed_for_pair};
