//! The inference procedure's parameters: the single pass (`net`) and the iterative
//! refinement (`net-iter`).

use pairs::math::Real;

use crate::inference::labels::HardLabelParams;

/// Parameters of the inference procedure.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InferenceParams {
    /// The hard-label step's parameters.
    pub labels: HardLabelParams,
    /// Most passes, the first included (paper: 10; 1 is the single pass).
    pub max_iterations: usize,
    /// Stop when the mean change of the flow between two passes is below this (normalised
    /// units: the clouds' bounding-box diagonals are 1).
    pub tolerance: Real,
    /// Also stop when the mean residual flow shrank by less than this fraction since the
    /// previous pass: the alignment has stopped improving (the paper iterates "until the
    /// total magnitude of the deformation flow field is minimized"). With the shipped
    /// weights the residual levels off after about 5 passes (0.068, 0.020, 0.016, 0.015,
    /// 0.014 on SF2F), where EPE does too.
    pub min_residual_decrease: Real,
    /// Search 48 rotations of P for the initial orientation (paper: when the pair's
    /// orientations are inconsistent; off by default).
    pub rotation_search: bool,
    /// Subtract the network's flow on (Q, Q) (at each point's nearest point of Q) from
    /// every predicted flow. A departure from the paper: a network should predict no flow
    /// between identical clouds, but the shipped weights predict a mean flow of about 0.02
    /// there, which the iteration would add again on every pass; with the correction, the
    /// procedure's fixed point is P' = Q.
    pub calibrate: bool,
    /// Global alignments before the first pass (the authors' release: 2; 0 by default, the
    /// paper's procedure): each predicts the flow of P' (P to begin with), fits one rigid
    /// motion to it (Kabsch) and moves P' by it, so that the passes start from a P' already
    /// aligned with Q as a whole. Not yet measured against the default on the validation
    /// sets.
    pub global_alignments: usize,
    /// Refine by per-segment sub-problems (the authors' release; off by default, the
    /// paper's procedure): every pass after the first runs the correspondence and flow
    /// modules on one sub-pair per segment of the previous pass, cut within a geodesic
    /// radius of the segment (0.2, then 0.15, then 0.1), instead of on the whole deformed
    /// pair ([`subproblems`]), each sub-pair's residual calibrated like the whole pair's.
    /// Every pass runs (`max_iterations`: 1 + 9 in the release), without the stop rules.
    pub sub_problems: bool,
    /// End on Q (the release's `ISFULL_MATCHING`, for full Q only): the last pass's flow
    /// is moved to the nearest point of Q and segmented again. Applies to SF2F pairs;
    /// a scanned Q is left alone (its points do not cover P's moved surface).
    pub full_matching: bool,
}

impl Default for InferenceParams {
    fn default() -> Self {
        Self::iterative()
    }
}

impl InferenceParams {
    /// The paper's iterative procedure: up to 10 passes, tolerance 1e-3, a residual that
    /// shrinks by at least 5% per pass, no rotation search, calibrated flows.
    pub fn iterative() -> Self {
        Self {
            labels: HardLabelParams::default(),
            max_iterations: 10,
            tolerance: 1e-3,
            min_residual_decrease: 0.05,
            rotation_search: false,
            calibrate: true,
            global_alignments: 0,
            sub_problems: false,
            full_matching: false,
        }
    }

    /// One pass only (the `net` row).
    pub fn single_pass() -> Self {
        Self { max_iterations: 1, ..Self::iterative() }
    }
}
