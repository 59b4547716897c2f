use super::*;
use crate::network::mlp::*;
use crate::network::norm::linear;
use crate::network::rng;
use rand::{Rng, SeedableRng};

fn cloud(n: usize, seed: u64) -> Vec<f32> {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    (0..n * 3).map(|_| rng.random_range(-0.5f32..0.5)).collect()
}

fn tensor(values: Vec<f32>, shape: [usize; 3], device: &Device) -> Tensor<3> {
    Tensor::from_data(TensorData::new(values, shape), device)
}

#[test]
fn linear_on_flattened_rows_is_burns_linear_with_the_same_gradients() {
    // The rows are flattened into one product: the same dot products, and
    // the same weight gradients up to the order of the sums.
    let device = Device::flex().autodiff();
    let layer = rng::seeded(&device, 1, || rng::materialised(relu_layer(32, 48).init(&device)));
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
    let values: Vec<f32> = (0..4 * 16 * 16 * 32).map(|_| rng.random_range(-1.0f32..1.0)).collect();
    let pairs = Tensor::<4>::from_data(TensorData::new(values, [4, 16, 16, 32]), &device);
    let floats = |t: Tensor<4>| t.into_data().convert::<f32>().try_to_vec::<f32>().expect("f32");
    let ours = linear(&layer, pairs.clone());
    let burns = layer.forward(pairs);
    assert_eq!(ours.dims(), [4, 16, 16, 48]);
    for (a, b) in floats(ours.clone()).iter().zip(floats(burns.clone())) {
        assert!((a - b).abs() <= 1e-5 * (1.0 + b.abs()), "{a} vs {b}");
    }
    let grad = |out: Tensor<4>| {
        let grads = (out.clone() * out).sum().backward();
        let g = layer.weight.grad(&grads).expect("a weight gradient");
        g.into_data().convert::<f32>().try_to_vec::<f32>().expect("f32")
    };
    for (a, b) in grad(ours).iter().zip(grad(burns)) {
        assert!((a - b).abs() <= 1e-3 * (1.0 + b.abs()), "{a} vs {b}");
    }
}

fn rows(t: Tensor<3>) -> Vec<Vec<f32>> {
    let [_, n, c] = t.dims();
    let flat: Vec<f32> = t.into_data().convert::<f32>().try_to_vec().expect("f32");
    (0..n).map(|i| flat[i * c..(i + 1) * c].to_vec()).collect()
}

#[test]
fn permuting_the_points_permutes_the_dense_outputs() {
    let device = Device::flex();
    let n = 48;
    let values = cloud(n, 1);
    let permutation: Vec<usize> = (0..n).map(|i| (i * 7 + 3) % n).collect();
    let permuted: Vec<f32> =
        permutation.iter().flat_map(|&i| values[i * 3..i * 3 + 3].to_vec()).collect();
    let (sa, fp) = rng::seeded(&device, 2, || {
        let sa = SetAbstractionConfig::single(12, 0.4, 8, vec![16, 16]).init(0, false, &device);
        (rng::materialised(sa), rng::materialised(FeaturePropagation::new(16, &[8], &device)))
    });
    let run = |v: Vec<f32>| {
        let xyz = tensor(v, [1, n, 3], &device);
        let (centres, f) = sa.forward(xyz.clone(), None).expect("enough points");
        rows(fp.forward(xyz, centres, None, f).expect("enough centres"))
    };
    let (a, b) = (run(values), run(permuted));
    for (j, &i) in permutation.iter().enumerate() {
        for (x, y) in a[i].iter().zip(&b[j]) {
            assert!((x - y).abs() < 1e-5, "point {i}: {:?} vs {:?}", a[i], b[j]);
        }
    }
}

#[test]
fn gradients_reach_the_grouped_features() {
    let device = Device::flex().autodiff();
    let xyz = tensor(cloud(32, 2), [1, 32, 3], &device);
    let features = tensor(cloud(32, 3), [1, 32, 3], &device).require_grad();
    let sa = rng::seeded(&device, 3, || {
        rng::materialised(SetAbstractionConfig::single(8, 0.5, 6, vec![8]).init(3, false, &device))
    });
    let (_, out) = sa.forward(xyz, Some(features.clone())).expect("enough points");
    let grads = out.sum().backward();
    let g = features.grad(&grads).expect("a gradient for the features");
    let nonzero = g
        .into_data()
        .convert::<f32>()
        .try_to_vec::<f32>()
        .expect("f32")
        .iter()
        .filter(|v| **v != 0.0)
        .count();
    assert!(nonzero > 0);
}

#[test]
fn too_small_clouds_are_errors_not_panics() {
    let device = Device::flex();
    let sa = rng::seeded(&device, 4, || {
        rng::materialised(SetAbstractionConfig::single(16, 0.4, 8, vec![8]).init(0, false, &device))
    });
    let err = sa.forward(tensor(cloud(10, 4), [1, 10, 3], &device), None).expect_err("10 < 16");
    assert_eq!(err, SamplingError::TooFewPoints { wanted: 16, points: 10 });
    let same = tensor(vec![0.25; 30], [1, 10, 3], &device);
    let small = rng::seeded(&device, 5, || {
        rng::materialised(SetAbstractionConfig::single(4, 0.4, 8, vec![8]).init(0, false, &device))
    });
    let (_, f) = small.forward(same, None).expect("duplicates are fine");
    assert!(rows(f).iter().flatten().all(|v| v.is_finite()));
}

#[test]
fn global_abstraction_pools_each_cloud() {
    let device = Device::flex();
    let g =
        rng::seeded(&device, 6, || rng::materialised(GlobalAbstraction::new(2, &[8, 4], &device)));
    let out = g.forward(
        tensor(cloud(20, 5), [2, 10, 3], &device),
        tensor(cloud(20, 6)[..40].to_vec(), [2, 10, 2], &device),
    );
    assert_eq!(out.dims(), [2, 1, 4]);
}

#[test]
fn centred_features_ignore_a_uniform_offset() {
    // With the release's `centralize_points` a uniform flow (a pure translation) reaches the
    // first level as zeros, so adding one changes nothing; without it the output moves.
    let device = Device::flex();
    let xyz = tensor(cloud(32, 5), [1, 32, 3], &device);
    let features = tensor(cloud(32, 6), [1, 32, 3], &device);
    let shifted = features.clone() + tensor(vec![0.3, -0.2, 0.5], [1, 1, 3], &device);
    for centred in [true, false] {
        let sa = rng::seeded(&device, 7, || {
            rng::materialised(
                SetAbstractionConfig::single(8, 0.5, 6, vec![8]).init(3, centred, &device),
            )
        });
        let a = rows(sa.forward(xyz.clone(), Some(features.clone())).expect("32 points").1);
        let b = rows(sa.forward(xyz.clone(), Some(shifted.clone())).expect("32 points").1);
        let moved = a.iter().flatten().zip(b.iter().flatten()).map(|(x, y)| (x - y).abs());
        let largest = moved.fold(0.0f32, f32::max);
        if centred {
            assert!(largest < 1e-5, "centred output moved by {largest}");
        } else {
            assert!(largest > 1e-3, "uncentred output did not move ({largest})");
        }
    }
}
