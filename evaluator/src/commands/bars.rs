//! The evaluator's progress on the terminal: an indicatif bar for dataset generation and
//! one per row and dataset, with a line when each ends.

use std::sync::Mutex;

use indicatif::{ProgressBar, ProgressStyle};

use crate::commands::pipeline::Progress;

/// indicatif bars: one for dataset generation, one per row and dataset.
#[derive(Default)]
pub struct Bars {
    bar: Mutex<Option<ProgressBar>>,
}

impl Bars {
    fn new_bar(&self, total: u64, message: String) {
        let bar = ProgressBar::new(total);
        bar.set_style(
            ProgressStyle::with_template("{msg:40} [{bar:30}] {pos}/{len} {elapsed}<{eta}")
                .expect("the template is valid")
                .progress_chars("=> "),
        );
        bar.set_message(message);
        *self.bar.lock().unwrap_or_else(|e| e.into_inner()) = Some(bar);
    }
}

impl Progress for Bars {
    fn generating(&self, dataset: &str, done: u64, total: u64) {
        if done <= 1 {
            self.new_bar(total, format!("generating {dataset}"));
        }
        if let Some(bar) = self.bar.lock().unwrap_or_else(|e| e.into_inner()).as_ref() {
            bar.set_position(done);
        }
    }

    fn start(&self, entry: &str, dataset: &str, pairs: u64) {
        self.new_bar(pairs, format!("{entry} on {dataset}"));
    }

    fn tick(&self) {
        if let Some(bar) = self.bar.lock().unwrap_or_else(|e| e.into_inner()).as_ref() {
            bar.inc(1);
        }
    }

    fn finish(&self, entry: &str, dataset: &str, cached: bool) {
        if let Some(bar) = self.bar.lock().unwrap_or_else(|e| e.into_inner()).take() {
            bar.finish_and_clear();
        }
        let how = if cached { "cached" } else { "done" };
        eprintln!("{entry} on {dataset}: {how}");
    }

    fn notice(&self, message: &str) {
        eprintln!("{message}");
    }
}
