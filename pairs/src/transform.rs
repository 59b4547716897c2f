//! Rigid and similarity motions, and the motion math every crate shares: weighted
//! Kabsch/Umeyama fits, rotation and axis errors, interpolation.

use nalgebra::{Matrix3 as Matrix3d, Vector3 as Vector3d};

use crate::cloud::Normalisation;
use crate::math::{Isometry3, Matrix3, Point3, Real, Rotation3, UnitQuaternion, Vector3};

/// A similarity `x -> scale * rotation * x + translation`.
///
/// Ground-truth part motions map P's normalised frame to Q's normalised frame; because the two
/// clouds are normalised separately, all parts of a pair share one `scale` (P's diagonal over
/// Q's diagonal).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Similarity {
    /// Rotation matrix (orthonormal, determinant +1).
    pub rotation: Matrix3,
    /// Translation, target frame units.
    pub translation: Vector3,
    /// Uniform scale, > 0.
    pub scale: Real,
}

impl Similarity {
    /// The identity motion.
    pub fn identity() -> Self {
        Self { rotation: Matrix3::identity(), translation: Vector3::zeros(), scale: 1.0 }
    }

    /// A rigid motion (scale 1) from an isometry.
    pub fn from_isometry(iso: &Isometry3) -> Self {
        Self {
            rotation: iso.rotation.to_rotation_matrix().into_inner(),
            translation: iso.translation.vector,
            scale: 1.0,
        }
    }

    /// The map between two normalised frames induced by a rigid motion of the object frame:
    /// `to.apply(rigid * from.invert(x))`, a similarity with scale `from.scale / to.scale`.
    pub fn between_normalised(rigid: &Isometry3, from: &Normalisation, to: &Normalisation) -> Self {
        let rotation = rigid.rotation.to_rotation_matrix().into_inner();
        let translation =
            (rotation * from.centre + rigid.translation.vector - to.centre) / to.scale;
        Self { rotation, translation, scale: from.scale / to.scale }
    }

    /// Applies the motion to a point.
    pub fn apply(&self, p: &Point3) -> Point3 {
        Point3::from(self.rotation * p.coords * self.scale + self.translation)
    }

    /// Applies the rotation (without scale or translation) to a direction.
    pub fn rotate(&self, v: &Vector3) -> Vector3 {
        self.rotation * v
    }

    /// The rotation as a unit quaternion (re-orthonormalised).
    pub fn quaternion(&self) -> UnitQuaternion {
        UnitQuaternion::from_matrix(&self.rotation)
    }

    /// Whether every parameter is finite.
    pub fn is_finite(&self) -> bool {
        self.rotation.iter().chain(self.translation.iter()).all(|v| v.is_finite())
            && self.scale.is_finite()
    }

    /// `self ∘ other`: the motion that applies `other`, then `self`.
    pub fn compose(&self, other: &Self) -> Self {
        Self {
            rotation: self.rotation * other.rotation,
            translation: self.rotation * other.translation * self.scale + self.translation,
            scale: self.scale * other.scale,
        }
    }

    /// The inverse motion, `y -> R^T (y - t) / scale` (the rotation taken as orthonormal).
    pub fn inverse(&self) -> Self {
        let rotation = self.rotation.transpose();
        Self {
            rotation,
            translation: -(rotation * self.translation) / self.scale,
            scale: 1.0 / self.scale,
        }
    }

    /// Largest deviation of `rotation` from an orthonormal matrix with determinant +1.
    pub fn rotation_defect(&self) -> Real {
        let gram = self.rotation.transpose() * self.rotation - Matrix3::identity();
        gram.amax().max((self.rotation.determinant() - 1.0).abs())
    }
}

/// The sums of a weighted Umeyama fit of `src` onto `dst`, in f64: the optimal rotation, the
/// weighted means, and the scale's numerator and denominator. Callers that share one scale
/// between several fits (e.g. all parts of a pair) add the numerators and denominators.
#[derive(Debug, Clone, PartialEq)]
pub struct UmeyamaFit {
    /// The optimal rotation (reflection corrected).
    pub rotation: Matrix3d<f64>,
    /// Weighted mean of `src`.
    pub mean_src: Vector3d<f64>,
    /// Weighted mean of `dst`.
    pub mean_dst: Vector3d<f64>,
    /// `Σ σ_i d_i` of the weighted cross-covariance (the optimal scale's numerator).
    pub trace: f64,
    /// `Σ w |src - mean_src|²` (the optimal scale's denominator).
    pub variance: f64,
}

impl UmeyamaFit {
    /// Fits the weighted sums; `None` when the inputs differ in length or are empty, the
    /// weights (negative ones count as zero) sum to zero, or any input is non-finite.
    pub fn new(src: &[Point3], dst: &[Point3], weights: &[Real]) -> Option<Self> {
        if src.len() != dst.len() || src.len() != weights.len() || src.is_empty() {
            return None;
        }
        let wsum: f64 = weights.iter().map(|&w| f64::from(w.max(0.0))).sum();
        if !(wsum > 0.0 && wsum.is_finite()) {
            return None;
        }
        let to64 = |p: &Point3| Vector3d::new(f64::from(p.x), f64::from(p.y), f64::from(p.z));
        let (mut mean_src, mut mean_dst) = (Vector3d::zeros(), Vector3d::zeros());
        for ((s, d), &w) in src.iter().zip(dst).zip(weights) {
            let w = f64::from(w.max(0.0));
            mean_src += to64(s) * w;
            mean_dst += to64(d) * w;
        }
        mean_src /= wsum;
        mean_dst /= wsum;
        let (mut cov, mut variance) = (Matrix3d::zeros(), 0.0);
        for ((s, d), &w) in src.iter().zip(dst).zip(weights) {
            let w = f64::from(w.max(0.0));
            let (cs, cd) = (to64(s) - mean_src, to64(d) - mean_dst);
            cov += cd * cs.transpose() * w;
            variance += cs.norm_squared() * w;
        }
        if !cov.iter().all(|v| v.is_finite()) {
            return None;
        }
        let svd = cov.svd(true, true);
        let (u, v_t) = (svd.u?, svd.v_t?);
        // Reflection correction: flip the weakest singular direction when det(U V^T) < 0.
        let mut d = Matrix3d::identity();
        if (u * v_t).determinant() < 0.0 {
            d[(2, 2)] = -1.0;
        }
        let trace = svd.singular_values.component_mul(&d.diagonal()).sum();
        Some(Self { rotation: u * d * v_t, mean_src, mean_dst, trace, variance })
    }

    /// The similarity with this fit's rotation and the given `scale`.
    pub fn with_scale(&self, scale: f64) -> Similarity {
        Similarity {
            rotation: self.rotation.cast::<Real>(),
            translation: (self.mean_dst - self.rotation * self.mean_src * scale).cast::<Real>(),
            scale: scale as Real,
        }
    }

    /// The optimal scale of this fit alone (1 when degenerate).
    pub fn scale(&self) -> f64 {
        if self.variance > 0.0 {
            self.trace / self.variance
        } else {
            1.0
        }
    }
}

/// Fits the similarity (or, with `with_scale = false`, the rigid motion) that best maps `src`
/// onto `dst` in the weighted least-squares sense (Umeyama 1991; Kabsch without scale).
///
/// Returns `None` when the inputs differ in length, the weights sum to zero, or any input is
/// non-finite. Degenerate configurations (fewer than three non-collinear points) give one of
/// the optimal motions. Computed in f64 for accuracy.
pub fn fit_similarity_weighted(
    src: &[Point3],
    dst: &[Point3],
    weights: &[Real],
    with_scale: bool,
) -> Option<Similarity> {
    let fit = UmeyamaFit::new(src, dst, weights)?;
    Some(fit.with_scale(if with_scale { fit.scale() } else { 1.0 }))
}

/// Angle in degrees of the rotation that takes `a` to `b` (the geodesic distance on SO(3)).
pub fn rotation_error_deg(a: &Matrix3, b: &Matrix3) -> Real {
    // ||A - B||_F = 2 sqrt(2) sin(θ / 2): unlike acos((tr(AᵀB) - 1) / 2), exact near θ = 0,
    // where the trace form loses the angle to f32 rounding (0.03° for identical matrices).
    let chord = (a - b).norm() / (2.0 * std::f32::consts::SQRT_2);
    (2.0 * chord.clamp(0.0, 1.0).asin()).to_degrees()
}

/// Angle in degrees between two axes taken as lines (direction sign ignored): 0 to 90.
pub fn axis_error_deg(a: &Vector3, b: &Vector3) -> Real {
    let (na, nb) = (a.norm(), b.norm());
    if na == 0.0 || nb == 0.0 {
        return 90.0;
    }
    (a.dot(b).abs() / (na * nb)).clamp(0.0, 1.0).acos().to_degrees()
}

/// Rotation angle in degrees of a rotation matrix (0 to 180).
pub fn rotation_angle_deg(r: &Matrix3) -> Real {
    rotation_error_deg(&Matrix3::identity(), r)
}

/// Interpolates between two rigid motions at `t` in `[0, 1]`: the rotation along the
/// geodesic (slerp) and the translation linearly.
pub fn interpolate_rigid(a: &Isometry3, b: &Isometry3, t: Real) -> Isometry3 {
    a.lerp_slerp(b, t)
}

/// A rotation about a unit axis through a pivot, as an isometry.
pub fn rotation_about(pivot: &Point3, axis: &Vector3, angle: Real) -> Isometry3 {
    // A zero axis has no rotation about it: the identity.
    let rot = Rotation3::new(crate::math::unit_or(axis, Vector3::zeros()) * angle);
    let translation = pivot.coords - rot * pivot.coords;
    Isometry3::from_parts(translation.into(), rot.into())
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn arb_point() -> impl Strategy<Value = Point3> {
        (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0).prop_map(|(x, y, z)| Point3::new(x, y, z))
    }

    proptest! {
        #[test]
        fn fit_recovers_a_planted_similarity(
            pts in proptest::collection::vec(arb_point(), 8..40),
            axis in (-1.0f32..1.0, -1.0f32..1.0, 0.1f32..1.0),
            angle in -3.0f32..3.0,
            t in arb_point(),
            scale in 0.5f32..2.0,
        ) {
            let rot = Rotation3::new(crate::math::unit_or(&Vector3::new(axis.0, axis.1, axis.2), Vector3::z()) * angle);
            let truth = Similarity { rotation: rot.into_inner(), translation: t.coords, scale };
            let dst: Vec<_> = pts.iter().map(|p| truth.apply(p)).collect();
            let w = vec![1.0; pts.len()];
            let fit = fit_similarity_weighted(&pts, &dst, &w, true).expect("well posed");
            for (p, q) in pts.iter().zip(&dst) {
                prop_assert!((fit.apply(p) - q).norm() < 1e-3);
            }
            prop_assert!(fit.rotation_defect() < 1e-4);
        }

        #[test]
        fn rigid_motion_preserves_distances(a in arb_point(), b in arb_point(), angle in -3.0f32..3.0) {
            let m = Similarity::from_isometry(&rotation_about(&Point3::new(0.3, 0.1, 0.0), &Vector3::z(), angle));
            prop_assert!(((m.apply(&a) - m.apply(&b)).norm() - (a - b).norm()).abs() < 1e-5);
        }
    }

    #[test]
    fn normalised_motion_commutes_with_normalisation() {
        let rigid = rotation_about(&Point3::new(0.2, 0.0, 1.0), &Vector3::y(), 0.7);
        let from = Normalisation { centre: Vector3::new(1.0, 2.0, 3.0), scale: 2.5 };
        let to = Normalisation { centre: Vector3::new(-1.0, 0.5, 0.0), scale: 1.5 };
        let m = Similarity::between_normalised(&rigid, &from, &to);
        let x = Point3::new(0.3, -0.2, 0.1);
        let expected = to.apply(&(rigid * from.invert(&x)));
        assert!((m.apply(&x) - expected).norm() < 1e-5);
    }

    #[test]
    fn weights_ignore_outliers() {
        let src = [
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.0, 1.0, 0.0),
            Point3::new(0.0, 0.0, 1.0),
            Point3::new(5.0, 5.0, 5.0),
        ];
        let mut dst: Vec<_> = src.iter().map(|p| p + Vector3::new(1.0, 2.0, 3.0)).collect();
        dst[4] = Point3::new(-9.0, 0.0, 0.0);
        let fit = fit_similarity_weighted(&src, &dst, &[1.0, 1.0, 1.0, 1.0, 0.0], false)
            .expect("well posed");
        assert!((fit.translation - Vector3::new(1.0, 2.0, 3.0)).norm() < 1e-5);
        assert!(rotation_angle_deg(&fit.rotation) < 1e-2);
    }

    #[test]
    fn fit_rejects_bad_input() {
        let p = [Point3::origin()];
        assert!(fit_similarity_weighted(&p, &p, &[0.0], false).is_none());
        assert!(fit_similarity_weighted(&p, &[], &[1.0], false).is_none());
        let nan = [Point3::new(f32::NAN, 0.0, 0.0)];
        assert!(fit_similarity_weighted(&nan, &p, &[1.0], false).is_none());
    }

    #[test]
    fn angle_errors_on_hand_computed_cases() {
        let r90 = Rotation3::new(Vector3::z() * std::f32::consts::FRAC_PI_2).into_inner();
        assert!((rotation_error_deg(&Matrix3::identity(), &r90) - 90.0).abs() < 1e-3);
        assert!((axis_error_deg(&Vector3::x(), &-Vector3::x())).abs() < 1e-3);
        assert!((axis_error_deg(&Vector3::x(), &Vector3::new(1.0, 1.0, 0.0)) - 45.0).abs() < 1e-3);
    }

    #[test]
    fn interpolation_hits_endpoints_and_midpoint() {
        let a = Isometry3::identity();
        let b = rotation_about(&Point3::origin(), &Vector3::z(), 1.0);
        let mid = interpolate_rigid(&a, &b, 0.5);
        assert!((mid.rotation.angle() - 0.5).abs() < 1e-5);
        assert!(interpolate_rigid(&a, &b, 1.0).rotation.angle_to(&b.rotation) < 1e-5);
    }
}
