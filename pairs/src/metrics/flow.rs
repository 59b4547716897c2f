//! Flow metrics: end-point error (EPE) and the percentage of correct correspondences (PCC)
//! under a distance threshold, as in the paper's Table 1 and Figure 7.

use super::{check_lengths, MetricError};
use crate::math::{Real, Vector3};

/// Spacing of the PCC thresholds, Q's normalised units.
pub const PCC_STEP: f64 = 0.005;
/// Number of PCC thresholds: 0, 0.005, ..., 0.25.
pub const PCC_THRESHOLDS: usize = 51;

/// Per point of P, the Euclidean norm of the flow error.
pub fn end_point_errors(predicted: &[Vector3], truth: &[Vector3]) -> Result<Vec<f64>, MetricError> {
    check_lengths("flow", predicted.len(), truth.len())?;
    if let Some(index) = predicted.iter().position(|v| !v.iter().all(|c| c.is_finite())) {
        return Err(MetricError::NotFinite { what: "flow", index });
    }
    Ok(predicted.iter().zip(truth).map(|(p, t)| f64::from((p - t).norm())).collect())
}

/// EPE of one pair: the mean over P's points of the flow error's norm.
pub fn epe(predicted: &[Vector3], truth: &[Vector3]) -> Result<f64, MetricError> {
    let errors = end_point_errors(predicted, truth)?;
    Ok(errors.iter().sum::<f64>() / errors.len() as f64)
}

/// The PCC curve of one pair: for each threshold `k * PCC_STEP`, the fraction of points whose
/// flow error is at most the threshold.
pub fn pcc(errors: &[f64]) -> [f64; PCC_THRESHOLDS] {
    let mut curve = [0.0; PCC_THRESHOLDS];
    if errors.is_empty() {
        return curve;
    }
    for (k, value) in curve.iter_mut().enumerate() {
        let threshold = k as f64 * PCC_STEP;
        *value = errors.iter().filter(|&&e| e <= threshold).count() as f64 / errors.len() as f64;
    }
    curve
}

/// The curve's value at `threshold` (rounded to the nearest step), e.g. 0.05 or 0.10.
pub fn pcc_at(curve: &[f64; PCC_THRESHOLDS], threshold: Real) -> f64 {
    let k = (f64::from(threshold) / PCC_STEP).round() as usize;
    curve[k.min(PCC_THRESHOLDS - 1)]
}

/// Normalised area under the curve over thresholds 0 to 0.25 (trapezoids), in [0, 1].
pub fn pcc_auc(curve: &[f64; PCC_THRESHOLDS]) -> f64 {
    let area: f64 = curve.windows(2).map(|w| 0.5 * (w[0] + w[1])).sum();
    area / (PCC_THRESHOLDS - 1) as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hand_computed_pair() {
        let truth = vec![Vector3::zeros(); 4];
        let predicted = vec![
            Vector3::zeros(),
            Vector3::new(0.03, 0.04, 0.0),
            Vector3::new(0.0, 0.09, 0.0),
            Vector3::new(0.0, 0.0, 1.0),
        ];
        let errors = end_point_errors(&predicted, &truth).expect("same length");
        assert!((epe(&predicted, &truth).expect("epe") - (0.05 + 0.09 + 1.0) / 4.0).abs() < 1e-7);
        // 0.05 in f32 lies just above 0.05: it counts from the next threshold on.
        let curve = pcc(&errors);
        assert_eq!(curve[0], 0.25);
        assert_eq!(pcc_at(&curve, 0.05), 0.25);
        assert_eq!(pcc_at(&curve, 0.055), 0.5);
        assert_eq!(pcc_at(&curve, 0.10), 0.75);
        assert_eq!(curve[PCC_THRESHOLDS - 1], 0.75);
        // Perfect flow has area 1; a flow off by more than 0.25 everywhere has area 0.
        assert_eq!(pcc_auc(&pcc(&[0.0; 3])), 1.0);
        assert_eq!(pcc_auc(&pcc(&[0.3; 3])), 0.0);
    }

    #[test]
    fn bad_inputs_are_named() {
        let one = vec![Vector3::zeros()];
        assert!(matches!(epe(&one, &[]), Err(MetricError::LengthMismatch { .. })));
        assert!(matches!(epe(&[], &[]), Err(MetricError::Empty("flow"))));
        let nan = vec![Vector3::new(Real::NAN, 0.0, 0.0)];
        assert_eq!(epe(&nan, &one), Err(MetricError::NotFinite { what: "flow", index: 0 }));
    }
}
