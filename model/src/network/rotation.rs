//! Differentiable projection of 3x3 matrices onto rotations, for the hypothesis generator's
//! residual parameterisation `R = R̂ + I` (the paper projects with an SVD; SVD has no
//! stable gradient for near-equal singular values, so this uses Newton–Schulz iterations
//! for the orthogonal polar factor, which are plain matrix products).

use burn::prelude::*;
use burn::tensor::TensorData;

/// Newton–Schulz iterations used by default: enough for a singular value of 0.001 (after
/// scaling) to reach 1 within f32 precision.
pub const ITERATIONS: usize = 24;

/// The orthogonal polar factor of each matrix (its nearest orthogonal matrix), with the
/// matrix first negated where its determinant is negative so that every result is a proper
/// rotation (determinant +1). For the residual parameterisation near the identity the
/// determinant is positive and the result is the nearest rotation.
///
/// # Shapes
/// `[batch, 3, 3]` -> `[batch, 3, 3]`
pub fn project_to_rotation(matrices: Tensor<3>, iterations: usize) -> Tensor<3> {
    let [batch, _, _] = matrices.dims();
    let device = matrices.device();
    let values: Vec<f32> =
        matrices.to_data().convert::<f32>().try_to_vec().expect("float data converts to f32");
    // The sign needs no gradient: it is piecewise constant.
    let signs: Vec<f32> =
        values.chunks_exact(9).map(|m| if determinant(m) < 0.0 { -1.0 } else { 1.0 }).collect();
    let signs = Tensor::<3>::from_data(TensorData::new(signs, [batch, 1, 1]), &device);
    let m = matrices * signs;
    // Scaling by the Frobenius norm puts every singular value in (0, 1], inside the
    // iteration's basin of convergence (0, sqrt 3).
    let norm = (m.clone() * m.clone()).sum_dim(1).sum_dim(2).sqrt() + 1e-12; // [batch, 1, 1]
    let identity = Tensor::<2>::eye(3, &device).unsqueeze_dim::<3>(0) * 3.0; // [1, 3, 3]
    let mut x = m / norm;
    for _ in 0..iterations {
        let gram = x.clone().swap_dims(1, 2).matmul(x.clone()); // [batch, 3, 3]
        x = x.matmul(identity.clone() - gram) * 0.5;
    }
    x
}

/// Determinant of a row-major 3x3 matrix.
fn determinant(m: &[f32]) -> f32 {
    m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6])
        + m[2] * (m[3] * m[7] - m[4] * m[6])
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    fn random_matrices(batch: usize, seed: u64) -> Vec<f32> {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        (0..batch * 9).map(|_| rng.random_range(-1.0f32..1.0)).collect()
    }

    fn values(t: Tensor<3>) -> Vec<f32> {
        t.into_data().convert::<f32>().try_to_vec().expect("f32")
    }

    #[test]
    fn results_are_rotations_and_the_nearest_one() {
        let device = Device::flex();
        let batch = 32;
        let input = random_matrices(batch, 7);
        let out = values(project_to_rotation(
            Tensor::from_data(TensorData::new(input.clone(), [batch, 3, 3]), &device),
            ITERATIONS,
        ));
        for (m, r) in input.chunks_exact(9).zip(out.chunks_exact(9)) {
            let r = nalgebra::Matrix3::from_row_slice(r);
            assert!((r.transpose() * r - nalgebra::Matrix3::identity()).amax() < 1e-4, "{r}");
            assert!((r.determinant() - 1.0).abs() < 1e-4);
            let m = nalgebra::Matrix3::from_row_slice(m);
            if m.determinant() > 0.0 && m.singular_values().min() > 0.05 {
                let svd = m.svd(true, true);
                let nearest = svd.u.expect("u") * svd.v_t.expect("v");
                assert!((nearest - r).amax() < 1e-3, "{nearest} vs {r}");
            }
        }
    }

    #[test]
    fn gradients_match_finite_differences() {
        let device = Device::flex().autodiff();
        // A well-conditioned input near the identity, as R̂ + I is.
        let base: Vec<f32> = random_matrices(1, 3)
            .iter()
            .enumerate()
            .map(|(i, v)| v * 0.3 + if i % 4 == 0 { 1.0 } else { 0.0 })
            .collect();
        let weights =
            Tensor::<3>::from_data(TensorData::new(random_matrices(1, 4), [1, 3, 3]), &device);
        let loss = |m: &[f32]| {
            let t = Tensor::<3>::from_data(TensorData::new(m.to_vec(), [1, 3, 3]), &device);
            (project_to_rotation(t, ITERATIONS) * weights.clone()).sum()
        };
        let input = Tensor::<3>::from_data(TensorData::new(base.clone(), [1, 3, 3]), &device)
            .require_grad();
        let grads =
            (project_to_rotation(input.clone(), ITERATIONS) * weights.clone()).sum().backward();
        let analytic = values(input.grad(&grads).expect("gradient"));
        let h = 1e-2f32;
        for k in 0..9 {
            let (mut plus, mut minus) = (base.clone(), base.clone());
            plus[k] += h;
            minus[k] -= h;
            let numeric: f32 =
                (loss(&plus).into_scalar::<f32>() - loss(&minus).into_scalar::<f32>()) / (2.0 * h);
            assert!(
                (numeric - analytic[k]).abs() < 2e-2 * (1.0 + numeric.abs()),
                "entry {k}: {numeric} vs {}",
                analytic[k]
            );
        }
    }
}
