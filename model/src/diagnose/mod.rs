//! Where the network loses accuracy, stage by stage, by oracle substitution (`model
//! diagnose`): every row replaces one stage's output with what a perfect or a classical
//! stage would give and scores the rest of the single pass on it.
//!
//! - **Flow floors**: the flow module's flow against the flows the matching alone implies
//!   (soft-argmax and argmax over Q's subset) and against the true flow sampled at a subset
//!   and interpolated back (what the subset size alone costs); the matching floor (every
//!   subset point of P sent to the point of Q's subset nearest its true end: no matching onto
//!   Q's subset can do better); the flow module fed that true matching (can it read
//!   offsets?); and the residual floor, the flow the module predicts where none is left (P
//!   moved by its true part motions, and Q against itself); and two passes, the module run
//!   again on P moved by its own flow and the two flows summed (does it refine itself?).
//! - **Segmentation on the true flow**: the support module's matrix, a threshold rule on the
//!   motion residual `‖R_i x_j + t_i − (x_j + f_j)‖ < τ` with the network's hypotheses or with
//!   a rigid or similarity fit per true part (exact hypotheses), and the true same-part
//!   matrix, each fed to the RPEN; the support IoU of the matrix and the IoU of the pass.
//! - **The subset ceiling**: the true labels on the segmentation and correspondence subsets,
//!   interpolated to every point (argmax, and the graph cut of
//!   [`segment_pair`](crate::inference::labels::segment_pair)).
//! - **The iterations** (`net-iter`), from the network's first pass and from the true
//!   labels (their ceiling), each scored on its final flow (the last pass's piecewise-rigid
//!   motion plus its residual flow) and on the piecewise-rigid flow of its final segments
//!   alone.
//! - **Scale**: the one scale of each pair's part motions, P's and Q's separate
//!   normalisations (a rotation cannot fit it; a similarity can).

pub mod report;
pub mod run;

pub use report::{DiagnoseError, DiagnoseParams, Diagnosis, Row, ScaleSummary};
pub use run::diagnose;
