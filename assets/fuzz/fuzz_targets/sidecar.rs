//! Joints sidecar JSON to joint records.
#![no_main]

use std::path::Path;

use assets::sidecar::parse_sidecar;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    if let Ok(spec) = parse_sidecar(Path::new("fuzz.joints.json"), text) {
        for joint in &spec.joints {
            let _ = joint.to_raw(Some("parent"), Some("child"));
        }
    }
});
