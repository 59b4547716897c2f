//! The default registry of `--all`: the `gt` oracle, the network (`net`, one pass; `net-iter`,
//! the iterative procedure) from the shipped weights and its segmentation module on the true
//! flow (`net-seg@gt-flow`), `one-part` (one rigid part on nearest-neighbour flow), NRR and
//! the flow baselines, and every segmentation baseline on the ground-truth flow (oracle
//! rows), on the network's single pass (`net-flow`), on its iterative procedure's final flow
//! (`net-iter-flow`, the protocol of the paper's Table 2) and on embedded deformation's flow
//! (`ed-flow`, an all-classical pipeline). Every segmentation baseline and NRR's
//! segmentation step are tuned per flow source on the validation sets ([`crate::tuning`]).

use std::fmt::Debug;
use std::path::Path;
use std::sync::Arc;

use baselines::{
    EmbeddedDeformation, FpfhFlow, IcpFlow, JLinkage, JLinkageParams, NearestFlow, Nrr, NrrParams,
    SeqRansac, SeqRansacParams, Spectral, SpectralParams,
};
use model::inference::method::NetworkMethod;
use model::inference::InferenceParams;
use model::network::PartInductionNet;
use pairs::{Method, Segmenter};
use sha2::{Digest, Sha256};

use crate::error::EvalError;
use crate::rows::grid::{Axis, Grid};
use crate::rows::reference::OnePart;
use crate::rows::registry::{Board, FlowSource, Registry, Runner};

/// The row whose passes make the iteration board (`crate::boards::iterations`): the
/// network's iterative procedure.
pub const ITERATIVE_ROW: &str = "net-iter";

/// The shipped weights the default rows use (a folder with `config.toml` and `model.bpk`).
pub const DEFAULT_WEIGHTS: &str = "model/weights/cpu";

/// Hash of the source of `pairs` and `baselines`, the evaluator's scoring code and
/// `Cargo.lock` (see `build.rs`).
const BASELINES_CODE: &str = concat!(
    "pairs ",
    env!("SOURCE_HASH_PAIRS"),
    " baselines ",
    env!("SOURCE_HASH_BASELINES"),
    " scoring ",
    env!("SOURCE_HASH_SCORING"),
    " lock ",
    env!("SOURCE_HASH_LOCK")
);

/// Hash of the source of `pairs` and `model`, the scoring code and `Cargo.lock`.
const MODEL_CODE: &str = concat!(
    "pairs ",
    env!("SOURCE_HASH_PAIRS"),
    " model ",
    env!("SOURCE_HASH_MODEL"),
    " scoring ",
    env!("SOURCE_HASH_SCORING"),
    " lock ",
    env!("SOURCE_HASH_LOCK")
);

/// Fingerprint of a method from its parameters (its `Debug` form) and the source hash of the
/// code that runs it: changing either recomputes the method's rows.
fn fingerprint(method: &impl Debug) -> String {
    format!("{method:?} {BASELINES_CODE}")
}

/// The network of `weights`; its fingerprint is the sha256 of its config and weights and the
/// source hash of the code that runs it.
pub fn load_network(weights: &Path) -> Result<(PartInductionNet, String), EvalError> {
    let fail = |path: &Path, message: String| EvalError::Weights { path: path.into(), message };
    let loaded = model::weights::load(weights).map_err(|e| fail(weights, e.to_string()))?;
    let mut hash = Sha256::new();
    for path in [&loaded.config_file, &loaded.model_file] {
        let bytes =
            std::fs::read(path).map_err(|e| fail(path, format!("{}: {e}", path.display())))?;
        hash.update(&bytes);
    }
    let fingerprint = format!("net {:x} {MODEL_CODE}", hash.finalize());
    Ok((loaded.net, fingerprint))
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
pub fn iterative_network(net: PartInductionNet) -> Arc<NetworkMethod> {
    Arc::new(NetworkMethod::with_params(ITERATIVE_ROW, net, InferenceParams::iterative()))
}

/// The `net-iter` row's fingerprint: the network's and the procedure's parameters.
pub fn iterative_fingerprint(net_fingerprint: &str) -> String {
    format!("{net_fingerprint} {:?}", InferenceParams::iterative())
}

/// A segmenter row's tuning grid: `make` builds the segmenter of a grid point.
fn segmenter_grid<S: Segmenter + Debug + 'static>(
    axes: Vec<Axis>,
    flow: FlowSource,
    make: impl Fn(&[f64]) -> S + Send + Sync + 'static,
) -> Grid {
    Grid::new(axes, move |point| {
        let (seg, fingerprint) = segmenter(make(point));
        (Runner::Segmenter { segmenter: seg, flow: flow.clone() }, fingerprint)
    })
}

/// The residual thresholds every motion-fitting segmenter sweeps (Q's normalised units).
fn threshold_axis() -> Axis {
    Axis::new("inlier_threshold", &[0.01, 0.02, 0.04, 0.08], 2.0, 0.0025, 0.32)
}

/// The grids of the three segmentation baselines on `flow`: SeqRANSAC's and J-Linkage's
/// inlier threshold and smallest part, spectral clustering's two affinity scales.
pub fn baseline_grids(flow: &FlowSource) -> [(&'static str, Grid); 3] {
    let fraction = |name| Axis::new(name, &[0.02, 0.05, 0.12], 2.4, 0.005, 0.45);
    [
        (
            "seqransac",
            segmenter_grid(
                vec![threshold_axis(), fraction("min_mode_fraction")],
                flow.clone(),
                |v| {
                    SeqRansac::with_params(SeqRansacParams {
                        inlier_threshold: v[0] as f32,
                        min_mode_fraction: v[1] as f32,
                        ..SeqRansacParams::default()
                    })
                },
            ),
        ),
        (
            "sc",
            segmenter_grid(
                vec![
                    Axis::new("sigma_distance", &[0.005, 0.01, 0.02, 0.04], 2.0, 0.001, 0.2),
                    Axis::new("sigma_angle", &[0.05, 0.1, 0.2], 2.0, 0.0125, 0.8),
                ],
                flow.clone(),
                |v| {
                    Spectral::with_params(SpectralParams {
                        sigma_distance: v[0] as f32,
                        sigma_angle: v[1] as f32,
                        ..SpectralParams::default()
                    })
                },
            ),
        ),
        (
            "jlc",
            segmenter_grid(
                vec![threshold_axis(), fraction("min_segment_fraction")],
                flow.clone(),
                |v| {
                    JLinkage::with_params(JLinkageParams {
                        inlier_threshold: v[0] as f32,
                        min_segment_fraction: v[1] as f32,
                        ..JLinkageParams::default()
                    })
                },
            ),
        ),
    ]
}

/// NRR's grid: the threshold of its segmentation step (its registration is fixed).
pub fn nrr_grid() -> Grid {
    Grid::new(vec![Axis::new("segment_threshold", &[0.015, 0.03, 0.06], 2.0, 0.004, 0.25)], |v| {
        let (nrr, fingerprint) =
            whole(Nrr::with_params(NrrParams { segment_threshold: v[0], ..NrrParams::default() }));
        (Runner::Method(nrr), fingerprint)
    })
}

/// The default rows, with the network loaded from `weights`.
pub fn standard_registry(weights: &Path) -> Result<Registry, EvalError> {
    let (net, net_fingerprint) = load_network(weights)?;
    let net_segmenter: Arc<dyn Segmenter> = Arc::new(NetworkMethod::new("net-seg", net.clone()));
    let iterative: Arc<dyn Method> = iterative_network(net.clone());
    let iterative_fp = iterative_fingerprint(&net_fingerprint);
    let net: Arc<dyn Method> = Arc::new(NetworkMethod::new("net", net));
    let (nearest, nearest_fingerprint) = whole(NearestFlow);
    let (ed, ed_fingerprint) = whole(EmbeddedDeformation::default());
    let mut registry = Registry::new();
    registry.oracle();
    registry.method(net.clone(), Board::Both, &net_fingerprint);
    registry.method(iterative.clone(), Board::Both, &iterative_fp);
    let (one_part, one_part_fingerprint) = segmenter(OnePart);
    registry.combine(
        one_part,
        FlowSource::Method(nearest.clone()),
        &format!("{one_part_fingerprint} on {nearest_fingerprint}"),
        Some("one-part"),
    );
    registry.tuned("nrr", nrr_grid(), Board::Both, "own", false);
    registry.method(nearest, Board::Flow, &nearest_fingerprint);
    for (method, fingerprint) in [whole(IcpFlow::default()), (ed.clone(), ed_fingerprint.clone())]
        .into_iter()
        .chain([whole(FpfhFlow::default())])
    {
        registry.method(method, Board::Flow, &fingerprint);
    }
    registry.combine(net_segmenter, FlowSource::GroundTruth, &net_fingerprint, None);
    let sources = [
        (FlowSource::GroundTruth, format!("ground truth {BASELINES_CODE}")),
        (FlowSource::Method(net), net_fingerprint),
        (FlowSource::Method(iterative), iterative_fp),
        (FlowSource::Method(ed), ed_fingerprint),
    ];
    for (source, source_fingerprint) in sources {
        let oracle = matches!(source, FlowSource::GroundTruth);
        for (name, grid) in baseline_grids(&source) {
            let row = format!("{name}@{}", source.name());
            registry.tuned(&row, grid, Board::Segmentation, &source_fingerprint, oracle);
        }
    }
    Ok(registry)
}
