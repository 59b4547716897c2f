use super::*;
use crate::network::fused::*;
use crate::network::rng;
use burn::module::Param;
use burn::nn::{LayerNormConfig, LinearConfig};
use burn::tensor::Distribution;

/// A layer of 10 inputs and 24 outputs with random bias, γ and β.
fn layer(device: &Device) -> (Linear, LayerNorm) {
    let (mut linear, mut norm) = rng::seeded(device, 1, || {
        let linear = rng::materialised(LinearConfig::new(10, 24).init(device));
        (linear, LayerNormConfig::new(24).init(device))
    });
    let random = |seed, d| Param::from_tensor(rng::random(device, seed, [24], d));
    linear.bias = Some(random(2, Distribution::Normal(0.0, 0.5)));
    // γ and β away from 1 and 0, so that every term of the gradient matters.
    norm.gamma = random(3, Distribution::Uniform(0.5, 1.5));
    norm.beta = Some(random(4, Distribution::Normal(0.0, 0.5)));
    (linear, norm)
}

fn values<const D: usize>(t: Tensor<D>) -> Vec<f32> {
    t.to_data().try_to_vec::<f32>().expect("f32")
}

/// Values and the gradients of input, weight, bias, γ and β, through `f`, for the loss
/// `sum(out * weights)`.
fn run(
    (linear, norm): &(Linear, LayerNorm),
    x: &Tensor<3>,
    weights: &Tensor<3>,
    f: fn(&Linear, &LayerNorm, Tensor<3>) -> Tensor<3>,
) -> Vec<Vec<f32>> {
    let x = x.clone().require_grad();
    let out = f(linear, norm, x.clone());
    let grads = (out.clone() * weights.clone()).sum().backward();
    let bias = linear.bias.as_ref().expect("a bias");
    let beta = norm.beta.as_ref().expect("a beta");
    vec![
        values(out),
        values(x.grad(&grads).expect("input gradient")),
        values(linear.weight.grad(&grads).expect("weight gradient")),
        values(bias.grad(&grads).expect("bias gradient")),
        values(norm.gamma.grad(&grads).expect("gamma gradient")),
        values(beta.grad(&grads).expect("beta gradient")),
    ]
}

fn reference(layer: &Linear, norm: &LayerNorm, x: Tensor<3>) -> Tensor<3> {
    activation::relu(norm.forward(layer.forward(x)))
}

#[test]
fn matches_linear_layer_norm_relu_in_values_and_gradients() {
    let device = Device::flex().autodiff();
    // 300 rows: more than one block, and a last block that is not full.
    let x = rng::random(&device, 5, [3, 100, 10], Distribution::Normal(0.5, 2.0));
    let weights = rng::random(&device, 6, [3, 100, 24], Distribution::Normal(0.0, 1.0));
    let layer = layer(&device);
    assert!(is_fused(&layer.0, &layer.1, &x));
    let fused = run(&layer, &x, &weights, linear_norm_relu);
    let expected = run(&layer, &x, &weights, reference);
    let names = ["output", "input", "weight", "bias", "gamma", "beta"];
    for (name, (a, b)) in names.iter().zip(fused.iter().zip(&expected)) {
        assert_eq!(a.len(), b.len(), "{name}");
        let scale = b.iter().fold(1.0f32, |m, v| m.max(v.abs()));
        let worst = a.iter().zip(b).map(|(a, b)| (a - b).abs()).fold(0.0, f32::max);
        assert!(worst <= 2e-5 * scale, "{name}: differs by {worst} (scale {scale})");
    }
    // Some outputs are clipped, some are not: both branches of the ReLU are tested.
    let zeros = fused[0].iter().filter(|&&v| v == 0.0).count();
    assert!(zeros > 100 && zeros < fused[0].len() - 100, "{zeros} zeros");
}

/// The fused layer's output agrees with burn's `Linear`, `LayerNorm` and `relu` within 2e-5
/// of the output's scale.
fn assert_agrees_with_burns(linear: &Linear, norm: &LayerNorm, x: Tensor<3>) {
    let a = values(linear_norm_relu(linear, norm, x.clone()));
    let b = values(reference(linear, norm, x));
    let scale = b.iter().fold(1.0f32, |m, v| m.max(v.abs()));
    let worst = a.iter().zip(&b).map(|(a, b)| (a - b).abs()).fold(0.0, f32::max);
    assert!(worst <= 2e-5 * scale, "differs by {worst} (scale {scale})");
}

#[test]
fn inference_takes_the_fused_operation_and_agrees_with_burns() {
    let device = Device::flex();
    let x = rng::random(&device, 7, [2, 35, 10], Distribution::Normal(0.0, 1.0));
    let (linear, norm) = layer(&device);
    assert!(is_fused(&linear, &norm, &x));
    assert_agrees_with_burns(&linear, &norm, x);
}

#[test]
fn untracked_autodiff_tensors_take_the_fused_operation_without_a_product() {
    // No tensor tracks gradients: the operation runs without keeping the product.
    let device = Device::flex().autodiff();
    let x = rng::random(&device, 8, [2, 35, 10], Distribution::Normal(0.0, 1.0));
    let (linear, norm) = layer(&device);
    let (linear, norm) = (linear.no_grad(), norm.no_grad());
    assert!(is_fused(&linear, &norm, &x));
    assert_agrees_with_burns(&linear, &norm, x);
}

#[test]
fn epsilon_is_layer_norms_default() {
    assert_eq!(LayerNormConfig::new(4).epsilon as f32, EPSILON);
}

#[test]
fn gradients_do_not_depend_on_the_thread_count() {
    let (input, c) = (5, 8);
    let rows = 5 * ROWS_PER_TASK + 3;
    let x: Vec<f32> = (0..rows * input).map(|i| ((i * 37 % 101) as f32).sin()).collect();
    let weight: Vec<f32> = (0..input * c).map(|i| ((i * 13 % 17) as f32).cos()).collect();
    let (bias, gamma, beta) = (vec![0.2f32; c], vec![0.9f32; c], vec![0.1f32; c]);
    let channels = Channels { bias: &bias, gamma: &gamma, beta: &beta };
    let run = |threads| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool");
        pool.install(|| {
            let (out, z) = forward(&x, &weight, &channels, true);
            let mut grad: Vec<f32> = out.iter().map(|v| (v * 3.0).cos()).collect();
            let grads = backward(&x, &weight, &z, &channels, &mut grad, true);
            (out, grads)
        })
    };
    let one = run(1);
    assert_eq!(one.1[0].len(), rows * input);
    assert_eq!(one, run(3));
}
