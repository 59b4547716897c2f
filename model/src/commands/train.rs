//! `model train`: train stage by stage, or resume from the checkpoint folder.

use std::path::PathBuf;

use anyhow::{Context, Result};
use burn::prelude::*;
use clap::ValueEnum;
use indicatif::{ProgressBar, ProgressStyle};

use crate::train::checkpoint::CheckpointDir;
use crate::train::config::TrainConfig;
use crate::train::{Budget, RunPaths, Trainer};

/// Train stage by stage; resumes from the checkpoint folder if it holds a checkpoint.
#[derive(clap::Args, Debug)]
pub struct TrainArgs {
    /// Config file, or a built-in name (paper, cpu, tiny).
    #[arg(long)]
    pub config: String,
    /// Checkpoint folder [default: checkpoints/<config name>]; it is a weights folder of
    /// the latest weights, and its best/ one of the best validation so far.
    #[arg(long)]
    pub checkpoints: Option<PathBuf>,
    /// Report folder for log.csv, validation.csv and loss.png
    /// [default: reports/training/<config name>].
    #[arg(long)]
    pub reports: Option<PathBuf>,
    /// Stop after this many steps (a checkpoint is written), e.g. to time a config.
    #[arg(long)]
    pub max_steps: Option<u64>,
    /// Stop after this many minutes of training (a checkpoint is written; the next
    /// `train` resumes from it), e.g. for a bounded slot on a GPU machine.
    #[arg(long)]
    pub max_minutes: Option<f64>,
    /// Device to train on.
    #[arg(long, value_enum, default_value_t = DeviceKind::Cpu)]
    pub device: DeviceKind,
}

/// Where tensors live.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum DeviceKind {
    /// burn's flex CPU backend.
    Cpu,
    /// NVIDIA GPU 0 (build with `--features cuda`).
    Cuda,
}

/// Runs `model train`.
pub fn run(args: TrainArgs) -> Result<()> {
    if let Some(m) = args.max_minutes.filter(|m| !(m.is_finite() && *m > 0.0)) {
        anyhow::bail!("--max-minutes must be a positive number of minutes, not {m}");
    }
    let budget = Budget {
        steps: args.max_steps,
        time: args.max_minutes.map(|m| std::time::Duration::from_secs_f64(m * 60.0)),
    };
    let config = TrainConfig::load(&args.config)?;
    let mut paths = RunPaths::for_config(&config);
    if let Some(dir) = args.checkpoints {
        paths.checkpoints = CheckpointDir::new(dir);
    }
    if let Some(dir) = args.reports {
        paths.reports = dir;
    }
    let total = config.total_pairs();
    let mut trainer = Trainer::new(config, paths.clone(), device(args.device)?.autodiff())
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
    Ok(())
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
