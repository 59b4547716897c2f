//! The output folder of an export: written into a staging folder beside it, then swapped
//! into place, so that a refused or interrupted export never changes what was there.

use std::path::{Path, PathBuf};

/// Why an output folder cannot be written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum OutputError {
    /// The folder holds files and replacing them was not asked for.
    #[error("{path} is not empty; pass --force to replace its contents")]
    NotEmpty {
        /// The output folder.
        path: PathBuf,
    },
    /// The output path exists and is not a folder.
    #[error("{path} exists and is not a folder")]
    NotAFolder {
        /// The output path.
        path: PathBuf,
    },
    /// A file system operation failed.
    #[error("{path}: {source}")]
    Io {
        /// The path concerned.
        path: PathBuf,
        /// The failure.
        source: std::io::Error,
    },
}

impl OutputError {
    /// An I/O error on `path`.
    pub fn io(path: &Path) -> impl FnOnce(std::io::Error) -> Self + '_ {
        move |source| Self::Io { path: path.into(), source }
    }
}

/// Writes `bytes` to `path` (a file of an export); returns the size written.
pub fn write_file(path: &Path, bytes: &[u8]) -> Result<u64, OutputError> {
    std::fs::write(path, bytes).map_err(OutputError::io(path))?;
    Ok(bytes.len() as u64)
}

/// A staging folder for the output folder `target`: write into [`Staging::path`], then
/// [`Staging::commit`]. Dropped without a commit, it removes itself and leaves `target`
/// untouched.
#[derive(Debug)]
pub struct Staging {
    target: PathBuf,
    staging: PathBuf,
    committed: bool,
}

impl Staging {
    /// Checks `target` (absent, an empty folder, or any folder when `force`) and creates
    /// the staging folder beside it.
    pub fn new(target: &Path, force: bool) -> Result<Self, OutputError> {
        match std::fs::metadata(target) {
            Ok(meta) if !meta.is_dir() => {
                return Err(OutputError::NotAFolder { path: target.into() });
            }
            Ok(_) => {
                let mut entries = std::fs::read_dir(target).map_err(OutputError::io(target))?;
                if !force && entries.next().is_some() {
                    return Err(OutputError::NotEmpty { path: target.into() });
                }
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
            Err(e) => return Err(OutputError::Io { path: target.into(), source: e }),
        }
        let parent = match target.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        std::fs::create_dir_all(&parent).map_err(OutputError::io(&parent))?;
        let name = target.file_name().map_or("export".into(), |n| n.to_string_lossy().to_string());
        let staging = parent.join(format!(".{name}.partial-{}", std::process::id()));
        if staging.exists() {
            std::fs::remove_dir_all(&staging).map_err(OutputError::io(&staging))?;
        }
        std::fs::create_dir(&staging).map_err(OutputError::io(&staging))?;
        Ok(Self { target: target.into(), staging, committed: false })
    }

    /// The folder to write into.
    pub fn path(&self) -> &Path {
        &self.staging
    }

    /// Puts the staged folder in place of the target (whose old contents are removed only
    /// once the new folder is in place).
    pub fn commit(mut self) -> Result<(), OutputError> {
        let old = self.staging.with_file_name(format!(
            "{}.old",
            self.staging.file_name().map_or_else(String::new, |n| n.to_string_lossy().into())
        ));
        let had_target = self.target.exists();
        if had_target {
            std::fs::rename(&self.target, &old).map_err(OutputError::io(&self.target))?;
        }
        if let Err(source) = std::fs::rename(&self.staging, &self.target) {
            if had_target {
                // Put the old folder back; the staged one stays for `drop` to remove.
                let _ = std::fs::rename(&old, &self.target);
            }
            return Err(OutputError::Io { path: self.target.clone(), source });
        }
        self.committed = true;
        if had_target {
            std::fs::remove_dir_all(&old).map_err(OutputError::io(&old))?;
        }
        Ok(())
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.staging);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refuses_a_non_empty_folder_and_replaces_it_only_when_forced() {
        let dir = tempfile::tempdir().expect("temp dir");
        let out = dir.path().join("out");
        std::fs::create_dir(&out).expect("mkdir");
        std::fs::write(out.join("keep.txt"), "old").expect("write");
        assert!(matches!(Staging::new(&out, false), Err(OutputError::NotEmpty { .. })));
        // An export that fails before its commit leaves the old contents.
        let staging = Staging::new(&out, true).expect("forced");
        std::fs::write(staging.path().join("new.txt"), "new").expect("write");
        drop(staging);
        assert_eq!(std::fs::read_to_string(out.join("keep.txt")).expect("kept"), "old");
        let staging = Staging::new(&out, true).expect("forced");
        std::fs::write(staging.path().join("new.txt"), "new").expect("write");
        staging.commit().expect("commit");
        assert!(!out.join("keep.txt").exists());
        assert_eq!(std::fs::read_to_string(out.join("new.txt")).expect("new"), "new");
        let left: Vec<_> = std::fs::read_dir(dir.path()).expect("list").collect();
        assert_eq!(left.len(), 1, "no staging folder is left behind");
    }

    #[test]
    fn refuses_a_file() {
        let dir = tempfile::tempdir().expect("temp dir");
        let file = dir.path().join("f");
        std::fs::write(&file, "x").expect("write");
        assert!(matches!(Staging::new(&file, true), Err(OutputError::NotAFolder { .. })));
    }
}
