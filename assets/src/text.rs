//! Reading asset files: bytes with the path in every error, and text that must be UTF-8.

use std::path::Path;

use super::ImportError;

/// The whole file.
pub fn read_bytes(path: &Path) -> Result<Vec<u8>, ImportError> {
    std::fs::read(path).map_err(|error| ImportError::Io { path: path.into(), error })
}

/// The file as UTF-8 text; names in URDF, OBJ and sidecar files must be UTF-8.
pub fn read_text(path: &Path) -> Result<String, ImportError> {
    utf8(path, read_bytes(path)?)
}

/// Bytes as UTF-8 text, or an error giving the offset of the first bad byte.
pub fn utf8(path: &Path, bytes: Vec<u8>) -> Result<String, ImportError> {
    String::from_utf8(bytes).map_err(|e| ImportError::NotUtf8 {
        path: path.into(),
        offset: e.utf8_error().valid_up_to(),
    })
}
