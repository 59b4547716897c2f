//! glTF JSON or GLB bytes to an articulated object (external buffers are refused).
#![no_main]

use std::path::Path;

use assets::assemble;
use assets::gltf::gltf_skeleton;
use assets::ImportError;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let external = |_: &str| -> Result<(Vec<u8>, std::path::PathBuf), ImportError> {
        Err(ImportError::Options("no external buffers while fuzzing".into()))
    };
    if let Ok((skeleton, _)) = gltf_skeleton(Path::new("fuzz.gltf"), data, None, &external) {
        let _ = assemble(skeleton, (-3.0, 3.0));
    }
});
