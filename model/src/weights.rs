//! Weights folders: what every command that runs trained weights takes as `--weights`.
//!
//! A weights folder holds `model.bpk` (the network's parameters, burn's record) and
//! `config.toml` (the training config whose `network` table sized them). The shipped
//! weights (`model/weights/cpu`) are one; so is every checkpoint folder of `model train`
//! (its latest weights) and its `best/` (the weights of the best validation so far). A
//! checkpoint folder written before checkpoints carried `config.toml` still loads: its
//! `state.json` holds the same config.
//!
//! [`load`] and [`save`] are the only way in and out; the record itself is read and written
//! by [`read_record`] and [`write_record`] (checkpoints, `init_weights`, averaging).

use std::path::{Path, PathBuf};

use burn::prelude::*;
use burn::store::ModuleRecord;

use pairs::atomic::{at, replace_with, FileError};

use crate::network::config::{ConfigError, NetworkConfig};
use crate::network::PartInductionNet;
use crate::train::config::TrainConfig;

/// The parameters' file in a weights folder.
pub const MODEL_FILE: &str = "model.bpk";
/// The config's file in a weights folder.
pub const CONFIG_FILE: &str = "config.toml";
/// The checkpoint state that carries the config in folders written before `config.toml`.
const STATE_FILE: &str = "state.json";

/// Why a weights folder could not be read or written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum WeightsError {
    /// A file was given where a folder is expected.
    #[error(
        "{path} is a file; weights are a folder holding {CONFIG_FILE} and {MODEL_FILE} \
         (here: {folder})",
        folder = .path.parent().map_or_else(|| ".".into(), |p| p.display().to_string())
    )]
    NotAFolder {
        /// The file given.
        path: PathBuf,
    },
    /// The folder holds no `model.bpk`.
    #[error("{dir}: not a weights folder (no {MODEL_FILE}; the shipped weights are model/weights/cpu, a run's are its checkpoint folder or its best/)")]
    NoModel {
        /// The folder.
        dir: PathBuf,
    },
    /// The folder holds `model.bpk` but no config.
    #[error("{dir}: no {CONFIG_FILE} beside {MODEL_FILE} (nor the {STATE_FILE} of a checkpoint)")]
    NoConfig {
        /// The folder.
        dir: PathBuf,
    },
    /// The config does not parse or is invalid.
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// A checkpoint's `state.json` does not parse.
    #[error("{path}: {source}")]
    State {
        /// The file.
        path: PathBuf,
        /// The parser's error.
        #[source]
        source: serde_json::Error,
    },
    /// The config cannot be written as TOML.
    #[error("{path}: the config does not serialise: {message}")]
    Serialise {
        /// The file being written.
        path: PathBuf,
        /// The serialiser's message.
        message: String,
    },
    /// burn could not write or read a record (for example, sizes other than the config's).
    #[error("{path}: {message}")]
    Record {
        /// The file.
        path: PathBuf,
        /// burn's message.
        message: String,
    },
    /// File system error.
    #[error(transparent)]
    Io(#[from] FileError),
}

/// A loaded weights folder.
#[derive(Debug)]
pub struct Weights {
    /// The network, on the device it was loaded to.
    pub net: PartInductionNet,
    /// The config that sized it (its validation pairs are the ones to score it on).
    pub config: TrainConfig,
    /// The file the config was read from (`config.toml`, or an older checkpoint's
    /// `state.json`).
    pub config_file: PathBuf,
    /// The parameters' file.
    pub model_file: PathBuf,
}

/// The weights folder `dir`, on the CPU.
pub fn load(dir: &Path) -> Result<Weights, WeightsError> {
    load_on(dir, &Device::flex())
}

/// The weights folder `dir`, on `device`.
pub fn load_on(dir: &Path, device: &Device) -> Result<Weights, WeightsError> {
    if dir.is_file() {
        return Err(WeightsError::NotAFolder { path: dir.to_path_buf() });
    }
    let model_file = dir.join(MODEL_FILE);
    if !model_file.is_file() {
        return Err(WeightsError::NoModel { dir: dir.to_path_buf() });
    }
    let (config, config_file) = read_config(dir)?;
    let net = read_record(&config.network, &model_file, device)?;
    Ok(Weights { net, config, config_file, model_file })
}

/// The config of the weights folder `dir` and the file it came from.
pub fn read_config(dir: &Path) -> Result<(TrainConfig, PathBuf), WeightsError> {
    let toml = dir.join(CONFIG_FILE);
    if toml.is_file() {
        return Ok((TrainConfig::load(&toml.to_string_lossy())?, toml));
    }
    let state = dir.join(STATE_FILE);
    if state.is_file() {
        #[derive(serde::Deserialize)]
        struct State {
            config: TrainConfig,
        }
        let text = std::fs::read_to_string(&state).map_err(at(&state))?;
        let read: State = serde_json::from_str(&text)
            .map_err(|source| WeightsError::State { path: state.clone(), source })?;
        read.config.validate()?;
        return Ok((read.config, state));
    }
    Err(WeightsError::NoConfig { dir: dir.to_path_buf() })
}

/// Writes `net` and `config` as the weights folder `dir` (created if missing), each file
/// whole or not at all.
pub fn save(dir: &Path, net: &PartInductionNet, config: &TrainConfig) -> Result<(), WeightsError> {
    std::fs::create_dir_all(dir).map_err(at(dir))?;
    write_config(dir, config)?;
    write_record(net, &dir.join(MODEL_FILE))
}

/// Writes `config` as `dir/config.toml`, whole or not at all.
pub fn write_config(dir: &Path, config: &TrainConfig) -> Result<(), WeightsError> {
    let path = dir.join(CONFIG_FILE);
    let text = config
        .to_toml()
        .map_err(|e| WeightsError::Serialise { path: path.clone(), message: e.to_string() })?;
    replace_with(&path, |tmp| std::fs::write(tmp, text).map_err(at(tmp)))?;
    Ok(())
}

fn record(path: &Path) -> impl FnOnce(burn::store::RecordError) -> WeightsError + '_ {
    move |e| WeightsError::Record { path: path.to_path_buf(), message: e.to_string() }
}

/// Writes the network's parameters to the record file `path`, whole or not at all.
pub fn write_record(net: &PartInductionNet, path: &Path) -> Result<(), WeightsError> {
    replace_with(path, |tmp| net.clone().into_record().save(tmp).map_err(record(tmp)))
}

/// A network with `config`'s sizes and the parameters of the record file `path`, on `device`.
pub fn read_record(
    config: &NetworkConfig,
    path: &Path,
    device: &Device,
) -> Result<PartInductionNet, WeightsError> {
    let rec = ModuleRecord::load(path).map_err(record(path))?;
    // Building the network draws initial weights from burn's shared generator: take the
    // generator's turn, so a network being seeded on another thread is not disturbed.
    let net = crate::network::rng::exclusive(|| PartInductionNet::new(config, device));
    net.try_load_record(rec).map_err(record(path))
}
