//! Any bytes as a render folder's `render.json` and `ground_truth.json`: read, or refused with a
//! typed error, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    pairs::fuzz::read_render_records(data);
});
