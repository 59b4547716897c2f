//! Mesh files as URDF links reference them: STL (ASCII or binary) and OBJ (every group).
#![no_main]

use std::path::Path;

use assets::mesh_build::build_mesh;
use assets::mesh_files::{parse_obj, read_stl};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok((positions, triangles)) = read_stl(data) {
        let _ = build_mesh("fuzz", &positions, &triangles);
    }
    if let Ok(text) = std::str::from_utf8(data) {
        if let Ok(groups) = parse_obj(Path::new("fuzz.obj"), text) {
            for g in groups {
                let _ = build_mesh(&g.name, &g.positions, &g.triangles);
            }
        }
    }
});
