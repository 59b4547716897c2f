//! Files written whole or not at all. Each is written to a `.partial` sibling of its final
//! name and renamed onto it only once complete, so an interrupted or failed write never
//! leaves a half-written file and never destroys the old one. Every crate that writes
//! outputs (the evaluator's reports, the trainer's checkpoints and logs) goes through here.
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
}
