//! `manifest.json`: what made a dataset (version, config, seed), its counts, and a checksum of
//! every file.

use std::collections::BTreeMap;
use std::fs::File;
use std::io::{BufReader, Read};
use std::path::Path;

use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

use crate::error::DatasetError;

/// Name of the manifest file in a dataset folder.
pub const MANIFEST_FILE: &str = "manifest.json";
/// Value of the manifest's `format` field.
pub const FORMAT_NAME: &str = "part-induction-dataset";
/// Version of the dataset folder layout.
pub const FORMAT_VERSION: u32 = 1;

/// Size and sha256 of one file of a dataset.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct FileEntry {
    /// Size in bytes.
    pub bytes: u64,
    /// Lower-case hex sha256 of the contents.
    pub sha256: String,
}

/// Counts of what a dataset holds.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Counts {
    /// Number of pairs.
    pub pairs: u64,
    /// Sets (set datasets only; absent from a pair dataset's manifest).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub sets: u64,
    /// Number of distinct objects.
    pub objects: u64,
    /// Pairs per category.
    pub categories: BTreeMap<String, u64>,
    /// Pairs per kind (`SF2F`, ...).
    pub kinds: BTreeMap<String, u64>,
}

/// What the writer needs to know that is not in the pairs: who made them and how.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DatasetOrigin {
    /// Version of the generator.
    pub generator_version: String,
    /// Dataset seed.
    pub seed: u64,
    /// The full configuration that made the dataset, as JSON.
    pub config: serde_json::Value,
    /// The generator's named category splits (`train`, `validation`, `test`), each with its
    /// categories, so that a reader can tell which categories a model never saw.
    #[serde(default)]
    pub splits: BTreeMap<String, Vec<String>>,
    /// Which part of a larger dataset this folder holds; absent for a whole dataset.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shard: Option<Shard>,
    /// The user assets the dataset was made from (`generator --assets`), in object order;
    /// absent for the procedural categories.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub assets: Vec<AssetRecord>,
    /// Cross-instance sets (XF2F, XF2P): objects left out per category because no second
    /// instance of their category could be matched to them part for part (same links and
    /// joints by name). Absent when none was left out.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub left_out: BTreeMap<String, u32>,
}

/// One user asset of a dataset: its files with their checksums, and its object id or the
/// error that kept it out.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct AssetRecord {
    /// Path of the asset's main file, relative to the folder given to `--assets` (the file
    /// name when a single file was given), `/`-separated.
    pub path: String,
    /// Object id of its pairs (`provenance.object_id`).
    pub object_id: u32,
    /// Size and sha256 of the main file.
    #[serde(flatten)]
    pub file: FileEntry,
    /// The other files it was read from (sidecar, meshes, buffers), by path relative to the
    /// same folder where they lie inside it.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub files: BTreeMap<String, FileEntry>,
    /// Why the asset gave no pairs; absent when it gave its pairs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

/// One of `count` shards of a dataset: the objects of contiguous range `index` of `count`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    /// Zero-based index of the shard.
    pub index: u32,
    /// Number of shards the dataset is split into.
    pub count: u32,
}

/// The contents of `manifest.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// Always [`FORMAT_NAME`].
    pub format: String,
    /// Layout version, [`FORMAT_VERSION`].
    pub format_version: u32,
    /// Generator version, seed and config.
    #[serde(flatten)]
    pub origin: DatasetOrigin,
    /// What the dataset holds.
    pub counts: Counts,
    /// Size and checksum of every other file, by path relative to the dataset folder.
    pub files: BTreeMap<String, FileEntry>,
}

impl Manifest {
    /// Reads and checks the manifest of a dataset folder.
    pub fn read(dir: &Path) -> Result<Self, DatasetError> {
        let path = dir.join(MANIFEST_FILE);
        if !path.is_file() {
            return Err(DatasetError::MissingManifest { dir: dir.into() });
        }
        let text = std::fs::read(&path).map_err(DatasetError::io(&path))?;
        let manifest: Self = serde_json::from_slice(&text)
            .map_err(|e| DatasetError::Manifest { path: path.clone(), reason: e.to_string() })?;
        if manifest.format != FORMAT_NAME || manifest.format_version != FORMAT_VERSION {
            let reason = format!(
                "format {:?} version {} (expected {FORMAT_NAME:?} version {FORMAT_VERSION})",
                manifest.format, manifest.format_version
            );
            return Err(DatasetError::Manifest { path, reason });
        }
        Ok(manifest)
    }

    /// Checks the size and sha256 of every file the manifest lists.
    pub fn verify(&self, dir: &Path) -> Result<(), DatasetError> {
        for (name, expected) in &self.files {
            let path = dir.join(name);
            let found = FileEntry::of(&path)?;
            if found.bytes != expected.bytes {
                let reason = format!("{} bytes, manifest says {}", found.bytes, expected.bytes);
                return Err(DatasetError::Checksum { path, reason });
            }
            if found.sha256 != expected.sha256 {
                let reason = "sha256 differs from the manifest".to_string();
                return Err(DatasetError::Checksum { path, reason });
            }
        }
        Ok(())
    }
}

impl FileEntry {
    /// Size and sha256 of bytes about to be written.
    pub fn of_bytes(bytes: &[u8]) -> Self {
        Self { bytes: bytes.len() as u64, sha256: hex(&Sha256::digest(bytes)) }
    }

    /// Size and sha256 of a file, read in a stream.
    pub fn of(path: &Path) -> Result<Self, DatasetError> {
        let file = File::open(path).map_err(DatasetError::io(path))?;
        let mut reader = BufReader::with_capacity(1 << 16, file);
        let mut hasher = Sha256::new();
        let mut buf = vec![0u8; 1 << 16];
        let mut bytes = 0u64;
        loop {
            let n = reader.read(&mut buf).map_err(DatasetError::io(path))?;
            if n == 0 {
                break;
            }
            hasher.update(&buf[..n]);
            bytes += n as u64;
        }
        Ok(Self { bytes, sha256: hex(&hasher.finalize()) })
    }
}

fn hex(digest: &[u8]) -> String {
    digest.iter().map(|b| format!("{b:02x}")).collect()
}

fn is_zero(n: &u64) -> bool {
    *n == 0
}
