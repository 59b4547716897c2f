//! An OBJ with a joints sidecar (the input's part before the first NUL byte is the OBJ,
//! the rest the sidecar) to an articulated object.
#![no_main]

use std::path::Path;

use assets::assemble;
use assets::obj_groups::obj_skeleton;
use assets::sidecar::parse_sidecar;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let split = data.iter().position(|&b| b == 0).unwrap_or(data.len());
    let (obj, sidecar) = (&data[..split], data.get(split + 1..).unwrap_or_default());
    let (Ok(obj), Ok(sidecar)) = (std::str::from_utf8(obj), std::str::from_utf8(sidecar)) else {
        return;
    };
    let path = Path::new("fuzz.obj");
    let spec = parse_sidecar(path, sidecar)
        .unwrap_or(assets::sidecar::Sidecar { category: None, joints: Vec::new() });
    if let Ok(skeleton) = obj_skeleton(path, obj, &spec) {
        let _ = assemble(skeleton, (-3.0, 3.0));
    }
});
