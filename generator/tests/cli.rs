//! The `generator` binary at its edges (the workspace's `cli` crate): a warning is shown
//! without `RUST_LOG`, and an error is one `error:` line with exit status 1.

use std::path::Path;
use std::process::Command;

fn generator() -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_generator"));
    command.env_remove("RUST_LOG");
    command
}

#[test]
fn an_unreadable_texture_is_a_warning_shown_by_default() {
    let dir = tempfile::tempdir().expect("tempdir");
    let assets = dir.path().join("assets");
    std::fs::create_dir_all(&assets).expect("mkdir");
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/assets/obj");
    let obj = std::fs::read_to_string(examples.join("lamp.obj")).expect("the example lamp");
    std::fs::write(assets.join("lamp.obj"), format!("mtllib lamp.mtl\nusemtl shade\n{obj}"))
        .expect("write");
    std::fs::write(assets.join("lamp.mtl"), "newmtl shade\nKd 0.8 0.8 0.8\nmap_Kd missing.png\n")
        .expect("write");
    std::fs::copy(examples.join("lamp.joints.json"), assets.join("lamp.joints.json"))
        .expect("copy");
    let out = dir.path().join("out");
    let run = generator()
        .arg("--assets")
        .arg(&assets)
        .arg("--out")
        .arg(&out)
        .output()
        .expect("the generator runs");
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    assert!(stderr.contains("WARN") && stderr.contains("missing.png"), "{stderr}");
}

#[test]
fn an_error_is_one_line_and_exit_status_one() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("out");
    let first = generator().args(["-n", "1", "--out"]).arg(&out).output().expect("runs");
    assert!(first.status.success(), "{}", String::from_utf8_lossy(&first.stderr));
    let again = generator().args(["-n", "1", "--out"]).arg(&out).output().expect("runs");
    let stderr = String::from_utf8_lossy(&again.stderr);
    assert_eq!(again.status.code(), Some(1), "{stderr}");
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(lines.len(), 1, "{stderr}");
    assert!(lines[0].starts_with("error: ") && lines[0].contains("--force"), "{stderr}");
}
