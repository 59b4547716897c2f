//! The boards and reports written from the cached runs: the CSV leaderboards, the PCC
//! plots, the segmentation gallery, the iteration table and `LEADERBOARD.md`.

pub mod gallery;
pub mod iterations;
pub mod leaderboard;
pub mod paper;
pub mod plots;
pub mod render_joints;
pub mod report;
pub mod sets;
