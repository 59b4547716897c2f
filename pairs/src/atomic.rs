//! Files and folders written whole or not at all. A file is written to a `.partial` sibling
//! of its final name and renamed onto it only once complete ([`replace_file`]); a folder of
//! outputs (an export, a render) is written into a staging folder beside it and swapped into
//! place once complete ([`Staging`]). So an interrupted or failed write never leaves a
//! half-written output and never destroys the old one. Every crate that writes outputs (the
//! evaluator's reports, the trainer's checkpoints and logs, the renderer's and the exporters'
//! folders) goes through here.
//!
//! ```
//! use std::io::Write;
//! use pairs::atomic::{replace_file, FileError};
//!
//! let dir = std::env::temp_dir().join(format!("pairs-atomic-doc-{}", std::process::id()));
//! let path = dir.join("table.csv");
//! replace_file(&path, |out| writeln!(out, "a,b").map_err(pairs::atomic::at(&path)))?;
//! // A failed write leaves the old file as it was, and no partial file behind.
//! let failed: Result<(), FileError> = replace_file(&path, |out| {
//!     writeln!(out, "half").map_err(pairs::atomic::at(&path))?;
//!     Err(pairs::atomic::at(&path)(std::io::Error::other("interrupted")))
//! });
//! assert!(failed.is_err());
//! assert_eq!(std::fs::read_to_string(&path)?, "a,b\n");
//! assert!(!pairs::atomic::partial_path(&path).exists());
//! # std::fs::remove_dir_all(&dir)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// An I/O error on a named file.
#[derive(Debug, thiserror::Error)]
#[error("{path}: {source}")]
pub struct FileError {
    /// The file or folder.
    pub path: PathBuf,
    /// The error.
    #[source]
    pub source: std::io::Error,
}

/// Turns an I/O error on `path` into a [`FileError`] (for `map_err`).
pub fn at(path: &Path) -> impl FnOnce(std::io::Error) -> FileError + '_ {
    move |source| FileError { path: path.to_path_buf(), source }
}

/// The temporary sibling `path` is written as: its file name with `.partial` appended.
pub fn partial_path(path: &Path) -> PathBuf {
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(".partial");
    path.with_file_name(name)
}

/// Writes `path` by `write`, which is given the temporary path to create: creates `path`'s
/// folder, renames the temporary onto `path` once `write` succeeded, and removes it when
/// `write` failed (the old `path`, if any, is then untouched).
pub fn replace_with<E: From<FileError>>(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), E>,
) -> Result<(), E> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(at(dir))?;
    }
    let tmp = partial_path(path);
    if let Err(e) = write(&tmp) {
        let _ = std::fs::remove_file(&tmp);
        return Err(e);
    }
    std::fs::rename(&tmp, path).map_err(at(path))?;
    Ok(())
}

/// [`replace_with`] through a buffered writer on the temporary, flushed before the rename.
pub fn replace_file<E: From<FileError>>(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<File>) -> Result<(), E>,
) -> Result<(), E> {
    replace_with(path, |tmp| {
        let mut out = BufWriter::new(File::create(tmp).map_err(at(tmp))?);
        write(&mut out)?;
        out.flush().map_err(at(tmp))?;
        Ok(())
    })
}

/// [`replace_file`] with `bytes` as the whole content.
pub fn replace_bytes(path: &Path, bytes: &[u8]) -> Result<(), FileError> {
    replace_file(path, |out| out.write_all(bytes).map_err(at(path)))
}

// Folders.

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

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("pairs-atomic-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        dir
    }

    #[test]
    fn a_write_creates_the_folder_and_replaces_the_old_file() {
        let dir = scratch("replace");
        let path = dir.join("sub").join("board.csv");
        replace_file(&path, |out| write!(out, "old").map_err(at(&path))).unwrap();
        replace_file(&path, |out| write!(out, "new").map_err(at(&path))).unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "new");
        replace_bytes(&path, b"bytes").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "bytes");
        assert_eq!(partial_path(&path), dir.join("sub").join("board.csv.partial"));
        assert!(!partial_path(&path).exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_failed_write_keeps_the_old_file_and_cleans_up() {
        let dir = scratch("failed");
        let path = dir.join("weights.bin");
        replace_with(&path, |tmp| std::fs::write(tmp, b"good").map_err(at(tmp))).unwrap();
        let err = replace_with(&path, |tmp| {
            std::fs::write(tmp, b"ha").map_err(at(tmp))?;
            Err(at(tmp)(std::io::Error::other("disk full")))
        })
        .unwrap_err();
        assert!(err.to_string().contains("weights.bin.partial"), "{err}");
        assert_eq!(std::fs::read(&path).unwrap(), b"good");
        assert!(!partial_path(&path).exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }

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
