//! Sharding for clusters: shard `i` of `n` holds a contiguous range of a dataset's objects,
//! and merging the shards in order gives files byte-identical to the unsharded run.

use std::ops::Range;
use std::path::{Path, PathBuf};

use pairs::dataset::{Dataset, DatasetWriter, Manifest, Shard};
use pairs::DatasetError;

/// Why a shard cannot be made or shards cannot be merged.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ShardError {
    /// `--shard i/n` with `i >= n`, `n = 0`, or more shards than objects.
    #[error(
        "shard {index}/{count} does not exist for {objects} objects (need 0 <= i < n <= objects)"
    )]
    OutOfRange {
        /// Zero-based shard index asked for.
        index: u32,
        /// Number of shards asked for.
        count: u32,
        /// Objects in the dataset.
        objects: u32,
    },
    /// `--shard` text that is not `i/n`.
    #[error("{0:?} is not a shard: write i/n, e.g. 0/4 for the first of four")]
    Syntax(String),
    /// A folder given to merge holds a whole dataset, not a shard.
    #[error("{0} holds a whole dataset, not a shard")]
    NotAShard(PathBuf),
    /// The shards do not come from one run: different configs, seeds, versions or counts.
    #[error("{path} does not belong with {first}: {what} differs")]
    Mismatch {
        /// The odd shard.
        path: PathBuf,
        /// The first shard.
        first: PathBuf,
        /// Which field differs.
        what: &'static str,
    },
    /// Some shards are missing or given twice.
    #[error("shards given: {given:?} of {count}; need each of 0..{count} exactly once")]
    Incomplete {
        /// Indices given, sorted.
        given: Vec<u32>,
        /// Number of shards of the run.
        count: u32,
    },
    /// Reading a shard or writing the merged dataset failed.
    #[error(transparent)]
    Dataset(#[from] DatasetError),
}

/// Parses `i/n` into a shard.
pub fn parse_shard(text: &str) -> Result<Shard, ShardError> {
    let syntax = || ShardError::Syntax(text.into());
    let (i, n) = text.split_once('/').ok_or_else(syntax)?;
    let index = i.trim().parse().map_err(|_| syntax())?;
    let count = n.trim().parse().map_err(|_| syntax())?;
    Ok(Shard { index, count })
}

/// The objects of `shard` of a dataset of `objects` objects (all of them for `None`).
pub fn shard_objects(objects: u32, shard: Option<Shard>) -> Result<Range<u32>, ShardError> {
    let Some(Shard { index, count }) = shard else {
        return Ok(0..objects);
    };
    if count == 0 || index >= count || count > objects {
        return Err(ShardError::OutOfRange { index, count, objects });
    }
    let bound = |i: u32| (u64::from(objects) * u64::from(i) / u64::from(count)) as u32;
    Ok(bound(index)..bound(index + 1))
}

/// Merges the shard folders `shards` (any order) into a whole dataset in `out`, calling
/// `progress` with the number of pairs written. Every shard is verified against its
/// manifest first; existing output is kept unless `overwrite`.
pub fn merge_shards(
    shards: &[PathBuf],
    out: &Path,
    overwrite: bool,
    mut progress: impl FnMut(u64),
) -> Result<Manifest, ShardError> {
    let mut opened: Vec<(Shard, Dataset)> = Vec::with_capacity(shards.len());
    for dir in shards {
        let dataset = Dataset::open(dir)?;
        let shard =
            dataset.manifest().origin.shard.ok_or_else(|| ShardError::NotAShard(dir.clone()))?;
        dataset.verify()?;
        opened.push((shard, dataset));
    }
    let Some((first_shard, first)) = opened.first() else {
        return Err(ShardError::Incomplete { given: Vec::new(), count: 0 });
    };
    let (count, origin) = (first_shard.count, &first.manifest().origin);
    for (shard, dataset) in &opened {
        let other = &dataset.manifest().origin;
        let differs = [
            ("shard count", shard.count != count),
            ("generator_version", other.generator_version != origin.generator_version),
            ("seed", other.seed != origin.seed),
            ("config", other.config != origin.config),
            ("splits", other.splits != origin.splits),
        ];
        if let Some((what, _)) = differs.iter().find(|(_, d)| *d) {
            let (path, first) = (dataset.dir().to_path_buf(), first.dir().to_path_buf());
            return Err(ShardError::Mismatch { path, first, what });
        }
    }
    let mut given: Vec<u32> = opened.iter().map(|(s, _)| s.index).collect();
    given.sort_unstable();
    if given != (0..count).collect::<Vec<_>>() {
        return Err(ShardError::Incomplete { given, count });
    }
    let mut origin = origin.clone();
    origin.shard = None;
    origin.left_out.clear();
    for (_, dataset) in &opened {
        for (category, n) in &dataset.manifest().origin.left_out {
            *origin.left_out.entry(category.clone()).or_insert(0) += n;
        }
    }
    let sets = first.holds_sets();
    opened.sort_by_key(|(s, _)| s.index);
    if sets {
        let mut writer = DatasetWriter::create_sets(out, overwrite)?;
        for (_, dataset) in &opened {
            for set in dataset.sets()? {
                let set = set?;
                writer.write_set(&set, &dataset.read_set_images(&set)?)?;
                progress(writer.len());
            }
        }
        return Ok(writer.finish(origin)?);
    }
    let mut writer = DatasetWriter::create(out, overwrite)?;
    for (_, dataset) in &opened {
        for pair in dataset.pairs()? {
            let pair = pair?;
            writer.write_scanned(&pair, &dataset.read_images(&pair)?)?;
            progress(writer.len());
        }
    }
    Ok(writer.finish(origin)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_cover_every_object_once_in_order() {
        for (objects, count) in [(175, 4), (10, 10), (7, 3), (1000, 7)] {
            let ranges: Vec<Range<u32>> = (0..count)
                .map(|index| shard_objects(objects, Some(Shard { index, count })).expect("shard"))
                .collect();
            assert_eq!(ranges.first().map(|r| r.start), Some(0));
            assert_eq!(ranges.last().map(|r| r.end), Some(objects));
            assert!(ranges.windows(2).all(|w| w[0].end == w[1].start && !w[0].is_empty()));
        }
    }

    #[test]
    fn bad_shards_are_refused() {
        assert!(shard_objects(10, Some(Shard { index: 4, count: 4 })).is_err());
        assert!(shard_objects(10, Some(Shard { index: 0, count: 0 })).is_err());
        assert!(shard_objects(3, Some(Shard { index: 0, count: 4 })).is_err());
        assert_eq!(parse_shard("2/8").expect("parses"), Shard { index: 2, count: 8 });
        for bad in ["2", "a/4", "1/", "-1/4"] {
            assert!(parse_shard(bad).is_err(), "{bad}");
        }
    }
}
