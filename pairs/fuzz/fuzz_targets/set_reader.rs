//! Any bytes as a `sets.mcap` stream: every set read must be valid or the stream must end
//! in a typed error, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    pairs::fuzz::read_sets(data);
});
