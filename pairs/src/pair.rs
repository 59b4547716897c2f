//! The pair record: two clouds ([`PairInput`]), their ground truth and their provenance,
//! checked when built ([`Pair::new`]).

use crate::error::PairError;
use crate::ground_truth::GroundTruth;
pub use crate::input::{PairInput, PairKind, Pose, Provenance};
use crate::scan::Scans;
use crate::validate;

/// A pair with its ground truth; constructed only through [`Pair::new`], which validates it.
#[derive(Debug, Clone, PartialEq)]
pub struct Pair {
    input: PairInput,
    truth: GroundTruth,
    provenance: Provenance,
    scans: Scans,
}

impl Pair {
    /// Builds a pair, checking every invariant of DESIGN.md (shapes agree, values finite,
    /// ids in range, correspondences consistent, flow equal to the part motions).
    pub fn new(
        input: PairInput,
        truth: GroundTruth,
        provenance: Provenance,
    ) -> Result<Self, PairError> {
        validate::pair(&input, &truth)?;
        validate::provenance(&input.id, &provenance)?;
        Ok(Self { input, truth, provenance, scans: Scans::default() })
    }

    /// The pair with the camera records of its scanned sides, checked (finite, positive
    /// intrinsics, a rotation in the extrinsics, a positive depth scale).
    pub fn with_scans(mut self, scans: Scans) -> Result<Self, PairError> {
        validate::scans(&self.input.id, &scans)?;
        self.scans = scans;
        Ok(self)
    }

    /// How the scanned sides were captured; both `None` for full shapes.
    pub fn scans(&self) -> &Scans {
        &self.scans
    }

    /// The pair without its ground truth, for methods.
    pub fn input(&self) -> &PairInput {
        &self.input
    }

    /// The ground truth.
    pub fn truth(&self) -> &GroundTruth {
        &self.truth
    }

    /// Where the pair came from.
    pub fn provenance(&self) -> &Provenance {
        &self.provenance
    }

    /// The pair's id.
    pub fn id(&self) -> &str {
        &self.input.id
    }

    /// Splits the pair into its parts.
    pub fn into_parts(self) -> (PairInput, GroundTruth, Provenance) {
        (self.input, self.truth, self.provenance)
    }
}
