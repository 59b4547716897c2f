//! Why a render failed.

use std::path::PathBuf;

use scanner::scene::SceneError;

/// Why a render failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RenderError {
    /// A setting is out of range.
    #[error("render setting {field}: {reason}")]
    Config {
        /// The field.
        field: String,
        /// What is wrong.
        reason: String,
    },
    /// A camera file or camera is unusable.
    #[error("cameras ({what}): {reason}")]
    Cameras {
        /// The file and camera.
        what: String,
        /// What is wrong.
        reason: String,
    },
    /// An object cannot be ray cast.
    #[error("object {object}: {source}")]
    Scene {
        /// The object's folder name.
        object: String,
        /// Why.
        source: SceneError,
    },
    /// A file cannot be read or written (the reason is in the message, not a source, so
    /// that an error chain does not print it twice).
    #[error("{path}: {error}")]
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        error: std::io::Error,
    },
    /// An image cannot be encoded or decoded.
    #[error("image {path}: {error}")]
    Image {
        /// The file.
        path: PathBuf,
        /// Why.
        error: image::ImageError,
    },
    /// The output folder cannot be written.
    #[error(transparent)]
    Output(#[from] pairs::atomic::OutputError),
    /// A layout cannot hold this object.
    #[error("object {object} cannot be written in the {layout} layout: {reason}")]
    Layout {
        /// The object's folder name.
        object: String,
        /// The layout.
        layout: &'static str,
        /// Why.
        reason: String,
    },
}
