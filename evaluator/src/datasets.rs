//! The datasets the evaluator scores: their names, generator configs and folders, generation
//! of missing ones through the generator library, loading, and a content hash that tells a
//! changed dataset from the one a cached run was made on.

use std::path::{Path, PathBuf};

use articulated::categories::Split;
use generator::config::GeneratorConfig;
use generator::generate::{dataset_origin, generate_dataset};
use pairs::dataset::{Dataset, Manifest, PAIRS_FILE, SETS_FILE};
use pairs::{Pair, PairKind, Set, SetMode};

use crate::error::EvalError;

/// A dataset the evaluator knows by name.
#[derive(Debug, Clone)]
pub struct DatasetSpec {
    /// Leaderboard name (`sf2f`).
    pub name: String,
    /// The generator config that makes it when it is missing (or stale); `None` for a user's
    /// dataset (`--dataset NAME=PATH`), which is only read.
    pub config: Option<GeneratorConfig>,
    /// Its folder, when it is not `<root>/<name>`.
    pub path: Option<PathBuf>,
}

impl DatasetSpec {
    /// A dataset of the generator's defaults for `kind`'s test protocol, named `name`.
    pub fn generated(name: &str, config: GeneratorConfig) -> Self {
        Self { name: name.to_owned(), config: Some(config), path: None }
    }

    /// A dataset the generator already wrote into `path` (from `--assets` too), scored under
    /// `name`.
    pub fn user(name: &str, path: &Path) -> Self {
        Self { name: name.to_owned(), config: None, path: Some(path.to_path_buf()) }
    }

    /// Its folder: the given path, or `<root>/<name>`.
    pub fn dir(&self, root: &Path) -> PathBuf {
        self.path.clone().unwrap_or_else(|| root.join(&self.name))
    }

    /// Whether it is a render folder given with `--dataset NAME=PATH` (made by `generator
    /// render`, scored on its joints) rather than a dataset of pairs.
    pub fn is_user_render(&self, root: &Path) -> bool {
        self.config.is_none() && pairs::renders::is_render(&self.dir(root))
    }
}

/// Parses `NAME=PATH` (the `--dataset` flag).
pub fn parse_user_dataset(arg: &str) -> Result<DatasetSpec, String> {
    let (name, path) = arg
        .split_once('=')
        .filter(|(n, p)| !n.is_empty() && !p.is_empty())
        .ok_or_else(|| format!("{arg:?}: expected NAME=PATH (e.g. lamps=datasets/lamps)"))?;
    if !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_') {
        return Err(format!("{name:?}: a dataset name has only letters, digits, '-' and '_'"));
    }
    Ok(DatasetSpec::user(name, Path::new(path)))
}

/// Seed of the validation sets (the model trainer's validation seed).
pub const VALIDATION_SEED: u64 = 20_181_201;

/// Objects per validation set: 10 objects of the 3 validation categories in turn, 5 pairs
/// each, so 50 pairs per kind and 150 over the three kinds.
pub const VALIDATION_OBJECTS: u32 = 10;

/// The validation sets the baselines are tuned on: the default datasets' protocol and kinds
/// (full and scanned, as the test sets are) on the validation categories, named
/// `val-<kind>`. No test pair is in them: their categories are the validation split's.
pub fn validation_datasets() -> Vec<DatasetSpec> {
    [PairKind::Sf2f, PairKind::Sf2p, PairKind::Sp2p]
        .into_iter()
        .map(|kind| {
            let config = GeneratorConfig {
                split: Split::Validation,
                objects: VALIDATION_OBJECTS,
                seed: VALIDATION_SEED,
                ..GeneratorConfig::of_kind(kind)
            };
            DatasetSpec::generated(&format!("val-{}", kind.as_str().to_lowercase()), config)
        })
        .collect()
}

/// Objects of each default cross-instance set (XF2F, XF2P): two per held-out test category
/// (26), 5 pairs each, so 260 pairs. The paper-size 875 pairs would take `--all` past its
/// 20-minute budget on 2 cores; `datasets/xf2f.toml` and `xf2p.toml` write these configs.
pub const CROSS_INSTANCE_OBJECTS: u32 = 52;

/// The default datasets: the paper's three synthetic test sets (SF2F, SF2P, SP2P) on the
/// generator's defaults, then the cross-instance sets (XF2F, XF2P: two objects of one
/// category) of [`CROSS_INSTANCE_OBJECTS`] objects, named by their kind, then the set
/// dataset of [`default_set_datasets`].
pub fn default_datasets() -> Vec<DatasetSpec> {
    let mut specs = pair_datasets();
    specs.extend(default_set_datasets());
    specs
}

/// The default pair datasets ([`default_datasets`] without the sets).
fn pair_datasets() -> Vec<DatasetSpec> {
    PairKind::ALL
        .into_iter()
        .map(|kind| {
            let config = GeneratorConfig::of_kind(kind);
            let config = match kind.cross_instance() {
                true => GeneratorConfig { objects: CROSS_INSTANCE_OBJECTS, ..config },
                false => config,
            };
            DatasetSpec::generated(&kind.as_str().to_lowercase(), config)
        })
        .collect()
}

/// Objects of the default set dataset: four per held-out test category (104 sets of 4
/// views, so 312 pairs (0, k) per row), within `--all`'s time budget on 2 cores.
pub const SET_OBJECTS: u32 = 104;

/// The default set dataset (`sets-scan`, `datasets/sets-scan.toml`): K = 4 virtual scans
/// of each of [`SET_OBJECTS`] test objects in four articulation states, the setting of
/// MultiBodySync's SAPIEN test data (K depth scans of one object).
pub fn default_set_datasets() -> Vec<DatasetSpec> {
    let config = GeneratorConfig {
        objects: SET_OBJECTS,
        sets: Some(generator::config::SetsConfig { views: 4, mode: SetMode::Scan, per_object: 1 }),
        ..GeneratorConfig::default()
    };
    vec![DatasetSpec::generated("sets-scan", config)]
}

/// Whether `spec` is a set dataset: its generator config makes sets, or (a user's dataset)
/// the manifest in its folder `dir` counts sets.
pub fn holds_sets(spec: &DatasetSpec, dir: &Path) -> bool {
    match &spec.config {
        Some(config) => config.sets.is_some(),
        None => Dataset::open(dir).is_ok_and(|d| d.holds_sets()),
    }
}

/// A loaded set dataset: its sets in file order, and the pairs (view 0, view k) of every
/// set, k = 1 .. K-1, set by set, which the pair rows run on before their predictions are
/// lifted to the set (`pairs::set_method::lift_pairs`).
#[derive(Debug)]
pub struct LoadedSets {
    /// The sets.
    pub sets: Vec<Set>,
    /// The pairs (0, k) of every set, as a dataset named like the set dataset whose content
    /// hash is the sets file's.
    pub pairs: LoadedDataset,
}

/// Loads the set dataset `name` from `dir` (verifying its checksums), keeping the first
/// `limit` sets when a limit is given.
pub fn load_set_dataset(
    name: &str,
    dir: &Path,
    limit: Option<usize>,
) -> Result<LoadedSets, EvalError> {
    let err = |source| EvalError::Dataset { name: name.to_owned(), source };
    let (dataset, content_hash, split) = open_verified(name, dir, SETS_FILE, limit)?;
    let sets: Vec<Set> = dataset
        .sets()
        .map_err(err)?
        .take(limit.unwrap_or(usize::MAX))
        .collect::<Result<_, _>>()
        .map_err(err)?;
    if sets.is_empty() {
        return Err(EvalError::EmptyDataset { name: name.to_owned(), dir: dir.to_path_buf() });
    }
    let mut pairs = Vec::new();
    for set in &sets {
        for k in 1..set.len() {
            let pair = set.pair(0, k).map_err(|e| {
                err(pairs::DatasetError::InvalidSet {
                    path: dir.join(SETS_FILE),
                    source: Box::new(e),
                })
            })?;
            pairs.push(pair);
        }
    }
    let pairs =
        LoadedDataset { name: name.to_owned(), pairs, content_hash, split, cross_instance: false };
    Ok(LoadedSets { sets, pairs })
}

/// A loaded dataset: its pairs in file order and the hash of its pair file.
#[derive(Debug)]
pub struct LoadedDataset {
    /// Leaderboard name.
    pub name: String,
    /// The pairs (the first `limit` of the file when a limit was given).
    pub pairs: Vec<Pair>,
    /// sha256 of `pairs.mcap` as the manifest records it, plus the limit: a cached run made on
    /// other data does not match.
    pub content_hash: String,
    /// The category split its manifest's config names (`None` when it names none).
    pub split: Option<Split>,
    /// Whether its pairs are cross-instance (XF2F, XF2P: no true flow), so that rows that
    /// need one (flow rows, segmenters on the true flow) do not run on it.
    pub cross_instance: bool,
}

/// Why a generated dataset on disk no longer matches its spec, if it does not: another
/// generator version, or another config.
pub fn stale_reason(spec: &DatasetSpec, manifest: &Manifest) -> Option<String> {
    let config = spec.config.as_ref()?;
    let expected = dataset_origin(config, None);
    if manifest.origin.generator_version != expected.generator_version {
        return Some(format!(
            "made by generator {}, this is {}",
            manifest.origin.generator_version, expected.generator_version
        ));
    }
    (manifest.origin.config != expected.config)
        .then(|| "its manifest's config differs from the evaluator's spec".to_owned())
}

/// Generates `spec` into `root` unless it already holds a dataset made by this generator
/// from the same config; a stale one is regenerated (replaced only once the new one is
/// complete), with `notice` told why. `progress(done, total)` follows the pairs written.
/// Returns whether it generated. A user's dataset is never generated: a missing one is an
/// error naming its folder.
pub fn ensure_dataset(
    spec: &DatasetSpec,
    root: &Path,
    notice: &dyn Fn(&str),
    progress: impl FnMut(u64, u64),
) -> Result<bool, EvalError> {
    let dir = spec.dir(root);
    let Some(config) = &spec.config else {
        Manifest::read(&dir)
            .map_err(|source| EvalError::Dataset { name: spec.name.clone(), source })?;
        return Ok(false);
    };
    let mut overwrite = false;
    if dir.join(pairs::dataset::MANIFEST_FILE).exists() {
        match Manifest::read(&dir).map(|m| stale_reason(spec, &m)) {
            Ok(None) => return Ok(false),
            Ok(Some(why)) => {
                notice(&format!("regenerating {} ({}): {why}", spec.name, dir.display()))
            }
            Err(e) => notice(&format!("regenerating {} ({}): {e}", spec.name, dir.display())),
        }
        overwrite = true;
    }
    let total = config.total_pairs();
    let mut progress = progress;
    generate_dataset(config, &dir, overwrite, None, |n| progress(n, total))
        .map_err(|e| EvalError::Generate { name: spec.name.clone(), source: Box::new(e) })?;
    Ok(true)
}

/// Opens the dataset `name` in `dir` and verifies its checksums; returns it, its content
/// hash (the sha256 of `records`, the file of its records, with `:first<N>` for a limited
/// load) and the category split its manifest's config names.
fn open_verified(
    name: &str,
    dir: &Path,
    records: &str,
    limit: Option<usize>,
) -> Result<(Dataset, String, Option<Split>), EvalError> {
    let err = |source| EvalError::Dataset { name: name.to_owned(), source };
    let dataset = Dataset::open(dir).map_err(err)?;
    dataset.verify().map_err(err)?;
    let hash = dataset.manifest().files.get(records).map(|f| f.sha256.clone()).unwrap_or_default();
    let content_hash = match limit {
        Some(l) => format!("{hash}:first{l}"),
        None => hash,
    };
    let split = dataset
        .manifest()
        .origin
        .config
        .get("split")
        .and_then(|s| s.as_str())
        .and_then(|s| s.parse().ok());
    Ok((dataset, content_hash, split))
}

/// Loads the dataset `name` from `dir` (verifying its checksums), keeping the first `limit`
/// pairs when a limit is given.
pub fn load_dataset(
    name: &str,
    dir: &Path,
    limit: Option<usize>,
) -> Result<LoadedDataset, EvalError> {
    let err = |source| EvalError::Dataset { name: name.to_owned(), source };
    let (dataset, content_hash, split) = open_verified(name, dir, PAIRS_FILE, limit)?;
    let pairs: Vec<Pair> = dataset
        .pairs()
        .map_err(err)?
        .take(limit.unwrap_or(usize::MAX))
        .collect::<Result<_, _>>()
        .map_err(err)?;
    if pairs.is_empty() {
        return Err(EvalError::EmptyDataset { name: name.to_owned(), dir: dir.to_path_buf() });
    }
    let cross_instance = pairs.iter().any(|p| p.truth().flow.is_none());
    Ok(LoadedDataset { name: name.to_owned(), pairs, content_hash, split, cross_instance })
}

/// The file under the reports folder that remembers the user datasets scored into it, so
/// their rows stay in the boards when a later run does not name them again.
pub const USER_DATASETS_FILE: &str = "user_datasets.json";

/// The user datasets remembered in `reports` (name → folder), in name order; none when the
/// file is missing or unreadable.
pub fn remembered_datasets(reports: &Path) -> Vec<DatasetSpec> {
    let Ok(text) = std::fs::read_to_string(reports.join(USER_DATASETS_FILE)) else {
        return Vec::new();
    };
    let map: std::collections::BTreeMap<String, PathBuf> =
        serde_json::from_str(&text).unwrap_or_default();
    map.iter().map(|(name, path)| DatasetSpec::user(name, path)).collect()
}

/// Every dataset the boards know: the defaults, then the user datasets remembered in
/// `reports` whose folders under `datasets_root` exist (they stay in the boards without
/// being rerun), then `user` (the `--dataset` flags), a later one replacing an earlier one
/// of the same name. A user dataset may not take a default's name.
pub fn dataset_specs(
    reports: &Path,
    datasets_root: &Path,
    user: &[DatasetSpec],
) -> Result<Vec<DatasetSpec>, EvalError> {
    let mut specs = default_datasets();
    let remembered = remembered_datasets(reports)
        .into_iter()
        .filter(|s| s.dir(datasets_root).join(pairs::dataset::MANIFEST_FILE).exists());
    for spec in remembered.chain(user.iter().cloned()) {
        if specs.iter().any(|s| s.name == spec.name && s.config.is_some()) {
            return Err(EvalError::DefaultName(spec.name));
        }
        specs.retain(|s| s.name != spec.name);
        specs.push(spec);
    }
    Ok(specs)
}

/// Remembers `specs`' user datasets in `reports` beside the ones already there.
pub fn remember_datasets(reports: &Path, specs: &[DatasetSpec]) -> Result<(), EvalError> {
    let mut map: std::collections::BTreeMap<String, PathBuf> =
        remembered_datasets(reports).into_iter().filter_map(|s| Some((s.name, s.path?))).collect();
    for spec in specs {
        if let (None, Some(path)) = (&spec.config, &spec.path) {
            map.insert(spec.name.clone(), path.clone());
        }
    }
    let path = reports.join(USER_DATASETS_FILE);
    if map.is_empty() && !path.exists() {
        return Ok(());
    }
    let json = serde_json::to_string_pretty(&map).expect("a name map serialises");
    Ok(pairs::atomic::replace_bytes(&path, json.as_bytes())?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cross_instance_sets_are_the_committed_configs() {
        let specs = default_datasets();
        for (name, text) in [
            ("xf2f", include_str!("../../datasets/xf2f.toml")),
            ("xf2p", include_str!("../../datasets/xf2p.toml")),
        ] {
            let parsed: GeneratorConfig = toml::from_str(text).expect("parses");
            let spec = specs.iter().find(|s| s.name == name).expect("a default set");
            assert_eq!(
                spec.config.as_ref().map(GeneratorConfig::resolved),
                Some(parsed.resolved())
            );
            assert_eq!(parsed.total_pairs(), 260);
        }
        let parsed: GeneratorConfig =
            toml::from_str(include_str!("../../datasets/sets-scan.toml")).expect("parses");
        let spec = specs.iter().find(|s| s.name == "sets-scan").expect("the set dataset");
        assert_eq!(spec.config.as_ref().map(GeneratorConfig::resolved), Some(parsed.resolved()));
        assert_eq!(parsed.total_pairs(), 104, "sets");
    }

    #[test]
    fn specs_are_the_defaults_then_remembered_folders_that_exist_then_the_flags() {
        let dir = tempfile::tempdir().expect("a temp dir");
        let (reports, root) = (dir.path().join("reports"), dir.path().join("datasets"));
        let here = dir.path().join("here");
        std::fs::create_dir_all(&here).expect("made");
        std::fs::write(here.join(pairs::dataset::MANIFEST_FILE), "{}").expect("written");
        let gone = dir.path().join("gone");
        let remembered = [DatasetSpec::user("mine", &here), DatasetSpec::user("old", &gone)];
        remember_datasets(&reports, &remembered).expect("remembered");
        let names = |specs: Vec<DatasetSpec>| specs.into_iter().map(|s| s.name).collect::<Vec<_>>();
        let defaults = names(default_datasets());
        let specs = dataset_specs(&reports, &root, &[]).expect("specs");
        assert_eq!(names(specs), [defaults.clone(), vec!["mine".into()]].concat());
        let flag = DatasetSpec::user("mine", &gone);
        let specs = dataset_specs(&reports, &root, std::slice::from_ref(&flag)).expect("specs");
        assert_eq!(specs.last().and_then(|s| s.path.clone()), Some(gone.clone()));
        let clash = DatasetSpec::user("sf2f", &here);
        let err = dataset_specs(&reports, &root, &[clash]).expect_err("a default's name");
        assert!(err.to_string().contains("sf2f"), "{err}");
    }
}
