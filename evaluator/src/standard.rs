//! The default registry of `--all`: the `gt` oracle, the network (`net`, one pass; `net-iter`,
//! the iterative procedure) from the shipped weights and its segmentation module on the true flow (`net-seg@gt-flow`), `one-part` (one rigid part on nearest-neighbour flow), NRR and the flow baselines,
//! and every segmentation baseline on the ground-truth flow (oracle rows) and on the
//! network's flow (the paper's protocol).

use std::fmt::Debug;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use baselines::{
    EmbeddedDeformation, FpfhFlow, IcpFlow, JLinkage, NearestFlow, Nrr, SeqRansac, Spectral,
};
use burn::prelude::Device;
use model::checkpoint::load_weights;
use model::config::TrainConfig;
use model::inference::InferenceParams;
use model::method::NetworkMethod;
use model::network::PartNet;
use pairs::{Method, Segmenter};
use sha2::{Digest, Sha256};

use crate::error::EvalError;
use crate::reference::OnePart;
use crate::registry::{Board, FlowSource, Registry};

/// The shipped weights the default rows use (a folder with `config.toml` and `model.bpk`).
pub const DEFAULT_WEIGHTS: &str = "model/weights/cpu";

/// Hash of the source of `pairs` and `baselines` (see `build.rs`).
const BASELINES_CODE: &str =
    concat!("pairs ", env!("SOURCE_HASH_PAIRS"), " baselines ", env!("SOURCE_HASH_BASELINES"));

/// Hash of the source of `pairs` and `model`.
const MODEL_CODE: &str =
    concat!("pairs ", env!("SOURCE_HASH_PAIRS"), " model ", env!("SOURCE_HASH_MODEL"));

/// Fingerprint of a method from its parameters (its `Debug` form) and the source hash of the
/// code that runs it: changing either recomputes the method's rows.
fn fingerprint(method: &impl Debug) -> String {
    format!("{method:?} {BASELINES_CODE}")
}

/// The network of `weights`; its fingerprint is the sha256 of its config and weights and the
/// source hash of the code that runs it.
pub fn load_network(weights: &Path) -> Result<(PartNet, String), EvalError> {
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
    let fingerprint = format!("net {:x} {MODEL_CODE}", hash.finalize());
    Ok((net, fingerprint))
}

/// A whole method and its fingerprint.
fn whole<M: Method + Debug + 'static>(method: M) -> (Arc<dyn Method>, String) {
    let fingerprint = fingerprint(&method);
    (Arc::new(method), fingerprint)
}

/// A segmenter and its fingerprint.
fn segmenter<S: Segmenter + Debug + 'static>(segmenter: S) -> (Arc<dyn Segmenter>, String) {
    let fingerprint = fingerprint(&segmenter);
    (Arc::new(segmenter), fingerprint)
}

/// The iterative network row, `net-iter` (the paper's full inference procedure).
pub fn iterative_network(net: PartNet) -> Arc<NetworkMethod> {
    Arc::new(NetworkMethod::with_params("net-iter", net, InferenceParams::iterative()))
}

/// The `net-iter` row's fingerprint: the network's and the procedure's parameters.
pub fn iterative_fingerprint(net_fingerprint: &str) -> String {
    format!("{net_fingerprint} {:?}", InferenceParams::iterative())
}

/// The default rows, with the network loaded from `weights`.
pub fn standard_registry(weights: &Path) -> Result<Registry, EvalError> {
    let (net, net_fingerprint) = load_network(weights)?;
    let net_segmenter: Arc<dyn Segmenter> = Arc::new(NetworkMethod::new("net-seg", net.clone()));
    let net_model = net.clone();
    let net: Arc<dyn Method> = Arc::new(NetworkMethod::new("net", net));
    let (nearest, nearest_fingerprint) = whole(NearestFlow);
    let mut registry = Registry::new();
    registry.oracle();
    registry.method(net.clone(), Board::Both, &net_fingerprint);
    registry.method(
        iterative_network(net_model),
        Board::Both,
        &iterative_fingerprint(&net_fingerprint),
    );
    let (one_part, one_part_fingerprint) = segmenter(OnePart);
    registry.combine(
        one_part,
        FlowSource::Method(nearest.clone()),
        &format!("{one_part_fingerprint} on {nearest_fingerprint}"),
        Some("one-part"),
    );
    let (nrr, nrr_fingerprint) = whole(Nrr::default());
    registry.method(nrr, Board::Both, &nrr_fingerprint);
    registry.method(nearest, Board::Flow, &nearest_fingerprint);
    for (method, fingerprint) in [
        whole(IcpFlow::default()),
        whole(EmbeddedDeformation::default()),
        whole(FpfhFlow::default()),
    ] {
        registry.method(method, Board::Flow, &fingerprint);
    }
    registry.combine(net_segmenter, FlowSource::GroundTruth, &net_fingerprint, None);
    let sources = [
        (FlowSource::GroundTruth, "ground truth".to_owned()),
        (FlowSource::Method(net), net_fingerprint),
    ];
    for (source, source_fingerprint) in sources {
        for (seg, fingerprint) in [
            segmenter(SeqRansac::default()),
            segmenter(Spectral::default()),
            segmenter(JLinkage::default()),
        ] {
            let fingerprint = format!("{fingerprint} on {source_fingerprint}");
            registry.combine(seg, source.clone(), &fingerprint, None);
        }
    }
    Ok(registry)
}
