//! What several commands do alike: progress bars, a dataset's first pairs, a table written
//! whole.

use std::path::Path;

use anyhow::{Context, Result};
use indicatif::{ProgressBar, ProgressStyle};

/// A progress bar over `len` pairs.
pub(crate) fn pairs_bar(len: u64) -> ProgressBar {
    ProgressBar::new(len).with_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:30}] {pos}/{len} pairs")
            .expect("a valid template")
            .progress_chars("=> "),
    )
}

/// A spinner with `message`, ticking until it is finished.
pub(crate) fn spinner(message: impl Into<String>) -> ProgressBar {
    let spinner = ProgressBar::new_spinner().with_message(message.into());
    spinner.enable_steady_tick(std::time::Duration::from_millis(120));
    spinner
}

/// The first `limit` pairs of a dataset folder (every pair without a limit).
pub(crate) fn read_dataset(dir: &Path, limit: Option<u32>) -> Result<Vec<pairs::Pair>> {
    let dataset = pairs::dataset::Dataset::open(dir)
        .with_context(|| format!("opening the dataset {}", dir.display()))?;
    let mut out = Vec::new();
    for pair in dataset.pairs().with_context(|| format!("reading {}", dir.display()))? {
        if limit.is_some_and(|n| out.len() >= n as usize) {
            break;
        }
        out.push(pair.with_context(|| format!("reading a pair of {}", dir.display()))?);
    }
    if out.is_empty() {
        anyhow::bail!("the dataset {} holds no pairs", dir.display());
    }
    Ok(out)
}

/// Writes `text` to `out`, replacing it whole or not at all.
pub(crate) fn write_table(out: &Path, text: &str) -> Result<()> {
    pairs::atomic::replace_file(out, |file| {
        std::io::Write::write_all(file, text.as_bytes()).map_err(pairs::atomic::at(out))
    })
    .with_context(|| format!("writing {}", out.display()))
}

/// The weights folder `dir` given as `flag`, on the CPU (the error names the flag; the
/// library's names the folder or file).
pub(crate) fn load_weights(dir: &Path, flag: &str) -> Result<crate::weights::Weights> {
    crate::weights::load(dir).with_context(|| flag.to_owned())
}
