//! One turn at a time for burn's random number generator.
//!
//! burn draws initial weights and `Tensor::random` values from one process-wide generator.
//! Some of its initialisers draw when a module is built, others when a parameter is first
//! read. Two threads drawing at once interleave their draws, so a seeded initialisation on
//! one thread would change whenever another thread builds, loads or initialises a network at
//! the same moment (a resumed-training test failed that way in CI, about one run in six).
//! Every draw of this crate therefore happens inside [`seeded`] or [`exclusive`]; code
//! outside the crate that draws from burn's generator on another thread while a network is
//! seeded is not covered.

use std::sync::{Mutex, PoisonError};

use burn::module::Module;
use burn::prelude::{Device, Tensor};
use burn::tensor::Distribution;

static TURN: Mutex<()> = Mutex::new(());

/// Runs `draw` while no other caller of [`seeded`] or [`exclusive`] runs: for code that
/// draws values it does not keep (a network built only to receive loaded weights).
pub fn exclusive<T>(draw: impl FnOnce() -> T) -> T {
    let _turn = TURN.lock().unwrap_or_else(PoisonError::into_inner);
    draw()
}

/// Seeds burn's generator with `seed` and runs `draw` while no other caller of this module
/// runs: the same seed gives the same values whatever other threads do. Parameters that burn
/// initialises lazily must be drawn inside `draw` (see [`materialised`]).
pub fn seeded<T>(device: &Device, seed: u64, draw: impl FnOnce() -> T) -> T {
    exclusive(|| {
        device.seed(seed);
        draw()
    })
}

/// A tensor of `shape` drawn from `distribution` by burn's generator seeded with `seed`:
/// the same seed gives the same values whatever other threads do. (`clippy.toml` bans
/// `Tensor::random` everywhere else.)
pub fn random<const D: usize>(
    device: &Device,
    seed: u64,
    shape: [usize; D],
    distribution: Distribution,
) -> Tensor<D> {
    #[allow(clippy::disallowed_methods)] // drawn under the lock
    seeded(device, seed, || Tensor::random(shape, distribution, device))
}

/// `module` with every parameter drawn now rather than when it is first read.
pub fn materialised<M: Module>(module: M) -> M {
    let record = module.clone().into_record();
    module.load_record(record)
}
