//! The default registry of `--all`: the `gt` oracle, `one-part`, the network (`net`) from the
//! shipped weights, and every segmenter on the ground-truth flow (oracle rows) and on the
//! network's flow (the paper's protocol).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use burn::prelude::Device;
use model::checkpoint::load_weights;
use model::config::TrainConfig;
use model::predict::NetworkMethod;
use pairs::{Method, Segmenter};
use sha2::{Digest, Sha256};

use crate::error::EvalError;
use crate::reference::OnePart;
use crate::registry::{Board, FlowSource, Registry};

/// The shipped weights the default rows use (a folder with `config.toml` and `model.bpk`).
pub const DEFAULT_WEIGHTS: &str = "model/weights/cpu";

/// Fingerprint of code that has no parameters or weights: the evaluator's version.
fn code_fingerprint(name: &str) -> String {
    format!("{name} evaluator-{}", env!("CARGO_PKG_VERSION"))
}

/// The network as a method, with the sha256 of its config and weights as fingerprint.
pub fn load_network(weights: &Path) -> Result<(Arc<dyn Method>, String), EvalError> {
    let (config_path, model_path) = (weights.join("config.toml"), weights.join("model.bpk"));
    let fail = |path: &PathBuf, message: String| EvalError::Weights { path: path.clone(), message };
    let config = TrainConfig::load(&config_path.to_string_lossy())
        .map_err(|e| fail(&config_path, e.to_string()))?;
    let net = load_weights(&config.network, &model_path, &Device::flex())
        .map_err(|e| fail(&model_path, e.to_string()))?;
    let mut hash = Sha256::new();
    for path in [&config_path, &model_path] {
        let bytes = std::fs::read(path).map_err(|e| fail(path, e.to_string()))?;
        hash.update(&bytes);
    }
    let fingerprint = format!("net {:x}", hash.finalize());
    Ok((Arc::new(NetworkMethod::new("net", net)), fingerprint))
}

/// The default rows, with the network loaded from `weights`.
pub fn standard_registry(weights: &Path) -> Result<Registry, EvalError> {
    let (net, net_fingerprint) = load_network(weights)?;
    let mut registry = Registry::new();
    registry.oracle();
    registry.method(net.clone(), Board::Both, &net_fingerprint);
    let one_part: Arc<dyn Segmenter> = Arc::new(OnePart);
    let sources =
        [(FlowSource::GroundTruth, String::new()), (FlowSource::Method(net), net_fingerprint)];
    for (source, source_fingerprint) in sources {
        let fingerprint = format!("{} on {source_fingerprint}", code_fingerprint("one-part"));
        registry.combine(one_part.clone(), source, &fingerprint, None);
    }
    Ok(registry)
}
