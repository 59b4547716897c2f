//! `model`: train the network stage by stage, score trained weights on the validation set,
//! run the whole inference procedure on a user's two files, or animate a dataset pair. Each
//! command's arguments and body live in the library's [`model::commands`].

use std::process::ExitCode;

use clap::{Parser, Subcommand};
use model::commands::average::AverageArgs;
use model::commands::diagnose::DiagnoseArgs;
use model::commands::infer::{AnimateArgs, InferArgs};
use model::commands::procedures::ProceduresArgs;
use model::commands::train::TrainArgs;
use model::commands::validate::ValidateArgs;
use model::commands::{average, diagnose, infer, procedures, train, validate};

#[derive(Parser, Debug)]
#[command(
    version,
    about = "Train, validate and run the part-induction network of Yi et al. 2018",
    after_help = "Weights are a folder holding config.toml and model.bpk: the shipped \
        model/weights/cpu, a checkpoint folder of `model train`, or its best/.\n\n\
        Examples:\n  \
        model train --config model/configs/cpu.toml      # train (or resume) the CPU config\n  \
        model train --config tiny --max-steps 20         # a built-in config by name\n  \
        model validate --weights checkpoints/cpu/best --against model/weights/cpu --pairs 960\n  \
        model diagnose --weights model/weights/cpu --pairs 240\n  \
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
    Train(TrainArgs),
    /// Score a weights folder on its config's validation set (EPE, Rand index, IoU, support
    /// IoU), or against a second one with paired-bootstrap intervals.
    Validate(ValidateArgs),
    /// Decompose the network's error by oracle substitution (flow, support, RPEN, subset
    /// ceiling); prints the table and writes it as CSV.
    Diagnose(DiagnoseArgs),
    /// Score the iterative procedure's variants (the paper's, the release's alignments,
    /// sub-problems, full-Q matching) side by side; prints the table and writes it as CSV.
    Procedures(ProceduresArgs),
    /// Average several weights folders of one network parameter by parameter (a "model
    /// soup") into a new weights folder.
    Average(AverageArgs),
    /// Run the inference procedure on two point clouds or meshes (.ply or .obj): print the
    /// parts, motions and joints, and write p_segments.ply and q_segments.ply.
    Infer(InferArgs),
    /// Animate a dataset pair: each found part moves from P to Q along its SE(3) geodesic,
    /// written as a binary glTF.
    Animate(AnimateArgs),
}

fn main() -> ExitCode {
    cli::run(|| match Cli::parse().command {
        Command::Train(args) => train::run(args),
        Command::Validate(args) => validate::run(args),
        Command::Diagnose(args) => diagnose::run(args),
        Command::Procedures(args) => procedures::run(args),
        Command::Average(args) => average::run(args),
        Command::Infer(args) => infer::run_infer(args),
        Command::Animate(args) => infer::run_animate(args),
    })
}
