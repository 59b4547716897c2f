//! Settings of the importers that change the objects they make (so they go into the
//! generator config and the manifest).

use std::path::PathBuf;

use serde::{Deserialize, Serialize};

/// How assets are read.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ImportOptions {
    /// Range given to joints without limits (URDF `continuous`, sidecar `continuous`),
    /// degrees, lower then upper.
    pub continuous_range_deg: [f64; 2],
    /// Folders searched for URDF mesh files: `package://name/rest` is tried as
    /// `<folder>/name/rest` and `<folder>/rest` for each folder here, then for the URDF's
    /// folder and its parent; a relative path is tried against the URDF's folder first.
    pub package_paths: Vec<PathBuf>,
}

impl Default for ImportOptions {
    fn default() -> Self {
        Self { continuous_range_deg: [-180.0, 180.0], package_paths: Vec::new() }
    }
}

impl ImportOptions {
    /// The continuous range in radians, or why it is unusable.
    pub fn continuous_range(&self) -> Result<(f64, f64), String> {
        let [lo, hi] = self.continuous_range_deg;
        if !(lo.is_finite() && hi.is_finite() && lo < hi) {
            return Err(format!("continuous_range_deg [{lo}, {hi}] must be finite and increasing"));
        }
        Ok((lo.to_radians(), hi.to_radians()))
    }
}
