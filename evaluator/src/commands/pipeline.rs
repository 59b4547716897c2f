//! The whole evaluation: make missing datasets, load them, run every selected row on every
//! selected dataset (reusing matching cached runs), then write the leaderboards, plots,
//! gallery, `LEADERBOARD.md` and the iteration board (from `net-iter`'s per-pass scores)
//! under the reports folder. Rows not selected still appear
//! in the tables when their cached runs match, so recomputing one row keeps the others; a
//! run limited to the first N pairs writes under `<reports>/limit-<N>/` and leaves the
//! full-dataset reports alone.

use std::path::PathBuf;

use crate::boards::gallery::write_gallery;
use crate::boards::iterations::{
    iteration_table, write_iterations, IterationRow, JointRow, ITERATIVE_ROW,
};
use crate::boards::leaderboard::{Leaderboards, Scored};
use crate::boards::plots::write_pcc_plots;
use crate::boards::render_joints::{score_joints, upsert as upsert_render_joints};
use crate::boards::report::write_report;
use crate::boards::sets::{set_board, write_set_board, ScoredSets, SetBoardRow};
use crate::datasets::{
    ensure_dataset, holds_sets, load_dataset, load_set_dataset, DatasetSpec, LoadedDataset,
    LoadedSets,
};
use crate::error::EvalError;
use crate::rows::registry::{Entry, Registry, Runner};
use crate::running::renders::{ensure_render, render_joints, RENDER_DATASET};
use crate::running::run::{cached_run, run_entry, FlowCache, RunOptions, RunResult};
use crate::running::sets::{cached_set_run, run_set_entry, runs_on_sets, SetRunResult};
use crate::tuning::{cached_sweep, sweep_key, tune, Sweep};

/// What to evaluate and where.
#[derive(Debug, Clone)]
pub struct Options {
    /// Datasets by name (empty: every default dataset).
    pub datasets: Vec<String>,
    /// Rows by name (empty: every registered row).
    pub methods: Vec<String>,
    /// Only the first pairs of each dataset (reports then go to `<reports>/limit-<N>`).
    pub limit: Option<usize>,
    /// Folder holding the dataset folders (`datasets`).
    pub datasets_root: PathBuf,
    /// Folder of the reports (`reports`).
    pub reports: PathBuf,
    /// Recompute runs even when cached.
    pub force: bool,
    /// Pairs per dataset shown in the gallery (the first ones of the file).
    pub gallery_pairs: usize,
    /// The validation sets tuned rows are tuned on (made when missing; never a test set):
    /// [`crate::datasets::validation_datasets`] for the benchmark.
    pub validation: Vec<DatasetSpec>,
}

/// Progress hooks for the binary's bars.
pub trait Progress: Sync {
    /// A dataset of `total` pairs is being generated; `done` pairs are written.
    fn generating(&self, dataset: &str, done: u64, total: u64);
    /// Row `entry` starts on `dataset` with `pairs` pairs.
    fn start(&self, entry: &str, dataset: &str, pairs: u64);
    /// One more pair is done.
    fn tick(&self);
    /// The row is done (`cached`: reused from the runs folder).
    fn finish(&self, entry: &str, dataset: &str, cached: bool);
    /// Something the user should know (a dataset regenerated, and why).
    fn notice(&self, message: &str) {
        let _ = message;
    }
}

/// Progress hooks that show nothing (tests, benches, library callers).
#[derive(Debug, Clone, Copy, Default)]
pub struct NoProgress;

impl Progress for NoProgress {
    fn generating(&self, _: &str, _: u64, _: u64) {}
    fn start(&self, _: &str, _: &str, _: u64) {}
    fn tick(&self) {}
    fn finish(&self, _: &str, _: &str, _: bool) {}
}

/// What an evaluation produced.
pub struct Summary {
    /// The leaderboards as written.
    pub boards: Leaderboards,
    /// The set board as written (`leaderboard_sets.csv`), empty without a set dataset.
    pub set_board: Vec<SetBoardRow>,
    /// Rows run afresh.
    pub fresh: usize,
    /// Rows reused from the cache.
    pub cached: usize,
    /// Failed pairs over all rows in the tables.
    pub failed: usize,
    /// Failed sets over all rows of the set board.
    pub failed_sets: usize,
    /// Where the reports were written.
    pub reports: PathBuf,
    /// The sweeps of the tuned rows in the tables.
    pub sweeps: Vec<Sweep>,
    /// The iteration board ([`ITERATIVE_ROW`] after every pass, per dataset), empty when no
    /// dataset has that row's run.
    pub iterations: Vec<IterationRow>,
    /// The joints of its first and last passes, per dataset.
    pub iteration_joints: Vec<JointRow>,
}

/// Runs the evaluation described by `options` over `registry`'s rows and `specs`' datasets.
pub fn evaluate(
    registry: &Registry,
    specs: &[DatasetSpec],
    options: &Options,
    progress: &dyn Progress,
) -> Result<Summary, EvalError> {
    let render_chosen = options.datasets.iter().any(|d| d == RENDER_DATASET);
    let selected_specs: Vec<&DatasetSpec> = if options.datasets.is_empty() {
        specs.iter().collect()
    } else {
        options
            .datasets
            .iter()
            .filter(|name| name.as_str() != RENDER_DATASET)
            .map(|name| {
                specs.iter().find(|s| &s.name == name).ok_or_else(|| EvalError::Unknown {
                    what: "dataset",
                    name: name.clone(),
                    known: specs.iter().map(|s| s.name.as_str()).collect::<Vec<_>>().join(", "),
                })
            })
            .collect::<Result<_, _>>()?
    };
    let selected = registry.select(&options.methods)?;
    let entries = registry.entries();
    let reports = match options.limit {
        Some(n) => options.reports.join(format!("limit-{n}")),
        None => options.reports.clone(),
    };
    // Selected datasets are made when missing; the others join the tables from the cache
    // when they exist on disk.
    let mut loaded: Vec<(LoadedDataset, bool)> = Vec::new();
    let mut loaded_sets: Vec<(LoadedSets, bool)> = Vec::new();
    for spec in specs {
        let chosen = selected_specs.iter().any(|s| s.name == spec.name);
        let dir = spec.dir(&options.datasets_root);
        if spec.is_user_render(&options.datasets_root) {
            continue;
        }
        if chosen {
            ensure_dataset(
                spec,
                &options.datasets_root,
                &|m| progress.notice(m),
                |done, total| progress.generating(&spec.name, done, total),
            )?;
        } else if !dir.join(pairs::dataset::MANIFEST_FILE).exists() {
            continue;
        }
        if holds_sets(spec, &dir) {
            loaded_sets.push((load_set_dataset(&spec.name, &dir, options.limit)?, chosen));
            continue;
        }
        loaded.push((load_dataset(&spec.name, &dir, options.limit)?, chosen));
    }
    let flows = FlowCache::default();
    let any_chosen =
        loaded.iter().any(|(_, chosen)| *chosen) || loaded_sets.iter().any(|(_, chosen)| *chosen);
    let (entries, sweeps) =
        resolve_tuning(entries, &selected, any_chosen, options, &flows, progress)?;
    let entries = entries.as_slice();
    let mut results: Vec<(usize, usize, RunResult)> = Vec::new();
    let (mut fresh, mut cached) = (0, 0);
    for (d, (dataset, chosen)) in loaded.iter().enumerate() {
        let run_options = RunOptions {
            runs: reports.join("runs"),
            force: options.force,
            gallery: dataset
                .pairs
                .iter()
                .take(options.gallery_pairs)
                .map(|p| p.id().to_owned())
                .collect(),
        };
        for (e, entry) in entries.iter().enumerate() {
            if !entry.runs_on(&dataset.name, dataset.cross_instance) {
                continue;
            }
            if !runs_now(entry, *chosen, &selected, options) {
                if let Some(result) = cached_run(entry, dataset, &run_options) {
                    results.push((d, e, result));
                }
                continue;
            }
            progress.start(&entry.name, &dataset.name, dataset.pairs.len() as u64);
            let result = run_entry(entry, dataset, &flows, &run_options, &|| progress.tick())?;
            progress.finish(&entry.name, &dataset.name, result.cached);
            if result.cached {
                cached += 1;
            } else {
                fresh += 1;
            }
            results.push((d, e, result));
        }
    }
    // Every segmentation row on every set dataset: its pairs (0, k) predicted, lifted to the
    // set and scored per set (`running::sets`).
    let mut set_results: Vec<(usize, usize, SetRunResult)> = Vec::new();
    for (d, (sets, chosen)) in loaded_sets.iter().enumerate() {
        let run_options =
            RunOptions { runs: reports.join("runs"), force: options.force, gallery: Vec::new() };
        let name = &sets.pairs.name;
        for (e, entry) in entries.iter().enumerate() {
            if !runs_on_sets(entry, name) {
                continue;
            }
            if !runs_now(entry, *chosen, &selected, options) {
                if let Some(result) = cached_set_run(entry, sets, &run_options) {
                    set_results.push((d, e, result));
                }
                continue;
            }
            progress.start(&entry.name, name, sets.pairs.pairs.len() as u64);
            let result = run_set_entry(entry, sets, &flows, &run_options, &|| progress.tick())?;
            progress.finish(&entry.name, name, result.cached);
            if result.cached {
                cached += 1;
            } else {
                fresh += 1;
            }
            set_results.push((d, e, result));
        }
    }
    let scored_sets: Vec<ScoredSets> = set_results
        .iter()
        .map(|(d, e, result)| ScoredSets {
            dataset: &loaded_sets[*d].0.pairs.name,
            entry: &entries[*e],
            rows: &result.rows,
        })
        .collect();
    let set_board = set_board(&scored_sets);
    let scored: Vec<Scored> = results
        .iter()
        .map(|(d, e, result)| Scored {
            dataset: &loaded[*d].0.name,
            cross_instance: loaded[*d].0.cross_instance,
            entry: &entries[*e],
            result,
        })
        .collect();
    let failed = scored.iter().map(|s| s.result.rows.iter().filter(|r| !r.scored()).count()).sum();
    let failed_sets = set_board.iter().map(|r| r.failed).sum();
    std::fs::create_dir_all(&reports)
        .map_err(|source| EvalError::Io { path: reports.clone(), source })?;
    let mut boards = Leaderboards::build(&scored)?;
    boards.write(&reports)?;
    write_set_board(&reports, &set_board)?;
    write_pcc_plots(&reports, &boards.curves)?;
    let datasets: Vec<&LoadedDataset> = loaded.iter().map(|(d, _)| d).collect();
    let gallery = write_gallery(&reports, options.gallery_pairs, &datasets, &scored)?;
    let sweeps: Vec<Sweep> =
        sweeps.into_iter().filter(|s| scored.iter().any(|r| r.entry.name == s.row)).collect();
    // The render benchmark: every selected row that runs on a pair's input, on the joints of
    // the default render's back-projected clouds, and of each render folder given with
    // `--dataset NAME=PATH` (not with --limit).
    if options.limit.is_none() {
        let mut renders = Vec::new();
        if render_chosen {
            let dir = ensure_render(&options.datasets_root, &|m| progress.notice(m))?;
            renders.push((RENDER_DATASET.to_owned(), dir));
        }
        for spec in &selected_specs {
            if spec.is_user_render(&options.datasets_root) {
                renders.push((spec.name.clone(), spec.dir(&options.datasets_root)));
            }
        }
        let chosen: Vec<&Entry> =
            entries.iter().filter(|e| selected.iter().any(|s| s.name == e.name)).collect();
        for (name, dir) in renders {
            let joints = render_joints(&chosen, &name, &dir, &|row| {
                progress.notice(&format!("{row} on {name}: joints"))
            })?;
            let truth = pairs::renders::read_truth(&dir)?;
            let rows: Vec<_> = joints
                .iter()
                .flat_map(|(row, predicted)| score_joints(&truth, predicted, &name, row))
                .collect();
            upsert_render_joints(&reports, &rows)?;
        }
    }
    write_report(&reports, &boards, &gallery, &sweeps, &set_board)?;
    let (mut iterations, mut iteration_joints) = (Vec::new(), Vec::new());
    for s in scored.iter().filter(|s| s.entry.name == ITERATIVE_ROW && !s.cross_instance) {
        if let Some(passes) = &s.result.passes {
            let (rows, joints) = iteration_table(s.dataset, passes);
            iterations.extend(rows);
            iteration_joints.extend(joints);
        }
    }
    if !iterations.is_empty() {
        write_iterations(&reports, &iterations, &iteration_joints)?;
    }
    Ok(Summary {
        boards,
        set_board,
        fresh,
        cached,
        failed,
        failed_sets,
        reports,
        sweeps,
        iterations,
        iteration_joints,
    })
}

/// Whether `entry` runs now on a dataset (`chosen`: selected by `--datasets`), rather than
/// joining the tables from its cached run: it is selected, and an external row (scored by
/// `evaluator score`) only when `--methods` names it.
fn runs_now(entry: &Entry, chosen: bool, selected: &[Entry], options: &Options) -> bool {
    let external = matches!(entry.runner, Runner::External(_));
    chosen
        && selected.iter().any(|s| s.name == entry.name)
        && (!external || options.methods.contains(&entry.name))
}

/// The rows with every tuned row's chosen parameters in place: a selected tuned row is tuned
/// (or its cached sweep reused) on the validation sets, generated when missing; an unselected
/// one takes its cached sweep when there is one, else it keeps an untuned fingerprint that no
/// cached run matches (so it stays out of the tables). The sweeps used are returned beside.
pub(crate) fn resolve_tuning(
    entries: &[Entry],
    selected: &[Entry],
    any_chosen: bool,
    options: &Options,
    flows: &FlowCache,
    progress: &dyn Progress,
) -> Result<(Vec<Entry>, Vec<Sweep>), EvalError> {
    let tuning_reports = &options.reports;
    let needs = |e: &Entry| any_chosen && selected.iter().any(|s| s.name == e.name);
    let must_tune = entries.iter().any(|e| e.grid.is_some() && needs(e));
    let mut validation = Vec::new();
    for spec in &options.validation {
        let dir = spec.dir(&options.datasets_root);
        if must_tune {
            ensure_dataset(spec, &options.datasets_root, &|m| progress.notice(m), |d, t| {
                progress.generating(&spec.name, d, t)
            })?;
        } else if !dir.join(pairs::dataset::MANIFEST_FILE).exists() {
            continue;
        }
        validation.push(load_dataset(&spec.name, &dir, None)?);
    }
    let validation: Vec<&LoadedDataset> = validation.iter().collect();
    let mut resolved = Vec::with_capacity(entries.len());
    let mut sweeps = Vec::new();
    for entry in entries {
        let Some(grid) = &entry.grid else {
            resolved.push(entry.clone());
            continue;
        };
        let key = sweep_key(&entry.name, grid, &entry.fingerprint, &validation);
        let sweep = if needs(entry) {
            progress.start(&format!("tuning {}", entry.name), "validation", grid_size(grid));
            let sweep = tune(
                &entry.name,
                grid,
                &entry.fingerprint,
                &validation,
                flows,
                tuning_reports,
                &|_| progress.tick(),
            )?;
            progress.finish(&format!("tuning {}", entry.name), "validation", false);
            Some(sweep)
        } else if validation.is_empty() {
            None
        } else {
            cached_sweep(tuning_reports, &entry.name, &key)
        };
        let mut entry = entry.clone();
        match sweep {
            Some(sweep) => {
                let (runner, fingerprint) = (grid.build)(&sweep.candidates[sweep.chosen].values);
                entry.fingerprint = format!("{fingerprint} on {}", entry.fingerprint);
                entry.runner = runner;
                sweeps.push(sweep);
            }
            None => entry.fingerprint = format!("untuned {}", entry.fingerprint),
        }
        entry.grid = None;
        resolved.push(entry);
    }
    Ok((resolved, sweeps))
}

/// Candidates of a grid before widening.
fn grid_size(grid: &crate::rows::grid::Grid) -> u64 {
    grid.axes.iter().map(|a| a.values.len() as u64).product()
}
