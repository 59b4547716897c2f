//! What `model infer` and `model animate` do, as library calls: load a weights folder, read
//! a user's two files or a dataset pair, run the inference procedure, describe its parts,
//! motions and joints, and write coloured PLYs or an animated glTF.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use burn::prelude::Device;
use pairs::dataset::viz::part_colour;
use pairs::dataset::Dataset;
use pairs::joint_estimate::{estimate_joints, JointParams};
use pairs::math::Point3;
use pairs::transform::rotation_angle_deg;
use pairs::{Cloud, JointKind, Pair, PairInput, PairKind, Prediction};

use crate::io::pointfile::{read_points, write_ply, PointFileError};
use crate::network::sampling::{farthest_point_sampling, SamplingError};
use crate::network::PartInductionNet;
use crate::train::checkpoint::{load_weights, CheckpointError};
use crate::train::config::{ConfigError, TrainConfig};

/// Why an application step failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum AppError {
    /// The weights folder's config is missing or invalid.
    #[error("{path}: {source}")]
    Config {
        /// The config file.
        path: PathBuf,
        /// The config error.
        #[source]
        source: ConfigError,
    },
    /// The weights could not be loaded.
    #[error(transparent)]
    Weights(#[from] CheckpointError),
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

/// The network of a weights folder (`config.toml` and `model.bpk`), on the CPU.
pub fn load_network_folder(dir: &Path) -> Result<PartInductionNet, AppError> {
    let config_path = dir.join("config.toml");
    let config = TrainConfig::load(&config_path.to_string_lossy())
        .map_err(|source| AppError::Config { path: config_path.clone(), source })?;
    Ok(load_weights(&config.network, &dir.join("model.bpk"), &Device::flex())?)
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
