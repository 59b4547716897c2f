use super::*;
use crate::network::rng;
use burn::tensor::Distribution;

fn values<const D: usize>(t: Tensor<D>) -> Vec<f32> {
    t.to_data().try_to_vec::<f32>().expect("f32")
}

#[test]
fn values_are_burns_max_dim_bit_for_bit() {
    for device in [Device::flex(), Device::flex().autodiff()] {
        // 40 sets: more than one block of work, the last one not full.
        let x = rng::random(&device, 1, [5, 8, 13, 24], Distribution::Normal(0.0, 1.0));
        assert!(is_pooled(&x));
        assert_eq!(values(max_pool(x.clone())), values(x.clone().max_dim(2)));
        assert_eq!(max_pool(x.clone()).dims(), [5, 8, 1, 24]);
        let points = rng::random(&device, 2, [3, 50, 7], Distribution::Normal(0.0, 1.0));
        assert_eq!(values(max_pool(points.clone())), values(points.max_dim(1)));
    }
}

#[test]
fn gradient_is_burns_and_goes_to_the_winning_row() {
    let device = Device::flex().autodiff();
    // Distinct values (no ties), so burn's gradient and ours must agree exactly.
    let x = rng::random(&device, 3, [2, 6, 9, 5], Distribution::Normal(0.0, 1.0)).require_grad();
    let weights = rng::random(&device, 4, [2, 6, 1, 5], Distribution::Normal(0.0, 1.0));
    let grad = |pooled: Tensor<4>| {
        let grads = (pooled * weights.clone()).sum().backward();
        values(x.grad(&grads).expect("an input gradient"))
    };
    let ours = grad(max_pool(x.clone()));
    assert_eq!(ours, grad(x.clone().max_dim(2)));
    // Per (set, channel) exactly one row carries the weight, the one holding the maximum.
    let (xs, ws) = (values(x.clone()), values(weights.clone()));
    for set in 0..12 {
        for c in 0..5 {
            let column: Vec<f32> = (0..9).map(|j| xs[(set * 9 + j) * 5 + c]).collect();
            let best = (0..9).fold(0, |b, j| if column[j] > column[b] { j } else { b });
            for j in 0..9 {
                let expected = if j == best { ws[set * 5 + c] } else { 0.0 };
                assert_eq!(ours[(set * 9 + j) * 5 + c], expected, "set {set} channel {c} row {j}");
            }
        }
    }
}

#[test]
fn ties_give_the_gradient_to_the_first_row() {
    let x = [1.0f32, 0.0, 3.0, 0.0, 3.0, 0.0];
    let (out, winners) = forward(&x, 3, 2, true);
    assert_eq!((out, winners.clone()), (vec![3.0, 0.0], vec![1, 0]));
    assert_eq!(backward(&[2.0, 5.0], &winners, 3, 2), vec![0.0, 5.0, 2.0, 0.0, 0.0, 0.0]);
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    let x: Vec<f32> = (0..37 * 11 * 6).map(|i| ((i * 37 % 101) as f32).sin()).collect();
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("pool");
    let three = rayon::ThreadPoolBuilder::new().num_threads(3).build().expect("pool");
    let a = one.install(|| forward(&x, 11, 6, true));
    assert_eq!(a, three.install(|| forward(&x, 11, 6, true)));
    let g: Vec<f32> = (0..37 * 6).map(|i| i as f32).collect();
    assert_eq!(
        one.install(|| backward(&g, &a.1, 11, 6)),
        three.install(|| backward(&g, &a.1, 11, 6))
    );
}

#[test]
fn an_empty_set_falls_back_to_burn() {
    let x = Tensor::<3>::zeros([2, 0, 4], &Device::flex());
    assert!(!is_pooled(&x));
}
