//! The source hashes behind the rows' fingerprints, shared by `build.rs` (which computes
//! them at compile time) and the tests (which check that an edit changes them).

use std::path::{Path, PathBuf};

use sha2::{Digest, Sha256};

/// The first 8 bytes of the sha256 of `paths` (sorted; each as its path relative to `base`,
/// then its contents), in hex. A missing file hashes as empty.
pub fn hash_files(base: &Path, paths: &[PathBuf]) -> String {
    let mut paths = paths.to_vec();
    paths.sort();
    let mut hash = Sha256::new();
    for path in paths {
        hash.update(path.strip_prefix(base).unwrap_or(&path).to_string_lossy().as_bytes());
        hash.update(std::fs::read(&path).unwrap_or_default());
    }
    hash.finalize().iter().take(8).map(|b| format!("{b:02x}")).collect()
}

/// The evaluator's files whose code changes a row's per-pair numbers (`SOURCE_HASH_SCORING`).
pub const SCORING: [&str; 7] = [
    "running/run.rs",
    "running/record.rs",
    "running/passes.rs",
    "rows/reference.rs",
    "rows/external.rs",
    "rows/grid.rs",
    "tuning.rs",
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_edit_to_a_hashed_file_changes_the_hash() {
        let dir = tempfile::tempdir().expect("a temporary folder");
        let files: Vec<PathBuf> = SCORING.iter().map(|f| dir.path().join(f)).collect();
        for f in &files {
            std::fs::create_dir_all(f.parent().expect("a folder")).expect("created");
            std::fs::write(f, "fn a() {}").expect("written");
        }
        std::fs::write(dir.path().join("report.rs"), "x").expect("written");
        let before = hash_files(dir.path(), &files);
        assert_eq!(before.len(), 16);
        // Another file than the scoring code does not move it.
        std::fs::write(dir.path().join("report.rs"), "y").expect("written");
        assert_eq!(hash_files(dir.path(), &files), before);
        // An edit to the scoring code does; so does a renamed file with the same contents.
        std::fs::write(&files[1], "fn a() { }").expect("written");
        let edited = hash_files(dir.path(), &files);
        assert_ne!(edited, before);
        std::fs::write(&files[1], "fn a() {}").expect("written");
        assert_eq!(hash_files(dir.path(), &files), before, "the hash is of the contents");
    }

    #[test]
    fn every_hashed_file_exists() {
        // A missing file hashes as empty: a renamed scoring file would drop out unseen.
        let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
        for file in SCORING {
            assert!(src.join(file).is_file(), "{file} is in SCORING but not in src/");
        }
    }
}
