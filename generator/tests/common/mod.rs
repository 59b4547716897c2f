//! Helpers shared by the generator's integration tests.

use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestRng, TestRunner};

/// Runs `check` on `cases` object seeds drawn by a seeded property-test runner, so that
/// every run tries the same seeds and a failure names the seed that broke.
pub fn for_seeds(cases: u32, check: impl Fn(u64) -> Result<(), String>) {
    let config = Config { cases, failure_persistence: None, ..Config::default() };
    let rng = TestRng::deterministic_rng(RngAlgorithm::ChaCha);
    let mut runner = TestRunner::new_with_rng(config, rng);
    runner
        .run(&(0u64..1_000_000), |seed| check(seed).map_err(TestCaseError::fail))
        .unwrap_or_else(|e| panic!("{e}"));
}
