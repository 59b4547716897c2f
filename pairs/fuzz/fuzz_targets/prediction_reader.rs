//! Any bytes as a prediction file: the header and every record must be read or the stream
//! must end in a typed error, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    pairs::fuzz::read_predictions(data);
});
