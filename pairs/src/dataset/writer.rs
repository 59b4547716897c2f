//! Streaming dataset writer: pairs go to `pairs.mcap` and `index.csv` as they come; files
//! carry a `.partial` suffix until [`DatasetWriter::finish`] renames them into place and
//! writes `manifest.json` last.

use std::collections::{BTreeMap, BTreeSet};
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

use mcap::records::MessageHeader;
use mcap::Writer;

use super::index::{IndexRow, SetIndexRow};
use super::manifest::{
    Counts, DatasetOrigin, FileEntry, Manifest, FORMAT_NAME, FORMAT_VERSION, MANIFEST_FILE,
};
use super::schema::{encode_pair, PAIR_ENCODING, PAIR_SCHEMA, PAIR_TOPIC, SCHEMA_VERSION};
use super::set_schema::{encode_set, SET_SCHEMA, SET_SCHEMA_VERSION, SET_TOPIC};
use super::viz::{
    self, COMPRESSED_IMAGE_JSON_SCHEMA, COMPRESSED_IMAGE_SCHEMA, POINT_CLOUD_JSON_SCHEMA,
    POINT_CLOUD_SCHEMA, VIZ_OFFSET, VIZ_P_TOPIC, VIZ_Q_TOPIC,
};
use crate::atomic::{at, partial_path, replace_with};
use crate::error::DatasetError;
use crate::mcap_files::reproducible_writer;
use crate::pair::Pair;
use crate::scan::{PairImages, Scan, ScanImages, IMAGES_DIR};
use crate::set::Set;

/// Name of the MCAP file in a dataset folder.
pub const PAIRS_FILE: &str = "pairs.mcap";
/// Name of the MCAP file in a set dataset folder.
pub const SETS_FILE: &str = "sets.mcap";
/// Topic of a set dataset's visualisation cloud: every view side by side.
pub const VIZ_VIEWS_TOPIC: &str = "/viz/views";
/// Name of the index file in a dataset folder.
pub const INDEX_FILE: &str = "index.csv";
/// Nanoseconds between consecutive pairs, so that Foxglove shows one pair per second.
const PAIR_PERIOD_NS: u64 = 1_000_000_000;

/// Writes one dataset folder, pair by pair, with bounded memory.
pub struct DatasetWriter {
    dir: PathBuf,
    /// `pairs.mcap` or `sets.mcap`.
    records: &'static str,
    mcap_path: PathBuf,
    index_path: PathBuf,
    mcap: Writer<BufWriter<File>>,
    index: csv::Writer<BufWriter<File>>,
    channels: Channels,
    counts: Counts,
    objects: BTreeSet<u32>,
    /// Image files written so far, by path relative to the dataset folder.
    images: BTreeMap<String, FileEntry>,
}

struct Channels {
    /// `/pair` or `/set`.
    record: u16,
    /// `/viz/p` and `/viz/q` for pairs, `/viz/views` for sets.
    viz: Vec<u16>,
    /// Image channels by topic, added when the first scanned pair comes, so that datasets
    /// of full shapes do not list them.
    images: BTreeMap<String, u16>,
}

/// The temporary sibling of `dir/name`, renamed into place when the dataset is finished.
fn partial(dir: &Path, name: &str) -> PathBuf {
    partial_path(&dir.join(name))
}

impl DatasetWriter {
    /// Starts a dataset in `dir` (created if missing). Fails with [`DatasetError::Exists`] if
    /// `dir` already holds dataset files and `overwrite` is false; with `overwrite`, the old
    /// files stay untouched until [`finish`](Self::finish) replaces them.
    pub fn create(dir: &Path, overwrite: bool) -> Result<Self, DatasetError> {
        Self::start(dir, overwrite, PAIRS_FILE)
    }

    /// Starts a set dataset (`sets.mcap`, one `/set` message per set) in `dir`, under the
    /// rules of [`create`](Self::create).
    pub fn create_sets(dir: &Path, overwrite: bool) -> Result<Self, DatasetError> {
        Self::start(dir, overwrite, SETS_FILE)
    }

    fn start(dir: &Path, overwrite: bool, records: &'static str) -> Result<Self, DatasetError> {
        let existing =
            [PAIRS_FILE, SETS_FILE, INDEX_FILE, MANIFEST_FILE].iter().any(|f| dir.join(f).exists());
        if existing && !overwrite {
            return Err(DatasetError::Exists { dir: dir.into() });
        }
        std::fs::create_dir_all(dir).map_err(DatasetError::io(dir))?;
        let images_partial = partial(dir, IMAGES_DIR);
        if images_partial.exists() {
            // Left by an interrupted run; never part of a finished dataset.
            std::fs::remove_dir_all(&images_partial).map_err(DatasetError::io(&images_partial))?;
        }
        let mcap_path = partial(dir, records);
        let file = File::create(&mcap_path).map_err(DatasetError::io(&mcap_path))?;
        let mut mcap = reproducible_writer(file).map_err(DatasetError::mcap(&mcap_path))?;
        let channels = if records == SETS_FILE {
            add_set_channels(&mut mcap)
        } else {
            add_channels(&mut mcap)
        }
        .map_err(DatasetError::mcap(&mcap_path))?;
        let index_path = partial(dir, INDEX_FILE);
        let index_file = File::create(&index_path).map_err(DatasetError::io(&index_path))?;
        Ok(Self {
            dir: dir.into(),
            records,
            mcap_path,
            index_path,
            mcap,
            index: csv::Writer::from_writer(BufWriter::new(index_file)),
            channels,
            counts: Counts::default(),
            objects: BTreeSet::new(),
            images: BTreeMap::new(),
        })
    }

    /// Appends one pair of full shapes: its record, its two visualisation clouds and its
    /// index row. A pair with scanned sides needs [`write_scanned`](Self::write_scanned).
    pub fn write(&mut self, pair: &Pair) -> Result<(), DatasetError> {
        self.write_scanned(pair, &PairImages::default())
    }

    /// Appends one pair with the PNG images of its scanned sides: the images go to the
    /// paths its scan records name (under `images/`) and to Foxglove image channels.
    pub fn write_scanned(&mut self, pair: &Pair, images: &PairImages) -> Result<(), DatasetError> {
        if self.records != PAIRS_FILE {
            let reason = "a pair goes to a pair dataset (DatasetWriter::create)".to_string();
            return Err(DatasetError::Images { pair: pair.id().into(), reason });
        }
        let seq = self.counts.pairs;
        let sides = [("p", &pair.scans().p, &images.p), ("q", &pair.scans().q, &images.q)];
        for (side, scan, pngs) in sides {
            match (scan, pngs) {
                (None, None) => {}
                (Some(scan), Some(pngs)) => self.write_images(pair.id(), side, scan, pngs, seq)?,
                (scan, _) => {
                    let reason = if scan.is_some() {
                        format!("side {side} is scanned but came without its images")
                    } else {
                        format!("side {side} has images but no scan record")
                    };
                    return Err(DatasetError::Images { pair: pair.id().into(), reason });
                }
            }
        }
        let (input, truth) = (pair.input(), pair.truth());
        let messages = [
            (self.channels.record, encode_pair(pair)),
            (
                self.channels.viz[0],
                viz::point_cloud_message(&input.p.points, &truth.part_p, seq, -VIZ_OFFSET),
            ),
            (
                self.channels.viz[1],
                viz::point_cloud_message(&input.q.points, &truth.part_q, seq, VIZ_OFFSET),
            ),
        ];
        for (channel_id, data) in messages {
            self.write_message(channel_id, seq, &data)?;
        }
        self.index
            .serialize(IndexRow::of(pair))
            .map_err(|source| DatasetError::Csv { path: self.index_path.clone(), source })?;
        let prov = pair.provenance();
        self.counts.pairs += 1;
        *self.counts.categories.entry(prov.category.clone()).or_default() += 1;
        *self.counts.kinds.entry(input.kind.as_str().into()).or_default() += 1;
        self.objects.insert(prov.object_id);
        Ok(())
    }

    /// Appends one set with the PNG images of its scanned views (`images[k]` for view k,
    /// `None` for a full view): its record, one visualisation cloud with every view side by
    /// side, and its index row. The dataset must have been started with
    /// [`create_sets`](Self::create_sets).
    pub fn write_set(
        &mut self,
        set: &Set,
        images: &[Option<ScanImages<Vec<u8>>>],
    ) -> Result<(), DatasetError> {
        if self.records != SETS_FILE {
            let reason = "a set goes to a set dataset (DatasetWriter::create_sets)".to_string();
            return Err(DatasetError::Images { pair: set.id().into(), reason });
        }
        let seq = self.counts.sets;
        if images.len() != set.len() {
            let reason = format!("{} image entries for {} views", images.len(), set.len());
            return Err(DatasetError::Images { pair: set.id().into(), reason });
        }
        for (k, (scan, pngs)) in set.scans().iter().zip(images).enumerate() {
            let side = format!("v{k}");
            match (scan, pngs) {
                (None, None) => {}
                (Some(scan), Some(pngs)) => self.write_images(set.id(), &side, scan, pngs, seq)?,
                _ => {
                    let reason =
                        format!("view {k}: a scanned view needs its images, a full one none");
                    return Err(DatasetError::Images { pair: set.id().into(), reason });
                }
            }
        }
        let (input, truth) = (set.input(), set.truth());
        let (mut points, mut parts) = (Vec::new(), Vec::new());
        for (k, view) in input.views.iter().enumerate() {
            let shift = crate::math::Vector3::x() * (2.0 * VIZ_OFFSET * k as crate::math::Real);
            points.extend(view.cloud.points.iter().map(|p| p + shift));
            parts.extend_from_slice(&truth.parts[k]);
        }
        let messages = [
            (self.channels.record, encode_set(set)),
            (self.channels.viz[0], viz::point_cloud_message(&points, &parts, seq, 0.0)),
        ];
        for (channel_id, data) in messages {
            self.write_message(channel_id, seq, &data)?;
        }
        self.index
            .serialize(SetIndexRow::of(set))
            .map_err(|source| DatasetError::Csv { path: self.index_path.clone(), source })?;
        let prov = set.provenance();
        self.counts.sets += 1;
        *self.counts.categories.entry(prov.category.clone()).or_default() += 1;
        *self.counts.kinds.entry(set.mode().as_str().into()).or_default() += 1;
        self.objects.insert(prov.object_id);
        Ok(())
    }

    /// Writes the images of one scanned side and their Foxglove messages.
    fn write_images(
        &mut self,
        pair: &str,
        side: &str,
        scan: &Scan,
        pngs: &ScanImages<Vec<u8>>,
        seq: u64,
    ) -> Result<(), DatasetError> {
        let dir = partial(&self.dir, IMAGES_DIR);
        if self.images.is_empty() {
            std::fs::create_dir_all(&dir).map_err(DatasetError::io(&dir))?;
        }
        for ((kind, path), (_, png)) in scan.images.iter().into_iter().zip(pngs.iter()) {
            let name = path
                .strip_prefix(IMAGES_DIR)
                .and_then(|rest| rest.strip_prefix('/'))
                .filter(|name| !name.is_empty() && !name.contains(['/', '\\']) && *name != "..")
                .ok_or_else(|| DatasetError::Images {
                    pair: pair.into(),
                    reason: format!(
                        "{kind} image path {path:?} is not a file name under {IMAGES_DIR}/"
                    ),
                })?;
            if self.images.contains_key(path.as_str()) {
                let reason = format!("{kind} image path {path:?} is used twice");
                return Err(DatasetError::Images { pair: pair.into(), reason });
            }
            let file = dir.join(name);
            std::fs::write(&file, png).map_err(DatasetError::io(&file))?;
            self.images.insert(path.clone(), FileEntry::of_bytes(png));
            let topic = viz::image_topic(side, kind);
            let channel = match self.channels.images.get(&topic) {
                Some(&c) => c,
                None => {
                    let c = add_image_channel(&mut self.mcap, &topic)
                        .map_err(DatasetError::mcap(&self.mcap_path))?;
                    self.channels.images.insert(topic, c);
                    c
                }
            };
            self.write_message(channel, seq, &viz::image_message(png, seq))?;
        }
        Ok(())
    }

    /// Writes one message stamped with the pair's time.
    fn write_message(
        &mut self,
        channel_id: u16,
        seq: u64,
        data: &[u8],
    ) -> Result<(), DatasetError> {
        let header = MessageHeader {
            channel_id,
            sequence: seq as u32,
            log_time: seq * PAIR_PERIOD_NS,
            publish_time: seq * PAIR_PERIOD_NS,
        };
        self.mcap.write_to_known_channel(&header, data).map_err(DatasetError::mcap(&self.mcap_path))
    }

    /// Number of pairs (or sets) written so far.
    pub fn len(&self) -> u64 {
        self.counts.pairs + self.counts.sets
    }

    /// Whether nothing has been written yet.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Closes the files, renames them into place, and writes `manifest.json` last, so that a
    /// folder with a manifest always holds a complete dataset.
    pub fn finish(mut self, origin: DatasetOrigin) -> Result<Manifest, DatasetError> {
        let (mcap_path, index_path) = (&self.mcap_path, &self.index_path);
        self.mcap.finish().map_err(DatasetError::mcap(mcap_path))?;
        let file = self
            .mcap
            .into_inner()
            .into_inner()
            .map_err(|e| DatasetError::io(mcap_path)(e.into_error()))?;
        file.sync_all().map_err(DatasetError::io(mcap_path))?;
        let index_file = self
            .index
            .into_inner()
            .map_err(|e| DatasetError::io(index_path)(e.into_error()))?
            .into_inner()
            .map_err(|e| DatasetError::io(index_path)(e.into_error()))?;
        index_file.sync_all().map_err(DatasetError::io(index_path))?;

        // An old manifest goes first: from here until the new one lands, the folder reads as
        // an unfinished dataset rather than as a finished one with mismatched files.
        let manifest_path = self.dir.join(MANIFEST_FILE);
        if manifest_path.exists() {
            std::fs::remove_file(&manifest_path).map_err(DatasetError::io(&manifest_path))?;
        }
        // A dataset of the other record kind that this one replaces loses its records file.
        let other = self.dir.join(if self.records == SETS_FILE { PAIRS_FILE } else { SETS_FILE });
        if other.exists() {
            std::fs::remove_file(&other).map_err(DatasetError::io(&other))?;
        }
        let mut files = BTreeMap::new();
        for name in [self.records, INDEX_FILE] {
            let (from, to) = (partial(&self.dir, name), self.dir.join(name));
            std::fs::rename(&from, &to).map_err(DatasetError::io(&to))?;
            files.insert(name.to_string(), FileEntry::of(&to)?);
        }
        let images = self.dir.join(IMAGES_DIR);
        if images.exists() {
            std::fs::remove_dir_all(&images).map_err(DatasetError::io(&images))?;
        }
        if !self.images.is_empty() {
            let from = partial(&self.dir, IMAGES_DIR);
            std::fs::rename(&from, &images).map_err(DatasetError::io(&images))?;
            files.append(&mut self.images);
        }
        self.counts.objects = self.objects.len() as u64;
        let manifest = Manifest {
            format: FORMAT_NAME.into(),
            format_version: FORMAT_VERSION,
            origin,
            counts: self.counts,
            files,
        };
        let mut text = serde_json::to_vec_pretty(&manifest).expect("a manifest always serialises");
        text.push(b'\n');
        replace_with(&manifest_path, |tmp| std::fs::write(tmp, text).map_err(at(tmp)))?;
        Ok(manifest)
    }
}

fn add_channels(mcap: &mut Writer<BufWriter<File>>) -> mcap::McapResult<Channels> {
    let pair_meta = BTreeMap::from([
        ("schema".to_string(), PAIR_SCHEMA.to_string()),
        ("schema_version".to_string(), SCHEMA_VERSION.to_string()),
    ]);
    // CBOR has no MCAP schema encoding: the channel has schema id 0 and names its layout in
    // its metadata (docs/FORMAT.md).
    let pair = mcap.add_channel(0, PAIR_TOPIC, PAIR_ENCODING, &pair_meta)?;
    let schema =
        mcap.add_schema(POINT_CLOUD_SCHEMA, "jsonschema", POINT_CLOUD_JSON_SCHEMA.as_bytes())?;
    let viz_p = mcap.add_channel(schema, VIZ_P_TOPIC, "json", &BTreeMap::new())?;
    let viz_q = mcap.add_channel(schema, VIZ_Q_TOPIC, "json", &BTreeMap::new())?;
    Ok(Channels { record: pair, viz: vec![viz_p, viz_q], images: BTreeMap::new() })
}

fn add_set_channels(mcap: &mut Writer<BufWriter<File>>) -> mcap::McapResult<Channels> {
    let meta = BTreeMap::from([
        ("schema".to_string(), SET_SCHEMA.to_string()),
        ("schema_version".to_string(), SET_SCHEMA_VERSION.to_string()),
    ]);
    let record = mcap.add_channel(0, SET_TOPIC, PAIR_ENCODING, &meta)?;
    let schema =
        mcap.add_schema(POINT_CLOUD_SCHEMA, "jsonschema", POINT_CLOUD_JSON_SCHEMA.as_bytes())?;
    let viz = mcap.add_channel(schema, VIZ_VIEWS_TOPIC, "json", &BTreeMap::new())?;
    Ok(Channels { record, viz: vec![viz], images: BTreeMap::new() })
}

fn add_image_channel(mcap: &mut Writer<BufWriter<File>>, topic: &str) -> mcap::McapResult<u16> {
    let schema = mcap.add_schema(
        COMPRESSED_IMAGE_SCHEMA,
        "jsonschema",
        COMPRESSED_IMAGE_JSON_SCHEMA.as_bytes(),
    )?;
    mcap.add_channel(schema, topic, "json", &BTreeMap::new())
}
