//! The evaluator's errors: each names the file, dataset or method it is about.

use std::path::PathBuf;

/// Why an evaluation step failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum EvalError {
    /// A user dataset was given a default dataset's name.
    #[error("--dataset {0}: that name is a default dataset's")]
    DefaultName(String),
    /// Reading or writing a file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// The I/O error.
        #[source]
        source: std::io::Error,
    },
    /// A CSV or JSON file is malformed or could not be written.
    #[error("{path}: {message}")]
    Csv {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// A dataset could not be read.
    #[error("dataset {name}: {source}")]
    Dataset {
        /// The dataset's name.
        name: String,
        /// The reader's error.
        #[source]
        source: pairs::DatasetError,
    },
    /// A dataset could not be generated.
    #[error("dataset {name}: generating it failed: {source}")]
    Generate {
        /// The dataset's name.
        name: String,
        /// The generator's error.
        #[source]
        source: Box<generator::generate::GenerateError>,
    },
    /// A method, dataset or flow source name is not registered.
    #[error("unknown {what} {name:?}; known: {known}")]
    Unknown {
        /// `method`, `dataset` or `flow source`.
        what: &'static str,
        /// The name asked for.
        name: String,
        /// The registered names, comma-separated.
        known: String,
    },
    /// A table could not be built or written.
    #[error("{what}: {source}")]
    Table {
        /// Which table.
        what: String,
        /// polars' error.
        #[source]
        source: polars::error::PolarsError,
    },
    /// A plot or picture could not be drawn.
    #[error("{path}: {message}")]
    Plot {
        /// The picture's file.
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
    /// Tuning was asked to read a dataset outside the validation split.
    #[error("dataset {name} is of the {split} split: baselines are tuned on validation data only")]
    NotValidation {
        /// The dataset's name.
        name: String,
        /// Its split.
        split: String,
    },
    /// A dataset holds no pairs.
    #[error("dataset {name} ({}) holds no pairs", dir.display())]
    EmptyDataset {
        /// The dataset's name.
        name: String,
        /// Its folder.
        dir: PathBuf,
    },
    /// The network's weights could not be loaded.
    #[error("network weights: {message}")]
    Weights {
        /// The weights folder or file (the message names it).
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
    /// A prediction file cannot be read or written (its structure, schema or header is
    /// broken; the error names the file).
    #[error(transparent)]
    Predictions(#[from] pairs::PredictionsError),
    /// The render benchmark's render cannot be made or read.
    #[error("render {name}: {message}")]
    Render {
        /// The render's name.
        name: String,
        /// What went wrong.
        message: String,
    },
    /// A render's ground truth or a joints-only prediction file cannot be used.
    #[error(transparent)]
    RenderFile(#[from] pairs::renders::RenderFileError),
    /// A prediction file does not fit the dataset it is scored on.
    #[error("predictions {}: {message}", path.display())]
    PredictionsMismatch {
        /// The file.
        path: PathBuf,
        /// What does not fit.
        message: String,
    },
}

impl From<pairs::atomic::FileError> for EvalError {
    fn from(e: pairs::atomic::FileError) -> Self {
        Self::Io { path: e.path, source: e.source }
    }
}
