//! Small dense least-squares machinery for the deformation solvers: normal equations
//! accumulated from sparse residual rows, and the Procrustes rotation of a covariance.

use faer::linalg::solvers::Solve;
use nalgebra::{DMatrix, DVector, Matrix3};

/// `J^T W J` and `J^T W r` of a least-squares problem, built row by row.
#[derive(Debug, Clone, PartialEq)]
pub struct NormalEquations {
    /// `J^T W J`.
    pub jtj: DMatrix<f64>,
    /// `J^T W r`.
    pub jtr: DVector<f64>,
}

impl NormalEquations {
    /// Empty equations in `unknowns` unknowns.
    pub fn new(unknowns: usize) -> Self {
        Self { jtj: DMatrix::zeros(unknowns, unknowns), jtr: DVector::zeros(unknowns) }
    }

    /// Adds the residual `r` whose gradient is the sparse row `row` (column, value), with
    /// weight `weight`.
    pub fn add(&mut self, row: &[(usize, f64)], r: f64, weight: f64) {
        for &(a, va) in row {
            self.jtr[a] += weight * va * r;
            for &(b, vb) in row {
                self.jtj[(a, b)] += weight * va * vb;
            }
        }
    }

    /// The Gauss-Newton step `-(J^T W J + damping I)^-1 J^T W r`, or `None` when the system
    /// is singular or the step is not finite.
    ///
    /// The Cholesky factorisation is faer's (blocked and vectorised; with the 576 unknowns
    /// of the ED baseline's 48 nodes it is several times faster than nalgebra's), run
    /// sequentially (faer is built without rayon), so the step does not depend on the
    /// thread count. Only the lower triangle of `J^T W J` is read.
    pub fn step(&self, damping: f64) -> Option<DVector<f64>> {
        let n = self.jtr.len();
        let system =
            faer::Mat::from_fn(n, n, |i, j| self.jtj[(i, j)] + if i == j { damping } else { 0.0 });
        let llt = system.llt(faer::Side::Lower).ok()?;
        let rhs = faer::Col::from_fn(n, |i| self.jtr[i]);
        let solution = llt.solve(&rhs);
        let step = DVector::from_fn(n, |i, _| -solution[i]);
        step.iter().all(|v| v.is_finite()).then_some(step)
    }
}

/// The rotation `R` maximising `trace(R^T cov)`, i.e. the best rotation taking the sources
/// onto the targets of `cov = sum w * target * source^T` (Kabsch, reflection corrected);
/// identity for a non-finite covariance.
pub fn rotation_procrustes(cov: &Matrix3<f64>) -> Matrix3<f64> {
    if !cov.iter().all(|v| v.is_finite()) {
        return Matrix3::identity();
    }
    let svd = cov.svd(true, true);
    let (Some(u), Some(v_t)) = (svd.u, svd.v_t) else { return Matrix3::identity() };
    let mut d = Matrix3::identity();
    if (u * v_t).determinant() < 0.0 {
        d[(2, 2)] = -1.0;
    }
    u * d * v_t
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Rotation3, Vector3};

    #[test]
    fn normal_equations_solve_a_line_fit() {
        // Fit y = a x + b to three points on y = 2x + 1: residual a x + b - y.
        let mut eq = NormalEquations::new(2);
        for x in [0.0, 1.0, 2.0] {
            eq.add(&[(0, x), (1, 1.0)], -(2.0 * x + 1.0), 1.0);
        }
        let step = eq.step(0.0).expect("well posed");
        assert!((step[0] - 2.0).abs() < 1e-9 && (step[1] - 1.0).abs() < 1e-9);
    }

    #[test]
    fn a_singular_system_has_no_step_until_damped() {
        // One residual in two unknowns: J^T J = [[1, 1], [1, 1]] has rank 1.
        let mut eq = NormalEquations::new(2);
        eq.add(&[(0, 1.0), (1, 1.0)], 1.0, 1.0);
        assert_eq!(eq.step(0.0), None);
        // Damped, the step is the minimum-norm direction: -(J^T J + d I)^-1 J^T r.
        let step = eq.step(1.0).expect("damped system is positive definite");
        let expected = -1.0 / 3.0;
        assert!((step[0] - expected).abs() < 1e-12 && (step[1] - expected).abs() < 1e-12);
    }

    #[test]
    fn procrustes_recovers_a_rotation() {
        let r = Rotation3::new(Vector3::new(0.3, -0.2, 0.9)).into_inner();
        let sources = [Vector3::x(), Vector3::y(), Vector3::new(0.2, 0.1, 1.0)];
        let cov = sources.iter().fold(Matrix3::zeros(), |acc, s| acc + (r * s) * s.transpose());
        assert!((rotation_procrustes(&cov) - r).norm() < 1e-9);
        assert_eq!(rotation_procrustes(&Matrix3::from_element(f64::NAN)), Matrix3::identity());
    }
}
