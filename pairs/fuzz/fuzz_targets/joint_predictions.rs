//! Any bytes as a joints-only prediction file (`joints.json`): read, or refused with a
//! typed error, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    pairs::fuzz::read_joint_predictions(data);
});
