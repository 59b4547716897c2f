//! Datasets for other methods (`generator export --format`): a dataset folder rewritten in
//! the layouts other methods read, so that their code runs on our pairs unchanged.
//!
//! - [`Format::YiMat`]: the `.mat` files of the paper authors' code
//!   (ericyi/articulated-part-induction): `pairs.mat`, `flow.mat`, `ids.txt` (module `yi`);
//! - [`Format::MbsNpz`]: MultiBodySync's folder (huangjh-pub/multibody-sync): `meta.json`,
//!   `data/%06d.npz`, `ids.txt` (module `mbs`).
//!
//! docs/FORMAT.md ("Exports for other methods") documents both layouts. The files are
//! written by hand (a MAT v5 writer in `mat`, NPY headers in `npy`, one pickle in
//! `pickle`), with no time stamps: the same dataset gives byte-identical files. The
//! output folder is written through [`Staging`]: a non-empty folder is refused unless
//! forced, and a failed or interrupted export leaves it as it was.

mod mat;
mod mbs;
mod npy;
mod pickle;
mod yi;

use std::path::{Path, PathBuf};

use pairs::dataset::Dataset;
use pairs::DatasetError;

use pairs::atomic::{write_file, OutputError, Staging};

/// An export layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// The paper authors' `.mat` files (`yi-mat`).
    YiMat,
    /// MultiBodySync's `meta.json` and `.npz` files (`mbs-npz`).
    MbsNpz,
}

impl Format {
    /// Every format, in the order of the CLI's help.
    pub const ALL: [Format; 2] = [Format::YiMat, Format::MbsNpz];

    /// The format's name on the command line.
    pub fn as_str(self) -> &'static str {
        match self {
            Format::YiMat => "yi-mat",
            Format::MbsNpz => "mbs-npz",
        }
    }
}

impl std::fmt::Display for Format {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl std::str::FromStr for Format {
    type Err = String;

    /// `yi-mat` or `mbs-npz`, in any case.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Format::ALL.into_iter().find(|f| f.as_str().eq_ignore_ascii_case(s)).ok_or_else(|| {
            let names: Vec<_> = Format::ALL.iter().map(|f| f.as_str()).collect();
            format!("unknown export format {s:?}; expected one of: {}", names.join(", "))
        })
    }
}

/// What an export wrote.
#[derive(Debug, Clone)]
pub struct FormatSummary {
    /// Pairs (or sets) exported.
    pub pairs: usize,
    /// Files written.
    pub files: usize,
    /// Their total size in bytes.
    pub bytes: u64,
}

/// Why an export failed; every message names the file, pair or field concerned.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum FormatError {
    /// The dataset folder cannot be read (not a dataset, or a broken file).
    #[error(transparent)]
    Dataset(#[from] DatasetError),
    /// The output folder cannot be written (not empty without force, not a folder, ...).
    #[error(transparent)]
    Output(#[from] OutputError),
    /// The dataset's manifest lacks what the format needs.
    #[error("{path}: {reason}")]
    Manifest {
        /// The manifest file.
        path: PathBuf,
        /// What is missing or wrong.
        reason: String,
    },
    /// A pair does not fit the format's array shapes.
    #[error("pair {pair}: {reason}")]
    Shape {
        /// The pair's id.
        pair: String,
        /// What differs, and what the format needs.
        reason: String,
    },
    /// A file would exceed what its format can hold.
    #[error("{path}: {reason}")]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// What is too large.
        reason: String,
    },
    /// The output folder is the dataset folder or holds it: replacing it would delete the
    /// dataset.
    #[error(
        "{out} holds the dataset {dataset}; exporting there would replace it: choose another \
         output folder"
    )]
    OutputHoldsDataset {
        /// The output folder.
        out: PathBuf,
        /// The dataset folder.
        dataset: PathBuf,
    },
}

/// MultiBodySync's name of the dataset's split (`config.split` of the manifest):
/// `train`, `val` or `test`.
fn mbs_split(dataset: &Dataset) -> Result<&'static str, FormatError> {
    let path = dataset.dir().join(pairs::dataset::MANIFEST_FILE);
    let split = dataset.manifest().origin.config.get("split").and_then(|s| s.as_str());
    match split {
        Some("train") => Ok("train"),
        Some("validation") => Ok("val"),
        Some("test") => Ok("test"),
        other => Err(FormatError::Manifest {
            path,
            reason: format!(
                "config.split is {other:?}; mbs-npz needs \"train\", \"validation\" or \"test\" \
                 to choose meta.json's list"
            ),
        }),
    }
}

/// Refuses an output folder that is the dataset folder or one of its parents.
fn check_output_apart(dataset: &Path, out: &Path) -> Result<(), FormatError> {
    let (Ok(dataset_abs), Ok(out_abs)) = (dataset.canonicalize(), out.canonicalize()) else {
        return Ok(());
    };
    if dataset_abs.starts_with(&out_abs) {
        return Err(FormatError::OutputHoldsDataset { out: out.into(), dataset: dataset.into() });
    }
    Ok(())
}

/// Exports the dataset folder `dataset` in `format` into the folder `out` (refused when
/// `out` is not empty, unless `force`); pairs are read in file order, and `progress` gets
/// the number of pairs exported so far.
pub fn export_dataset(
    format: Format,
    dataset: &Path,
    out: &Path,
    force: bool,
    mut progress: impl FnMut(u64),
) -> Result<FormatSummary, FormatError> {
    let data = Dataset::open(dataset)?;
    check_output_apart(dataset, out)?;
    let split = match format {
        Format::MbsNpz => Some(mbs_split(&data)?),
        Format::YiMat => None,
    };
    let staging = Staging::new(out, force)?;
    let dir = staging.path();
    let mut count = 0usize;
    let sizes = match format {
        Format::YiMat if data.holds_sets() => {
            let path = dataset.join(pairs::dataset::MANIFEST_FILE);
            let reason = "a set dataset: yi-mat holds pairs (export it as mbs-npz)".to_string();
            return Err(FormatError::Manifest { path, reason });
        }
        Format::YiMat => {
            let mut export = yi::YiExport::default();
            for pair in data.pairs()? {
                export.add(&pair?)?;
                count += 1;
                progress(count as u64);
            }
            export.write(dir)?
        }
        Format::MbsNpz => {
            let files = dir.join("data");
            std::fs::create_dir(&files).map_err(OutputError::io(&files))?;
            let mut sizes = Vec::new();
            let mut ids = String::new();
            let mut add = |id: &str, npz: Vec<u8>| -> Result<(), FormatError> {
                let path = files.join(format!("{count:06}.npz"));
                sizes.push(write_file(&path, &npz)?);
                ids.push_str(id);
                ids.push('\n');
                count += 1;
                progress(count as u64);
                Ok(())
            };
            if data.holds_sets() {
                for set in data.sets()? {
                    let set = set?;
                    add(set.id(), mbs::set_npz(&set)?)?;
                }
            } else {
                for pair in data.pairs()? {
                    let pair = pair?;
                    add(pair.id(), mbs::npz(&pair)?)?;
                }
            }
            let split = split.expect("mbs-npz reads the split first");
            let meta = mbs::meta_json(split, count);
            sizes.push(write_file(&dir.join("meta.json"), meta.as_bytes())?);
            sizes.push(write_file(&dir.join("ids.txt"), ids.as_bytes())?);
            sizes
        }
    };
    staging.commit()?;
    Ok(FormatSummary { pairs: count, files: sizes.len(), bytes: sizes.iter().sum() })
}

#[cfg(test)]
mod tests;
