//! `model infer` and `model animate`: read a user's two files or a dataset pair, run the
//! inference procedure of a weights folder, describe its parts, motions and joints, and
//! write coloured PLYs or an animated glTF.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use pairs::dataset::viz::part_colour;
use pairs::dataset::Dataset;
use pairs::joint_estimate::{estimate_joints, JointParams};
use pairs::math::Point3;
use pairs::transform::rotation_angle_deg;
use pairs::{Cloud, JointKind, Pair, PairInput, PairKind, Prediction};

use crate::commands::shared::{load_weights, spinner};
use crate::inference::InferenceParams;
use crate::io::animation::{write_animation, AnimationParams};
use crate::io::pointfile::{read_points, write_ply, PointFileError};
use crate::network::sampling::{farthest_point_sampling, SamplingError};

/// Run the inference procedure on two point clouds or meshes (.ply or .obj): print the
/// parts, motions and joints, and write p_segments.ply and q_segments.ply.
#[derive(clap::Args, Debug)]
pub struct InferArgs {
    /// The source shape P.
    pub p: PathBuf,
    /// The target shape Q.
    pub q: PathBuf,
    /// Folder for the coloured PLYs.
    #[arg(long, default_value = ".")]
    pub out: PathBuf,
    /// The network and procedure options.
    #[command(flatten)]
    pub run: RunArgs,
}

/// Animate a dataset pair: each found part moves from P to Q along its SE(3) geodesic,
/// written as a binary glTF (one node per segment, keyframes).
#[derive(clap::Args, Debug)]
pub struct AnimateArgs {
    /// The pair, as <dataset>:<id> or <dataset>:<index>.
    #[arg(long)]
    pub pair: String,
    /// Folder of the datasets.
    #[arg(long, default_value = "datasets")]
    pub datasets_root: PathBuf,
    /// The .glb file to write.
    #[arg(long, default_value = "anim.glb")]
    pub out: PathBuf,
    /// Keyframes from P to Q.
    #[arg(long, default_value_t = 31)]
    pub keyframes: usize,
    /// The network and procedure options.
    #[command(flatten)]
    pub run: RunArgs,
}

/// The network and procedure options shared by `infer` and `animate`.
#[derive(clap::Args, Debug)]
pub struct RunArgs {
    /// Weights folder (config.toml and model.bpk).
    #[arg(long, default_value = "model/weights/cpu")]
    pub weights: PathBuf,
    /// Most passes of the iterative procedure (1: a single pass).
    #[arg(long, default_value_t = 10)]
    pub iterations: usize,
    /// Search 48 rotations of P for the initial orientation (for pairs whose orientations
    /// differ a lot).
    #[arg(long)]
    pub rotation_search: bool,
    /// Global flow-then-Kabsch alignments of P before the passes (the authors' release
    /// does 2).
    #[arg(long, default_value_t = 0)]
    pub global_alignments: usize,
    /// Refine by per-segment sub-problems within a geodesic radius of each segment, as the
    /// authors' release does, instead of on the whole deformed pair.
    #[arg(long)]
    pub sub_problems: bool,
    /// End the last pass on Q's points (the release's full matching; for a full Q only:
    /// both files are taken as full shapes).
    #[arg(long)]
    pub full_matching: bool,
    /// Points per cloud (files with more are reduced by farthest-point sampling).
    #[arg(long, default_value_t = 512)]
    pub points: usize,
}

impl RunArgs {
    /// The inference procedure these options choose.
    pub fn params(&self) -> InferenceParams {
        InferenceParams {
            max_iterations: self.iterations.max(1),
            rotation_search: self.rotation_search,
            global_alignments: self.global_alignments,
            sub_problems: self.sub_problems,
            full_matching: self.full_matching,
            ..InferenceParams::iterative()
        }
    }

    /// The prediction of the weights folder's network on `input` by the chosen procedure.
    pub fn infer(&self, input: &PairInput) -> Result<Prediction> {
        let weights = load_weights(&self.weights, "--weights")?;
        let spinner = spinner("inferring");
        let inference = weights.net.infer(input, &self.params()).context("running the network")?;
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

/// Runs `model infer`.
pub fn run_infer(args: InferArgs) -> Result<()> {
    let input =
        input_from_files(&args.p, &args.q, args.run.points).context("reading the input files")?;
    let prediction = args.run.infer(&input)?;
    print!("{}", describe(&input, &prediction));
    let files = write_segment_plys(&args.out, &input, &prediction)
        .with_context(|| format!("writing the coloured clouds into {}", args.out.display()))?;
    for f in files {
        println!("wrote {}", f.display());
    }
    Ok(())
}

/// Runs `model animate`.
pub fn run_animate(args: AnimateArgs) -> Result<()> {
    let pair = pair_from_dataset(&args.datasets_root, &args.pair)
        .with_context(|| format!("reading {} from {}", args.pair, args.datasets_root.display()))?;
    let input = pair.input();
    let prediction = args.run.infer(input)?;
    print!("{}", describe(input, &prediction));
    let params = AnimationParams { keyframes: args.keyframes, ..AnimationParams::default() };
    write_animation(
        &args.out,
        &input.p.points,
        &prediction.segments_p,
        &prediction.motions,
        &input.q.points,
        &params,
    )
    .with_context(|| format!("writing {}", args.out.display()))?;
    println!("wrote {}", args.out.display());
    Ok(())
}

/// Why reading the input or writing the output failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum AppError {
    /// A point file could not be read or written.
    #[error(transparent)]
    PointFile(#[from] PointFileError),
    /// A cloud is unusable (too few points, not finite).
    #[error("{path}: {source}")]
    Cloud {
        /// The file.
        path: PathBuf,
        /// The sampling error.
        #[source]
        source: SamplingError,
    },
    /// A cloud's points all coincide, so it cannot be normalised.
    #[error("{0}: all points coincide")]
    Degenerate(PathBuf),
    /// A dataset could not be read.
    #[error("dataset {path}: {source}")]
    Dataset {
        /// The dataset folder.
        path: PathBuf,
        /// The dataset error.
        #[source]
        source: pairs::DatasetError,
    },
    /// The `<dataset>:<id>` argument is malformed or names no pair.
    #[error("pair {0}: expected <dataset>:<id or index> naming a pair of the dataset")]
    Pair(String),
}

/// A normalised cloud of at most `points` points from a `.ply` or `.obj` file (meshes are
/// sampled; larger clouds are reduced by farthest-point sampling).
pub fn cloud_from_file(path: &Path, points: usize) -> Result<Cloud, AppError> {
    let mut read = read_points(path, points)?;
    if read.len() > points {
        let plain: Vec<[f32; 3]> = read.iter().map(|p| [p.x, p.y, p.z]).collect();
        let keep = farthest_point_sampling(&plain, points)
            .map_err(|source| AppError::Cloud { path: path.to_path_buf(), source })?;
        read = keep.iter().map(|&i| read[i]).collect();
    }
    Cloud::normalise(&read).ok_or_else(|| AppError::Degenerate(path.to_path_buf()))
}

/// The pair input of two files (kind SF2F: full shapes are assumed).
pub fn input_from_files(p: &Path, q: &Path, points: usize) -> Result<PairInput, AppError> {
    Ok(PairInput {
        id: format!("{} -> {}", p.display(), q.display()),
        kind: PairKind::Sf2f,
        p: cloud_from_file(p, points)?,
        q: cloud_from_file(q, points)?,
    })
}

/// The pair `<dataset>:<id>` (or `<dataset>:<index>`, counting from 0) under `root`.
pub fn pair_from_dataset(root: &Path, spec: &str) -> Result<Pair, AppError> {
    let (name, id) = spec.split_once(':').ok_or_else(|| AppError::Pair(spec.to_owned()))?;
    let dir = root.join(name);
    let fail = |source| AppError::Dataset { path: dir.clone(), source };
    let dataset = Dataset::open(&dir).map_err(fail)?;
    let index: Option<usize> = id.parse().ok();
    for (i, pair) in dataset.pairs().map_err(fail)?.enumerate() {
        let pair = pair.map_err(fail)?;
        if pair.id() == id || index == Some(i) {
            return Ok(pair);
        }
    }
    Err(AppError::Pair(spec.to_owned()))
}

/// A human-readable account of a prediction: every segment's size in P and Q, its motion,
/// and its joint relative to the largest segment.
pub fn describe(input: &PairInput, prediction: &Prediction) -> String {
    let joints = estimate_joints(
        &input.p.points,
        &prediction.segments_p,
        &prediction.motions,
        &JointParams::default(),
    );
    let count = |labels: &[u32], k: usize| labels.iter().filter(|&&l| l as usize == k).count();
    let mut text = format!("{} segments\n", prediction.motions.len());
    for (k, m) in prediction.motions.iter().enumerate() {
        let axis = pairs::math::Rotation3::from_matrix(&m.rotation)
            .axis()
            .map_or(String::from("-"), |a| format!("({:.3}, {:.3}, {:.3})", a.x, a.y, a.z));
        let t = m.translation;
        let _ = writeln!(
            text,
            "segment {k}: {} points in P, {} in Q; rotation {:.1}° about {axis}, translation \
             ({:.3}, {:.3}, {:.3}), scale {:.3}",
            count(&prediction.segments_p, k),
            count(&prediction.segments_q, k),
            rotation_angle_deg(&m.rotation),
            t.x,
            t.y,
            t.z,
            m.scale
        );
        let joint = match joints.get(k).copied().flatten() {
            None => "  joint: none (base, or moves with it)".to_owned(),
            Some(j) => format!(
                "  joint: {} axis ({:.3}, {:.3}, {:.3}) pivot ({:.3}, {:.3}, {:.3}), {} {:.3}",
                j.kind.as_str(),
                j.axis.x,
                j.axis.y,
                j.axis.z,
                j.pivot.x,
                j.pivot.y,
                j.pivot.z,
                if j.kind == JointKind::Revolute { "angle (rad)" } else { "distance" },
                j.value
            ),
        };
        let _ = writeln!(text, "{joint}");
    }
    text
}

/// Writes `p_segments.ply` and `q_segments.ply` into `dir`, each in its file's own frame
/// (the normalisation undone), coloured by segment; returns the files written.
pub fn write_segment_plys(
    dir: &Path,
    input: &PairInput,
    prediction: &Prediction,
) -> Result<Vec<PathBuf>, AppError> {
    std::fs::create_dir_all(dir).map_err(pairs::atomic::at(dir)).map_err(PointFileError::from)?;
    let mut written = Vec::new();
    for (name, cloud, labels) in [
        ("p_segments.ply", &input.p, &prediction.segments_p),
        ("q_segments.ply", &input.q, &prediction.segments_q),
    ] {
        let points: Vec<Point3> =
            cloud.points.iter().map(|x| cloud.normalisation.invert(x)).collect();
        let colours: Vec<[u8; 3]> = labels.iter().map(|&l| part_colour(l as u8)).collect();
        let path = dir.join(name);
        write_ply(&path, &points, &colours)?;
        written.push(path);
    }
    Ok(written)
}
