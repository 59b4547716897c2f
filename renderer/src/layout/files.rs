//! The files every layout writes: JSON, raw bytes, PNG images and 16-bit depth.

use std::path::Path;

use image::ExtendedColorType;
use serde::Serialize;

use crate::RenderError;

/// Writes pretty JSON.
pub(crate) fn write_json(path: &Path, value: &impl Serialize) -> Result<(), RenderError> {
    let mut text = serde_json::to_string_pretty(value)
        .map_err(|e| RenderError::Io { path: path.into(), error: std::io::Error::other(e) })?;
    text.push('\n');
    write_bytes(path, text.as_bytes())
}

/// Writes a file, creating its folder.
pub(crate) fn write_bytes(path: &Path, bytes: &[u8]) -> Result<(), RenderError> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)
            .map_err(|error| RenderError::Io { path: dir.into(), error })?;
    }
    std::fs::write(path, bytes).map_err(|error| RenderError::Io { path: path.into(), error })
}

/// Writes a PNG.
pub(crate) fn write_png(
    path: &Path,
    data: &[u8],
    width: u32,
    height: u32,
    colour: ExtendedColorType,
) -> Result<(), RenderError> {
    let bytes = scanner::images::png(data, width, height, colour)
        .map_err(|error| RenderError::Image { path: path.into(), error })?;
    write_bytes(path, &bytes)
}

/// Bytes of 16-bit values in the order the PNG encoder takes them (native).
pub(crate) fn u16_bytes(values: &[u16]) -> Vec<u8> {
    values.iter().flat_map(|d| d.to_ne_bytes()).collect()
}
