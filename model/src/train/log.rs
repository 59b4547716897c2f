//! The training log: one CSV row per step (`log.csv`), one per validation (`validation.csv`),
//! and `loss.png`, redrawn at every checkpoint. On resume, rows after the checkpoint's step
//! (work that was lost) are dropped, so the files always match the weights.

use std::fs::File;
use std::io::{BufRead, BufReader, BufWriter, Write};
use std::path::{Path, PathBuf};

use crate::train::objective::{LossTerms, TERM_NAMES};
use crate::train::plot::{draw_loss_curves, Curves};
use crate::train::validation::Scores;
use pairs::atomic::{at, partial_path, replace_file, FileError};

/// One optimiser step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepRow {
    /// Steps taken, this one included.
    pub step: u64,
    /// Training pairs consumed, this step's included.
    pub pairs: u64,
    /// Training stage (1, 2, 3).
    pub stage: u8,
    /// Learning rate of the step.
    pub learning_rate: f64,
    /// Total weighted loss.
    pub loss: f32,
    /// Its terms.
    pub terms: LossTerms,
    /// Wall-clock seconds of the step.
    pub seconds: f64,
    /// Where the step's time went.
    pub phases: StepPhases,
}

/// Wall-clock seconds of a step's phases. With several replicas the batch, forward and
/// backward phases run on every shard at once, and each is the slowest shard's; what the
/// step's `seconds` holds besides them is waiting for training pairs and summing the shards'
/// gradients.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StepPhases {
    /// Building the batch's tensors from the pairs.
    pub batch: f64,
    /// The forward pass and the loss.
    pub forward: f64,
    /// The backward pass.
    pub backward: f64,
    /// The optimiser's update.
    pub optimizer: f64,
}

impl StepPhases {
    /// The slowest of `self` and `other` in every phase.
    pub fn max(self, other: Self) -> Self {
        Self {
            batch: self.batch.max(other.batch),
            forward: self.forward.max(other.forward),
            backward: self.backward.max(other.backward),
            optimizer: self.optimizer.max(other.optimizer),
        }
    }
}

/// One validation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ValidationRow {
    /// Steps taken.
    pub step: u64,
    /// Training pairs consumed.
    pub pairs: u64,
    /// Stage of the weights scored.
    pub stage: u8,
    /// The scores.
    pub scores: Scores,
}

/// Why the log could not be written.
#[derive(Debug, thiserror::Error)]
pub enum LogError {
    /// File system error.
    #[error(transparent)]
    Io(#[from] FileError),
    /// The plot could not be drawn.
    #[error("{path}: {message}")]
    Plot {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> LogError + '_ {
    move |e| at(path)(e).into()
}

const STEP_HEADER: &str = "step,pairs,stage,learning_rate,loss";
const PHASES_HEADER: &str = "batch_seconds,forward_seconds,backward_seconds,optimizer_seconds";
const VALIDATION_HEADER: &str = "step,pairs,stage,epe,rand_index,iou,support_iou";

/// The open log of a run.
#[derive(Debug)]
pub struct Log {
    dir: PathBuf,
    steps: BufWriter<File>,
    validations: BufWriter<File>,
    curves: Curves,
}

/// Keeps the rows of `path` up to step `last` (the first column), rewriting the file, and
/// opens it for appending; returns the kept rows. Rows with fewer fields than `header` (from
/// a log written before a column was added) get empty fields, read back as NaN.
fn reopen(
    path: &Path,
    header: &str,
    last: u64,
) -> Result<(BufWriter<File>, Vec<Vec<f64>>), LogError> {
    let mut kept = Vec::new();
    let columns = header.split(',').count();
    if path.exists() {
        let file = File::open(path).map_err(io(path))?;
        for line in BufReader::new(file).lines().skip(1) {
            let line = line.map_err(io(path))?;
            let mut fields: Vec<f64> =
                line.split(',').map(|f| f.parse().unwrap_or(f64::NAN)).collect();
            if fields.first().is_some_and(|&s| s <= last as f64) {
                let missing = columns.saturating_sub(fields.len());
                fields.resize(fields.len() + missing, f64::NAN);
                kept.push((format!("{line}{}", ",".repeat(missing)), fields));
            }
        }
    }
    let tmp = partial_path(path);
    replace_file(path, |out| {
        writeln!(out, "{header}").map_err(io(&tmp))?;
        for (line, _) in &kept {
            writeln!(out, "{line}").map_err(io(&tmp))?;
        }
        Ok::<(), LogError>(())
    })?;
    let file = std::fs::OpenOptions::new().append(true).open(path).map_err(io(path))?;
    Ok((BufWriter::new(file), kept.into_iter().map(|(_, f)| f).collect()))
}

fn optional(v: Option<f32>) -> String {
    v.map(|v| v.to_string()).unwrap_or_default()
}

impl Log {
    /// Opens the log in `dir`, keeping rows up to step `last`.
    pub fn open(dir: &Path, last: u64) -> Result<Self, LogError> {
        std::fs::create_dir_all(dir).map_err(io(dir))?;
        let header = format!("{STEP_HEADER},{},seconds,{PHASES_HEADER}", TERM_NAMES.join(","));
        let (steps, rows) = reopen(&dir.join("log.csv"), &header, last)?;
        let (validations, vrows) = reopen(&dir.join("validation.csv"), VALIDATION_HEADER, last)?;
        let mut curves = Curves::default();
        for r in rows {
            curves.loss.push((r[1], r[2] as u8, r[4]));
        }
        for r in vrows {
            curves.validation.push((r[1], r[3], r[5], r[6]));
        }
        Ok(Self { dir: dir.to_path_buf(), steps, validations, curves })
    }

    /// Appends a step.
    pub fn step(&mut self, row: &StepRow) -> Result<(), LogError> {
        let terms: Vec<String> = row.terms.values().iter().map(|v| optional(*v)).collect();
        let path = self.dir.join("log.csv");
        let p = row.phases;
        writeln!(
            self.steps,
            "{},{},{},{},{},{},{:.3},{:.3},{:.3},{:.3},{:.3}",
            row.step,
            row.pairs,
            row.stage,
            row.learning_rate,
            row.loss,
            terms.join(","),
            row.seconds,
            p.batch,
            p.forward,
            p.backward,
            p.optimizer
        )
        .map_err(io(&path))?;
        self.steps.flush().map_err(io(&path))?;
        self.curves.loss.push((row.pairs as f64, row.stage, f64::from(row.loss)));
        Ok(())
    }

    /// Appends a validation.
    pub fn validation(&mut self, row: &ValidationRow) -> Result<(), LogError> {
        let s = row.scores;
        let path = self.dir.join("validation.csv");
        writeln!(
            self.validations,
            "{},{},{},{},{},{},{}",
            row.step, row.pairs, row.stage, s.epe, s.rand_index, s.iou, s.support_iou
        )
        .map_err(io(&path))?;
        self.validations.flush().map_err(io(&path))?;
        self.curves.validation.push((row.pairs as f64, s.epe, s.iou, s.support_iou));
        Ok(())
    }

    /// Flushes the CSVs and redraws `loss.png`.
    pub fn plot(&mut self) -> Result<(), LogError> {
        let path = self.dir.join("log.csv");
        self.steps.flush().map_err(io(&path))?;
        let png = self.dir.join("loss.png");
        draw_loss_curves(&self.curves, &png)
            .map_err(|message| LogError::Plot { path: png.clone(), message })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resume_drops_lost_rows_and_pads_rows_of_an_older_header() {
        let dir = tempfile::tempdir().expect("temporary folder");
        let path = dir.path().join("validation.csv");
        std::fs::write(
            &path,
            "step,pairs,stage,epe,rand_index,iou\n10,80,1,0.5,0.6,0.2\n20,160,2,0.4,0.6,0.2\n",
        )
        .expect("old log");
        let mut log = Log::open(dir.path(), 15).expect("reopens");
        assert_eq!(log.curves.validation.len(), 1);
        assert!(log.curves.validation[0].3.is_nan());
        let scores = Scores { epe: 0.25, rand_index: 0.75, iou: 0.5, support_iou: 0.625 };
        log.validation(&ValidationRow { step: 30, pairs: 240, stage: 2, scores }).expect("row");
        let text = std::fs::read_to_string(&path).expect("log");
        assert_eq!(
            text,
            "step,pairs,stage,epe,rand_index,iou,support_iou\n10,80,1,0.5,0.6,0.2,\n30,240,2,0.25,0.75,0.5,0.625\n"
        );
    }

    #[test]
    fn step_rows_carry_the_phases_and_older_rows_get_empty_ones() {
        let dir = tempfile::tempdir().expect("temporary folder");
        let path = dir.path().join("log.csv");
        let old = "step,pairs,stage,learning_rate,loss,correspondence,flow,motion,support,\
                   segment,continuation,seconds\n1,8,1,0.001,2.5,2,0.5,,,,,0.750\n";
        std::fs::write(&path, old).expect("old log");
        let mut log = Log::open(dir.path(), 1).expect("reopens");
        let phases = StepPhases { batch: 0.01, forward: 0.2, backward: 0.4, optimizer: 0.05 };
        let row = StepRow {
            step: 2,
            pairs: 16,
            stage: 1,
            learning_rate: 0.001,
            loss: 2.0,
            terms: LossTerms::default(),
            seconds: 0.7,
            phases,
        };
        log.step(&row).expect("row");
        let text = std::fs::read_to_string(&path).expect("log");
        let lines: Vec<&str> = text.lines().collect();
        assert!(lines[0].ends_with(
            ",seconds,batch_seconds,forward_seconds,backward_seconds,optimizer_seconds"
        ));
        assert_eq!(lines[1], "1,8,1,0.001,2.5,2,0.5,,,,,0.750,,,,");
        assert_eq!(lines[2], "2,16,1,0.001,2,,,,,,,0.700,0.010,0.200,0.400,0.050");
    }
}
