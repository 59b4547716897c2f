//! Inputs that once crashed a fuzz target (`assets/fuzz`), kept as regression tests:
//! `tests/fuzz_regressions/<target>/<file>` is fed to the same parser as the fuzz target
//! `<target>`, which must return (an object or a typed error) without panicking.

use std::path::Path;

use assets::assemble;
use assets::gltf::gltf_skeleton;
use assets::mesh_build::build_mesh;
use assets::mesh_files::{parse_obj, read_stl};
use assets::obj_groups::obj_skeleton;
use assets::sidecar::{parse_sidecar, Sidecar};
use assets::urdf::{urdf_skeleton, MeshSearch};
use assets::{ImportError, ImportOptions};

/// What each fuzz target does with its input (the targets in `assets/fuzz` match).
fn run(target: &str, data: &[u8]) {
    let range = (-3.0, 3.0);
    match target {
        "gltf" => {
            let external = |_: &str| -> Result<(Vec<u8>, std::path::PathBuf), ImportError> {
                Err(ImportError::Options("no external buffers".into()))
            };
            if let Ok((s, _)) = gltf_skeleton(Path::new("f.gltf"), data, None, &external) {
                let _ = assemble(s, range);
            }
        }
        "urdf" => {
            let options = ImportOptions::default();
            let search = MeshSearch { base: Path::new("/nonexistent-fuzz"), options: &options };
            if let Ok(text) = std::str::from_utf8(data) {
                if let Ok((s, _)) = urdf_skeleton(Path::new("f.urdf"), text, &search) {
                    let _ = assemble(s, range);
                }
            }
        }
        "obj_groups" => {
            let split = data.iter().position(|&b| b == 0).unwrap_or(data.len());
            let obj = std::str::from_utf8(&data[..split]).unwrap_or("");
            let side = std::str::from_utf8(data.get(split + 1..).unwrap_or_default()).unwrap_or("");
            let spec = parse_sidecar(Path::new("f.joints.json"), side)
                .unwrap_or(Sidecar { category: None, joints: Vec::new() });
            if let Ok(s) = obj_skeleton(Path::new("f.obj"), obj, &spec) {
                let _ = assemble(s, range);
            }
        }
        "sidecar" => {
            if let Ok(spec) =
                parse_sidecar(Path::new("f.json"), std::str::from_utf8(data).unwrap_or(""))
            {
                spec.joints.iter().for_each(|j| drop(j.to_raw(Some("p"), Some("c"))));
            }
        }
        "mesh_files" => {
            if let Ok((p, t)) = read_stl(data) {
                let _ = build_mesh("f", &p, &t);
            }
            if let Ok(groups) =
                parse_obj(Path::new("f.obj"), std::str::from_utf8(data).unwrap_or(""))
            {
                groups.iter().for_each(|g| drop(build_mesh(&g.name, &g.positions, &g.triangles)));
            }
        }
        other => panic!("no fuzz target called {other}"),
    }
}

#[test]
fn every_kept_crash_input_now_returns_without_panicking() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz_regressions");
    let mut count = 0;
    for target in std::fs::read_dir(&root).expect("regression folder") {
        let target = target.expect("entry").path();
        let name = target.file_name().and_then(|n| n.to_str()).expect("utf8").to_string();
        for input in std::fs::read_dir(&target).expect("target folder") {
            let input = input.expect("entry").path();
            run(&name, &std::fs::read(&input).expect("input"));
            count += 1;
        }
    }
    assert!(count > 0, "no regression inputs found");
}
