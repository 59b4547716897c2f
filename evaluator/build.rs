//! Hashes the source of the crates whose code makes the evaluator's rows (`pairs`,
//! `baselines`, `model`), so a row's cached runs are recomputed when its code changes, not
//! only when its parameters or weights do (`SOURCE_HASH_<CRATE>` at compile time).

use std::path::{Path, PathBuf};

use sha2::{Digest, Sha256};

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

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    for krate in ["pairs", "baselines", "model"] {
        let src = root.join(krate).join("src");
        let mut paths = Vec::new();
        files(&src, &mut paths);
        paths.sort();
        let mut hash = Sha256::new();
        for path in paths {
            hash.update(path.strip_prefix(&src).unwrap_or(&path).to_string_lossy().as_bytes());
            hash.update(std::fs::read(&path).unwrap_or_default());
        }
        let digest = hash.finalize();
        let short: String = digest.iter().take(8).map(|b| format!("{b:02x}")).collect();
        println!("cargo:rustc-env=SOURCE_HASH_{}={short}", krate.to_uppercase());
    }
}
