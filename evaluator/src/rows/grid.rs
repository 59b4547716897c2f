//! The parameters a row exposes for tuning: a [`Grid`] of [`Axis`] values and the runner
//! of each grid point. [`crate::tuning`] sweeps it on the validation sets.

use std::sync::Arc;

use crate::rows::runner::Runner;

/// One swept parameter: its name, its starting values (ascending) and how it widens.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// The parameter's field name (`inlier_threshold`).
    pub name: &'static str,
    /// Starting values, ascending.
    pub values: Vec<f64>,
    /// Ratio between a widened value and the edge value it extends.
    pub factor: f64,
    /// Smallest value widening may add.
    pub lower: f64,
    /// Largest value widening may add.
    pub upper: f64,
}

impl Axis {
    /// An axis of `values` widened by `factor` within `[lower, upper]`.
    pub fn new(name: &'static str, values: &[f64], factor: f64, lower: f64, upper: f64) -> Self {
        Self { name, values: values.to_vec(), factor, lower, upper }
    }
}

/// Makes a row's runner for one point of the grid (values in axis order) and that runner's
/// fingerprint (its parameters).
pub type Build = dyn Fn(&[f64]) -> (Runner, String) + Send + Sync;

/// A row's parameter grid.
#[derive(Clone)]
pub struct Grid {
    /// The swept axes.
    pub axes: Vec<Axis>,
    /// The runner of a grid point.
    pub build: Arc<Build>,
    /// Widening rounds at most.
    pub max_rounds: usize,
}

impl std::fmt::Debug for Grid {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Grid")
            .field("axes", &self.axes)
            .field("max_rounds", &self.max_rounds)
            .finish()
    }
}

impl Grid {
    /// A grid over `axes` whose points `build` makes, widened at most three times.
    pub fn new(
        axes: Vec<Axis>,
        build: impl Fn(&[f64]) -> (Runner, String) + Send + Sync + 'static,
    ) -> Self {
        Self { axes, build: Arc::new(build), max_rounds: 3 }
    }

    /// What identifies the grid: its axes and the fingerprint of its first point (the
    /// method's fixed parameters and code).
    pub fn fingerprint(&self) -> String {
        let first: Vec<f64> = self.axes.iter().map(|a| a.values[0]).collect();
        format!("{:?} {}", self.axes, (self.build)(&first).1)
    }
}
