//! Writing report files whole or not at all: each is written beside its final name and
//! renamed into place, so an interrupted or failed run never leaves a half-written table.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use crate::error::EvalError;

/// Writes `path` through `write`, replacing any old file only once `write` succeeded.
pub fn replace_file(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<File>) -> Result<(), EvalError>,
) -> Result<(), EvalError> {
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(".partial");
    let tmp: PathBuf = path.with_file_name(name);
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| EvalError::Io { path, source }
    };
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(io(dir))?;
    }
    let mut out = BufWriter::new(File::create(&tmp).map_err(io(&tmp))?);
    let written = write(&mut out).and_then(|()| out.flush().map_err(io(&tmp)));
    if let Err(e) = written {
        let _ = std::fs::remove_file(&tmp);
        return Err(e);
    }
    drop(out);
    std::fs::rename(&tmp, path).map_err(io(path))
}
