//! `model`: train the network stage by stage, score trained weights on the validation set,
//! run the whole inference procedure on a user's two files, or animate a dataset pair.

use std::path::PathBuf;

use anyhow::{Context, Result};
use burn::prelude::*;
use clap::{Parser, Subcommand, ValueEnum};
use indicatif::{ProgressBar, ProgressStyle};
use model::diagnose::{diagnose, DiagnoseParams};
use model::inference::InferenceParams;
use model::io::animation::{write_animation, AnimationParams};
use model::io::commands::{
    describe, input_from_files, load_network_folder, pair_from_dataset, write_segment_plys,
};
use model::procedures::{self, release_variants, score_procedure, Variant};
use model::train::average::average_weights;
use model::train::checkpoint::{load_weights, save_weights, CheckpointDir};
use model::train::config::TrainConfig;
use model::train::validation::{
    compare, score_pairs_aligned, validation_pairs, PairScores, Scores, VALIDATION_SEED,
};
use model::train::{Budget, RunPaths, Trainer};
use pairs::{PairInput, Prediction};

#[derive(Parser, Debug)]
#[command(
    version,
    about = "Train, validate and run the part-induction network of Yi et al. 2018",
    after_help = "Examples:\n  \
        model train --config model/configs/cpu.toml      # train (or resume) the CPU config\n  \
        model train --config tiny --max-steps 20         # a built-in config by name\n  \
        model validate --config cpu --weights model/weights/cpu/model.bpk\n  \
        model diagnose --config cpu --weights model/weights/cpu/model.bpk --pairs 240\n  \
        model infer P.ply Q.obj --out out/               # parts, motions, coloured PLYs\n  \
        model animate --pair sf2f:sf2f-00000-1 --out anim.glb"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Train stage by stage; resumes from the checkpoint folder if it holds a checkpoint.
    Train {
        /// Config file, or a built-in name (paper, cpu, tiny).
        #[arg(long)]
        config: String,
        /// Checkpoint folder [default: checkpoints/<config name>].
        #[arg(long)]
        checkpoints: Option<PathBuf>,
        /// Report folder for log.csv, validation.csv and loss.png
        /// [default: reports/training/<config name>].
        #[arg(long)]
        reports: Option<PathBuf>,
        /// Stop after this many steps (a checkpoint is written), e.g. to time a config.
        #[arg(long)]
        max_steps: Option<u64>,
        /// Stop after this many minutes of training (a checkpoint is written; the next
        /// `train` resumes from it), e.g. for a bounded slot on a GPU machine.
        #[arg(long)]
        max_minutes: Option<f64>,
        /// Device to train on.
        #[arg(long, value_enum, default_value_t = DeviceKind::Cpu)]
        device: DeviceKind,
    },
    /// Score weights on the config's validation set (EPE, Rand index, IoU, support IoU).
    Validate {
        /// Config file, or a built-in name; its network sizes must match the weights.
        #[arg(long)]
        config: String,
        /// Weights file (burn record, e.g. checkpoints/cpu/best.bpk).
        #[arg(long)]
        weights: PathBuf,
        /// Validation pairs to score [default: the config's `validation_pairs`]; a larger
        /// set holds every pair of a smaller one.
        #[arg(long)]
        pairs: Option<u32>,
        /// A second weights file of the same network (the shipped weights, say): score it on
        /// the same pairs and print each score's difference (`--weights` minus this one)
        /// with a 95% paired-bootstrap interval over the pairs.
        #[arg(long)]
        against: Option<PathBuf>,
        /// Config of the `--against` weights, where it differs from `--config` in a switch
        /// that keeps the parameter shapes (an ablation's), e.g. `hypothesis_projection`;
        /// the validation pairs are still `--config`'s [default: --config].
        #[arg(long, requires = "against")]
        against_config: Option<String>,
        /// Bootstrap resamples for `--against`.
        #[arg(long, default_value_t = 2000)]
        resamples: usize,
        /// Global alignments of P before the `--weights` pass (the authors' release: 2),
        /// for weights trained without relative pose (`relative_pose = false`).
        #[arg(long, default_value_t = 0)]
        global_alignments: usize,
        /// Global alignments before the `--against` pass.
        #[arg(long, default_value_t = 0, requires = "against")]
        against_global_alignments: usize,
    },
    /// Decompose the network's error by oracle substitution, without training: the flow
    /// module against the matching alone and the true flow at subset sizes; on the true
    /// flow, the support module against a residual threshold rule (on the network's
    /// hypotheses, a rigid and a similarity fit per true part) and the true same-part
    /// matrix, each through the RPEN; the subset ceiling; the pairs' motion scales.
    /// Prints the table and writes it as CSV.
    Diagnose {
        /// Config file, or a built-in name; its network sizes must match the weights.
        #[arg(long)]
        config: String,
        /// Weights file (burn record).
        #[arg(long)]
        weights: PathBuf,
        /// A dataset folder (datasets/<name>) to diagnose instead of the validation pairs.
        #[arg(long)]
        dataset: Option<PathBuf>,
        /// Pairs to diagnose: the first N validation pairs, or of the dataset [default: the
        /// config's `validation_pairs`; every pair of a dataset].
        #[arg(long)]
        pairs: Option<u32>,
        /// Where to write the table as CSV (replaced whole).
        #[arg(long, default_value = "diagnose.csv")]
        out: PathBuf,
    },
    /// Score the iterative procedure's variants side by side on the same pairs: the
    /// paper's (the `net-iter` row), the authors' release's two global alignments,
    /// per-segment sub-problems and full-Q matching each alone, and all three; each with
    /// its paired-bootstrap 95% interval against the paper's, on all pairs and per kind.
    /// Prints the table and writes it as CSV.
    Procedures {
        /// Weights folder (config.toml and model.bpk).
        #[arg(long, default_value = "model/weights/cpu")]
        weights: PathBuf,
        /// A dataset folder (datasets/<name>) to score on, repeatable [default: the
        /// validation pairs of the weights' config, a quarter of them SF2P and a quarter
        /// SP2P when the config trains on scans].
        #[arg(long)]
        dataset: Vec<PathBuf>,
        /// Validation pairs, or the first N of each dataset [default: 240; every pair
        /// of a dataset].
        #[arg(long)]
        pairs: Option<u32>,
        /// Only these variants (comma-separated: paper, +align, +sub, +full, release); the
        /// first is the one the others are compared with.
        #[arg(long, value_delimiter = ',')]
        variants: Vec<String>,
        /// Bootstrap resamples.
        #[arg(long, default_value_t = 2000)]
        resamples: usize,
        /// Where to write the table as CSV (replaced whole).
        #[arg(long, default_value = "procedures.csv")]
        out: PathBuf,
    },
    /// Average several weights files of one network parameter by parameter (a "model soup":
    /// checkpoints fine-tuned from the same weights), into a new weights file.
    Average {
        /// Config file, or a built-in name; its network sizes must match every file.
        #[arg(long)]
        config: String,
        /// The weights files, averaged in this order.
        #[arg(long, num_args = 1.., required = true)]
        weights: Vec<PathBuf>,
        /// Where to write the averaged weights (replaced whole, or not at all).
        #[arg(long)]
        out: PathBuf,
    },
    /// Run the inference procedure on two point clouds or meshes (.ply or .obj): print the
    /// parts, motions and joints, and write p_segments.ply and q_segments.ply.
    Infer {
        /// The source shape P.
        p: PathBuf,
        /// The target shape Q.
        q: PathBuf,
        /// Folder for the coloured PLYs.
        #[arg(long, default_value = ".")]
        out: PathBuf,
        #[command(flatten)]
        run: RunArgs,
    },
    /// Animate a dataset pair: each found part moves from P to Q along its SE(3) geodesic,
    /// written as a binary glTF (one node per segment, keyframes).
    Animate {
        /// The pair, as <dataset>:<id> or <dataset>:<index>.
        #[arg(long)]
        pair: String,
        /// Folder of the datasets.
        #[arg(long, default_value = "datasets")]
        datasets_root: PathBuf,
        /// The .glb file to write.
        #[arg(long, default_value = "anim.glb")]
        out: PathBuf,
        /// Keyframes from P to Q.
        #[arg(long, default_value_t = 31)]
        keyframes: usize,
        #[command(flatten)]
        run: RunArgs,
    },
}

/// The network and procedure options shared by `infer` and `animate`.
#[derive(clap::Args, Debug)]
struct RunArgs {
    /// Weights folder (config.toml and model.bpk).
    #[arg(long, default_value = "model/weights/cpu")]
    weights: PathBuf,
    /// Most passes of the iterative procedure (1: a single pass).
    #[arg(long, default_value_t = 10)]
    iterations: usize,
    /// Search 48 rotations of P for the initial orientation (for pairs whose orientations
    /// differ a lot).
    #[arg(long)]
    rotation_search: bool,
    /// Global flow-then-Kabsch alignments of P before the passes (the authors' release
    /// does 2).
    #[arg(long, default_value_t = 0)]
    global_alignments: usize,
    /// Refine by per-segment sub-problems within a geodesic radius of each segment, as the
    /// authors' release does, instead of on the whole deformed pair.
    #[arg(long)]
    sub_problems: bool,
    /// End the last pass on Q's points (the release's full matching; for a full Q only:
    /// both files are taken as full shapes).
    #[arg(long)]
    full_matching: bool,
    /// Points per cloud (files with more are reduced by farthest-point sampling).
    #[arg(long, default_value_t = 512)]
    points: usize,
}

impl RunArgs {
    fn params(&self) -> InferenceParams {
        InferenceParams {
            max_iterations: self.iterations.max(1),
            rotation_search: self.rotation_search,
            global_alignments: self.global_alignments,
            sub_problems: self.sub_problems,
            full_matching: self.full_matching,
            ..InferenceParams::iterative()
        }
    }

    fn infer(&self, input: &PairInput) -> Result<Prediction> {
        let net = load_network_folder(&self.weights)
            .with_context(|| format!("loading the weights folder {}", self.weights.display()))?;
        let spinner = ProgressBar::new_spinner().with_message("inferring");
        spinner.enable_steady_tick(std::time::Duration::from_millis(120));
        let inference = net.infer(input, &self.params()).context("running the network")?;
        spinner.finish_and_clear();
        for (i, it) in inference.iterations.iter().enumerate() {
            tracing::info!(
                "pass {}: {} segments, mean flow change {:.4}",
                i + 1,
                it.prediction.motions.len(),
                it.change
            );
        }
        Ok(inference.prediction())
    }
}

/// `model procedures`: the variants on the pairs, the table printed and written to `out`.
fn run_procedures(
    weights: &std::path::Path,
    datasets: &[PathBuf],
    count: Option<u32>,
    names: &[String],
    resamples: usize,
    out: &std::path::Path,
) -> Result<()> {
    let all = release_variants();
    let variants: Vec<Variant> = if names.is_empty() {
        all
    } else {
        names
            .iter()
            .map(|n| {
                all.iter().find(|v| v.name == n).cloned().with_context(|| {
                    let known: Vec<&str> = all.iter().map(|v| v.name).collect();
                    format!("--variants: no variant {n:?} (known: {})", known.join(", "))
                })
            })
            .collect::<Result<_>>()?
    };
    let config_path = weights.join("config.toml");
    let config = TrainConfig::load(&config_path.to_string_lossy())?;
    let net = load_network_folder(weights)
        .with_context(|| format!("loading the weights folder {}", weights.display()))?;
    let pairs = if datasets.is_empty() {
        validation_pairs(config.points, count.unwrap_or(240), config.scanned_per_pair > 0)
            .context("generating the validation pairs")?
    } else {
        let mut pairs = Vec::new();
        for dir in datasets {
            pairs.extend(read_dataset(dir, count)?);
        }
        pairs
    };
    let mut scored = Vec::new();
    for variant in &variants {
        let spinner = ProgressBar::new_spinner().with_message(format!(
            "{} on {} pairs",
            variant.name,
            pairs.len()
        ));
        spinner.enable_steady_tick(std::time::Duration::from_millis(120));
        let s = score_procedure(&net, &pairs, variant)
            .with_context(|| format!("running the {} procedure", variant.name))?;
        spinner.finish_and_clear();
        tracing::info!("{}: {:.1} s", variant.name, s.seconds);
        scored.push(s);
    }
    let lines = procedures::table(&pairs, &scored, resamples, 20_181_201)
        .context("comparing the variants")?;
    println!("{} pairs, weights {}", pairs.len(), weights.display());
    println!(
        "{:<8} {:<5} {:>5} {:>7} {:>7} {:>7} {:>6}  {:<26} {:<26}",
        "variant", "group", "pairs", "EPE", "RI", "IoU", "passes", "ΔEPE [95%]", "ΔIoU [95%]"
    );
    let d = |x: Option<model::train::validation::Difference>| {
        x.map_or(String::new(), |d| format!("{:+.4} [{:+.4},{:+.4}]", d.value, d.low, d.high))
    };
    for l in &lines {
        println!(
            "{:<8} {:<5} {:>5} {:>7.4} {:>7.4} {:>7.4} {:>6.2}  {:<26} {:<26}",
            l.variant,
            l.group,
            l.pairs,
            l.scores.epe,
            l.scores.rand_index,
            l.scores.iou,
            l.passes,
            d(l.against_first.map(|c| c.epe)),
            d(l.against_first.map(|c| c.iou)),
        );
    }
    let seconds: Vec<String> =
        scored.iter().map(|s| format!("{} {:.1} s", s.name, s.seconds)).collect();
    println!("time: {}", seconds.join(", "));
    let csv = procedures::to_csv(&lines);
    pairs::atomic::replace_file(out, |file| {
        std::io::Write::write_all(file, csv.as_bytes()).map_err(pairs::atomic::at(out))
    })
    .with_context(|| format!("writing {}", out.display()))?;
    println!("written to {}", out.display());
    Ok(())
}

/// Where tensors live.
#[derive(Debug, Clone, Copy, ValueEnum)]
enum DeviceKind {
    /// burn's flex CPU backend.
    Cpu,
    /// NVIDIA GPU 0 (build with `--features cuda`).
    Cuda,
}

fn device(kind: DeviceKind) -> Result<Device> {
    match kind {
        DeviceKind::Cpu => Ok(Device::flex()),
        #[cfg(feature = "cuda")]
        DeviceKind::Cuda => {
            cuda_probe()?;
            Ok(Device::cuda(0))
        }
        #[cfg(not(feature = "cuda"))]
        DeviceKind::Cuda => {
            anyhow::bail!("this build has no CUDA support; rebuild with `--features cuda`")
        }
    }
}

/// burn's CUDA backend loads libcuda and libnvrtc on its first kernel and, when one is
/// missing, panics on a thread of its own (and the main thread then on a closed channel):
/// ask cudarc first, with the panic it raises for a missing library caught and kept quiet.
#[cfg(feature = "cuda")]
fn cuda_probe() -> Result<()> {
    fn quietly<T>(f: impl FnOnce() -> T + std::panic::UnwindSafe) -> Option<T> {
        let hook = std::panic::take_hook();
        std::panic::set_hook(Box::new(|_| {}));
        let out = std::panic::catch_unwind(f).ok();
        std::panic::set_hook(hook);
        out
    }
    match quietly(|| cudarc::driver::CudaContext::new(0).map(drop)) {
        None => anyhow::bail!(
            "--device cuda: the NVIDIA driver's libcuda.so does not load (no driver on this \
             machine, or not on the library path)"
        ),
        Some(Err(e)) => anyhow::bail!("--device cuda: CUDA device 0 does not open: {e:?}"),
        Some(Ok(())) => {}
    }
    match quietly(|| {
        cudarc::nvrtc::compile_ptx("extern \"C\" __global__ void probe() {}").map(drop)
    }) {
        None => anyhow::bail!(
            "--device cuda: libnvrtc does not load; kernels compile with NVRTC, from the CUDA \
             toolkit or the `nvidia-cuda-nvrtc` Python wheel, on LD_LIBRARY_PATH \
             (model/TRAINING.md, \"The GPU path\")"
        ),
        Some(Err(e)) => anyhow::bail!("--device cuda: NVRTC does not compile a kernel: {e:?}"),
        Some(Ok(())) => Ok(()),
    }
}

/// jemalloc keeps freed large blocks for reuse (see the workspace's Cargo.toml).
#[cfg(not(target_env = "msvc"))]
#[global_allocator]
static ALLOCATOR: tikv_jemallocator::Jemalloc = tikv_jemallocator::Jemalloc;

fn main() -> Result<()> {
    tracing_subscriber::fmt()
        .with_env_filter(
            tracing_subscriber::EnvFilter::try_from_default_env()
                .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new("info")),
        )
        .with_writer(std::io::stderr)
        .init();
    match Cli::parse().command {
        Command::Train { config, checkpoints, reports, max_steps, max_minutes, device: kind } => {
            if let Some(m) = max_minutes.filter(|m| !(m.is_finite() && *m > 0.0)) {
                anyhow::bail!("--max-minutes must be a positive number of minutes, not {m}");
            }
            let budget = Budget {
                steps: max_steps,
                time: max_minutes.map(|m| std::time::Duration::from_secs_f64(m * 60.0)),
            };
            let config = TrainConfig::load(&config)?;
            let mut paths = RunPaths::for_config(&config);
            if let Some(dir) = checkpoints {
                paths.checkpoints = CheckpointDir::new(dir);
            }
            if let Some(dir) = reports {
                paths.reports = dir;
            }
            let total = config.total_pairs();
            let mut trainer = Trainer::new(config, paths.clone(), device(kind)?.autodiff())
                .context("starting the run")?;
            let bar = ProgressBar::new(total).with_style(
                ProgressStyle::with_template(
                    "{elapsed_precise} [{bar:30}] {pos}/{len} pairs ({per_sec}, eta {eta}) {msg}",
                )
                .expect("a valid template")
                .progress_chars("=> "),
            );
            bar.set_position(trainer.state().pairs);
            trainer
                .run(budget, |p| {
                    bar.set_position(p.row.pairs);
                    let v = p.validation.map_or(String::new(), |v| {
                        format!(
                            " | val EPE {:.3} RI {:.3} IoU {:.3} support IoU {:.3}",
                            v.scores.epe, v.scores.rand_index, v.scores.iou, v.scores.support_iou
                        )
                    });
                    bar.set_message(format!("stage {} loss {:.4}{v}", p.row.stage, p.row.loss));
                })
                .context("training")?;
            bar.finish();
            let state = trainer.state();
            println!(
                "{} steps, {} pairs, {:.0} s of training; checkpoint in {}, log in {}",
                state.step,
                state.pairs,
                state.seconds,
                paths.checkpoints.root().display(),
                paths.reports.display()
            );
            if let Some(best) = state.best {
                println!(
                    "best validation (stage {}, {} pairs): EPE {:.4}, RI {:.4}, IoU {:.4}{} -> {}",
                    best.stage,
                    best.pairs,
                    best.epe,
                    best.rand_index,
                    best.iou,
                    best.support_iou.map(|s| format!(", support IoU {s:.4}")).unwrap_or_default(),
                    paths.checkpoints.best().display()
                );
            }
        }
        Command::Validate {
            config,
            weights,
            pairs,
            against,
            against_config,
            resamples,
            global_alignments,
            against_global_alignments,
        } => {
            let config = TrainConfig::load(&config)?;
            let other_config = match &against_config {
                Some(name) => TrainConfig::load(name)?,
                None => config.clone(),
            };
            let count = pairs.unwrap_or(config.validation_pairs);
            if count == 0 {
                anyhow::bail!("--pairs must be at least 1");
            }
            let load = |network, path: &PathBuf| {
                load_weights(network, path, &Device::flex())
                    .with_context(|| format!("loading weights {}", path.display()))
            };
            let net = load(&config.network, &weights)?;
            let other =
                against.as_ref().map(|path| load(&other_config.network, path)).transpose()?;
            let pairs = validation_pairs(config.points, count, config.scanned_per_pair > 0)
                .context("generating the validation pairs")?;
            let bar = ProgressBar::new(pairs.len() as u64 * (1 + u64::from(other.is_some())))
                .with_style(
                    ProgressStyle::with_template("{elapsed_precise} [{bar:30}] {pos}/{len} pairs")
                        .expect("a valid template")
                        .progress_chars("=> "),
                );
            let scored = |net, alignments| -> Result<Vec<PairScores>> {
                let mut all = Vec::with_capacity(pairs.len());
                for chunk in pairs.chunks(8) {
                    all.extend(score_pairs_aligned(net, chunk, alignments)?);
                    bar.inc(chunk.len() as u64);
                }
                Ok(all)
            };
            let a = scored(&net, global_alignments)
                .with_context(|| format!("scoring {}", weights.display()))?;
            let b = match (&other, &against) {
                (Some(net), Some(path)) => Some(
                    scored(net, against_global_alignments)
                        .with_context(|| format!("scoring {}", path.display()))?,
                ),
                _ => None,
            };
            bar.finish_and_clear();
            let line = |name: &std::path::Path, s: Scores| {
                println!(
                    "{}: {} validation pairs: EPE {:.4}, RI {:.4}, IoU {:.4}, support IoU on the true flow {:.4}",
                    name.display(),
                    pairs.len(),
                    s.epe,
                    s.rand_index,
                    s.iou,
                    s.support_iou
                )
            };
            line(&weights, Scores::of(&a));
            if let (Some(b), Some(path)) = (b, &against) {
                line(path, Scores::of(&b));
                let c = compare(&a, &b, resamples, VALIDATION_SEED).context("comparing")?;
                println!(
                    "difference (first minus second), 95% paired-bootstrap interval over {resamples} resamples:"
                );
                for (name, d) in [
                    ("EPE", c.epe),
                    ("RI", c.rand_index),
                    ("IoU", c.iou),
                    ("support IoU", c.support_iou),
                ] {
                    println!("  {name:<12} {:+.4}  [{:+.4}, {:+.4}]", d.value, d.low, d.high);
                }
            }
        }
        Command::Procedures { weights, dataset, pairs, variants, resamples, out } => {
            run_procedures(&weights, &dataset, pairs, &variants, resamples, &out)?;
        }
        Command::Diagnose { config, weights, dataset, pairs, out } => {
            let config = TrainConfig::load(&config)?;
            let net = load_weights(&config.network, &weights, &Device::flex())
                .with_context(|| format!("loading weights {}", weights.display()))?;
            let pairs = match &dataset {
                None => {
                    let count = pairs.unwrap_or(config.validation_pairs);
                    validation_pairs(config.points, count, config.scanned_per_pair > 0)
                        .context("generating the validation pairs")?
                }
                Some(dir) => read_dataset(dir, pairs)?,
            };
            let bar = ProgressBar::new(pairs.len() as u64).with_style(
                ProgressStyle::with_template("{elapsed_precise} [{bar:30}] {pos}/{len} pairs")
                    .expect("a valid template")
                    .progress_chars("=> "),
            );
            let diagnosis = diagnose(&net, &pairs, &DiagnoseParams::default(), |done| {
                bar.set_position(done as u64)
            })
            .context("diagnosing")?;
            bar.finish_and_clear();
            println!("{} pairs, weights {}", diagnosis.pairs, weights.display());
            println!("{:<72} {:>11} {:>7} {:>7}", "row", "support IoU", "IoU", "EPE");
            let cell = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4}"));
            for r in &diagnosis.rows {
                println!(
                    "{:<72} {:>11} {:>7} {:>7}",
                    r.name,
                    cell(r.support_iou),
                    cell(r.iou),
                    cell(r.epe)
                );
            }
            let s = diagnosis.scale;
            println!(
                "per-pair motion scale |s - 1|: median {:.4}, 90th percentile {:.4}, max {:.4}",
                s.median, s.p90, s.max
            );
            let csv = diagnosis.to_csv();
            pairs::atomic::replace_file(&out, |file| {
                std::io::Write::write_all(file, csv.as_bytes()).map_err(pairs::atomic::at(&out))
            })
            .with_context(|| format!("writing {}", out.display()))?;
            println!("wrote {}", out.display());
        }
        Command::Average { config, weights, out } => {
            let config = TrainConfig::load(&config)?;
            let net = average_weights(&config.network, &weights, &Device::flex())
                .context("averaging the weights")?;
            save_weights(&net, &out).with_context(|| format!("writing {}", out.display()))?;
            println!("wrote the mean of {} weights files to {}", weights.len(), out.display());
        }
        Command::Infer { p, q, out, run } => {
            let input = input_from_files(&p, &q, run.points).context("reading the input files")?;
            let prediction = run.infer(&input)?;
            print!("{}", describe(&input, &prediction));
            let files = write_segment_plys(&out, &input, &prediction)
                .with_context(|| format!("writing the coloured clouds into {}", out.display()))?;
            for f in files {
                println!("wrote {}", f.display());
            }
        }
        Command::Animate { pair, datasets_root, out, keyframes, run } => {
            let pair = pair_from_dataset(&datasets_root, &pair)
                .with_context(|| format!("reading {pair} from {}", datasets_root.display()))?;
            let input = pair.input();
            let prediction = run.infer(input)?;
            print!("{}", describe(input, &prediction));
            let params = AnimationParams { keyframes, ..AnimationParams::default() };
            write_animation(
                &out,
                &input.p.points,
                &prediction.segments_p,
                &prediction.motions,
                &input.q.points,
                &params,
            )
            .with_context(|| format!("writing {}", out.display()))?;
            println!("wrote {}", out.display());
        }
    }
    Ok(())
}

/// The first `limit` pairs of a dataset folder (every pair without a limit).
fn read_dataset(dir: &std::path::Path, limit: Option<u32>) -> Result<Vec<pairs::Pair>> {
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
