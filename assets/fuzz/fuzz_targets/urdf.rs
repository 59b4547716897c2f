//! URDF text to an articulated object: any input gives an object or a typed error.
#![no_main]

use std::path::Path;

use assets::assemble;
use assets::urdf::{urdf_skeleton, MeshSearch};
use assets::ImportOptions;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let options = ImportOptions::default();
    // Mesh references resolve against a folder that does not exist: they fail cleanly.
    let search = MeshSearch { base: Path::new("/nonexistent-fuzz"), options: &options };
    if let Ok((skeleton, _)) = urdf_skeleton(Path::new("fuzz.urdf"), text, &search) {
        let _ = assemble(skeleton, (-3.0, 3.0));
    }
});
