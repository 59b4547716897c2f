//! Hashes the source of the crates whose code makes the evaluator's rows (`pairs`,
//! `baselines`, `model`), the evaluator's own code that runs and scores them (`SCORING`:
//! run, score, record, passes, joints, reference, tuning, external) and `Cargo.lock`
//! (`LOCK`: a dependency's new version can move a number), and the set runner
//! (`SETS`: `running/sets.rs`, in the set rows' fingerprints only), so a row's cached runs
//! are recomputed when any of it changes,
//! not only when its parameters or weights do (`SOURCE_HASH_<NAME>` at compile time).

use std::path::{Path, PathBuf};

#[path = "src/running/source_hash.rs"]
#[allow(dead_code)]
mod source_hash;

/// Every file under `dir`, sorted, so the hash does not depend on directory order. Each
/// file and folder is also a `rerun-if-changed` path: cargo does not rescan a folder named
/// by one line for edits inside it, so without these the hashes went stale.
fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    println!("cargo:rerun-if-changed={}", dir.display());
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            files(&path, out);
        } else {
            println!("cargo:rerun-if-changed={}", path.display());
            out.push(path);
        }
    }
}

/// Prints `SOURCE_HASH_<name>` of `paths`.
fn emit(name: &str, base: &Path, paths: Vec<PathBuf>) {
    println!("cargo:rustc-env=SOURCE_HASH_{name}={}", source_hash::hash_files(base, &paths));
}

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    for krate in ["pairs", "baselines", "model"] {
        let src = root.join(krate).join("src");
        let mut paths = Vec::new();
        files(&src, &mut paths);
        emit(&krate.to_uppercase(), &src, paths);
    }
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    println!("cargo:rerun-if-changed={}", src.join("running").join("source_hash.rs").display());
    let scoring: Vec<PathBuf> = source_hash::SCORING.iter().map(|f| src.join(f)).collect();
    for path in &scoring {
        println!("cargo:rerun-if-changed={}", path.display());
    }
    emit("SCORING", &src, scoring);
    // The set runner, hashed on its own so that a change to it recomputes the set rows only.
    let sets = src.join("running").join("sets.rs");
    println!("cargo:rerun-if-changed={}", sets.display());
    emit("SETS", &src, vec![sets]);
    let lock = root.join("Cargo.lock");
    println!("cargo:rerun-if-changed={}", lock.display());
    emit("LOCK", &root, vec![lock]);
}
