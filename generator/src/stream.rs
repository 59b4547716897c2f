//! The training stream: an endless, seeded supply of training pairs made in parallel in a
//! background thread, never touching disk, for the model's trainer.
//!
//! Objects are numbered 0, 1, 2, ... and made exactly as object `i` of a dataset with the
//! same config (so a stream and `generator --split train` agree pair for pair), in batches
//! spread over rayon's pool; batches are delivered in order, so the stream is the same
//! whatever the thread count. A trainer that saves the number of objects it consumed can
//! resume the stream where it stopped with [`TrainingStream::starting_at`].
//!
//! ```
//! use generator::{config::GeneratorConfig, stream::TrainingStream};
//!
//! let config = GeneratorConfig { points: 64, min_part_points: 4, ..GeneratorConfig::training() };
//! let pairs: Vec<_> = TrainingStream::new(config)?.take(7).collect::<Result<_, _>>()?;
//! assert_eq!(pairs.len(), 7);
//! assert!(pairs.iter().all(|p| p.input().p.len() == 64));
//! # Ok::<(), generator::generate::GenerateError>(())
//! ```

use std::sync::mpsc::{sync_channel, Receiver};
use std::thread::JoinHandle;

use pairs::{Pair, PairKind};
use rayon::prelude::*;

use crate::config::GeneratorConfig;
use crate::generate::{object_pairs_with, GenerateError, Variant};

/// Objects made per batch; the stream keeps at most [`BATCHES_AHEAD`] batches ready.
const BATCH_OBJECTS: u32 = 16;
/// Batches made ahead of the consumer, so that training never waits on generation.
const BATCHES_AHEAD: usize = 2;

/// One batch of the stream: its pairs in object order, or the error that ended it.
type Batch = Result<Vec<Pair>, GenerateError>;

/// An endless iterator over training pairs (see the module docs).
///
/// It ends only after `u32::MAX` objects (billions of pairs) or on an error; an object
/// whose parts cannot all be sampled with `min_part_points` points is skipped, as a
/// training set would drop it. Dropping the stream stops its worker.
pub struct TrainingStream {
    batches: Receiver<Batch>,
    current: std::vec::IntoIter<Pair>,
    worker: Option<JoinHandle<()>>,
}

impl TrainingStream {
    /// A stream of the pairs of objects 0, 1, 2, ... of `config`.
    pub fn new(config: GeneratorConfig) -> Result<Self, GenerateError> {
        Self::starting_at(config, 0)
    }

    /// A stream that starts at object `first`, to resume training where it stopped.
    pub fn starting_at(config: GeneratorConfig, first: u32) -> Result<Self, GenerateError> {
        config.validate()?;
        let (sender, batches) = sync_channel(BATCHES_AHEAD);
        let worker = std::thread::Builder::new()
            .name("training-stream".into())
            .spawn(move || {
                let mut start = first;
                while start < u32::MAX {
                    let end = start.saturating_add(BATCH_OBJECTS);
                    let batch = make_batch(&config, start..end);
                    let failed = batch.is_err();
                    // A closed channel means the consumer dropped the stream.
                    if sender.send(batch).is_err() || failed {
                        return;
                    }
                    start = end;
                }
            })
            .expect("spawning a thread succeeds on any supported platform");
        Ok(Self { batches, current: Vec::new().into_iter(), worker: Some(worker) })
    }
}

/// The pairs of objects `objects`, made in parallel and returned in object order.
fn make_batch(config: &GeneratorConfig, objects: std::ops::Range<u32>) -> Batch {
    let made: Vec<Vec<Pair>> = objects
        .into_par_iter()
        .map(|i| object_stream_pairs(config, i))
        .collect::<Result<_, _>>()?;
    Ok(made.into_iter().flatten().collect())
}

/// The stream's pairs of object `index`: its pairs of the config's kind, then
/// `scanned_per_pair` scanned variants of them (SF2P and SP2P in turn), each from its own
/// viewpoints. A variant the object cannot give is skipped, as a training set would drop it.
fn object_stream_pairs(config: &GeneratorConfig, index: u32) -> Result<Vec<Pair>, GenerateError> {
    let variants = (0..=config.scanned_per_pair).map(|v| Variant {
        index: v,
        kind: match v {
            0 => config.kind,
            v if v % 2 == 1 => PairKind::Sf2p,
            _ => PairKind::Sp2p,
        },
        images: false,
    });
    let mut pairs = Vec::new();
    for variant in variants {
        match object_pairs_with(config, index, variant) {
            Ok(made) => pairs.extend(made.into_iter().map(|g| g.pair)),
            Err(GenerateError::TooFewPairs { object, category, .. }) => {
                tracing::debug!(
                    object,
                    category,
                    variant = variant.index,
                    "training stream skips an object whose parts cannot all be sampled"
                );
            }
            Err(e) => return Err(e),
        }
    }
    Ok(pairs)
}

impl Iterator for TrainingStream {
    type Item = Result<Pair, GenerateError>;

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            if let Some(pair) = self.current.next() {
                return Some(Ok(pair));
            }
            match self.batches.recv() {
                Ok(Ok(batch)) => self.current = batch.into_iter(),
                Ok(Err(e)) => return Some(Err(e)),
                Err(_) => return None,
            }
        }
    }
}

impl Drop for TrainingStream {
    fn drop(&mut self) {
        // Unblock a worker waiting to send, then let it finish its batch and see the
        // closed channel.
        let (_, closed) = sync_channel(0);
        drop(std::mem::replace(&mut self.batches, closed));
        if let Some(worker) = self.worker.take() {
            let _ = worker.join();
        }
    }
}

impl std::fmt::Debug for TrainingStream {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TrainingStream").field("ready", &self.current.len()).finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::object_pairs;
    use articulated::categories::Split;

    fn small() -> GeneratorConfig {
        GeneratorConfig { points: 64, min_part_points: 4, ..GeneratorConfig::training() }
    }

    #[test]
    fn the_stream_matches_the_dataset_objects_and_resumes() {
        let config = small();
        let from_stream: Vec<Pair> = TrainingStream::new(config.clone())
            .expect("stream")
            .take(40)
            .map(Result::unwrap)
            .collect();
        let from_objects: Vec<Pair> = (0..8)
            .flat_map(|i| object_pairs(&config, i).expect("pairs"))
            .map(|g| g.pair)
            .take(40)
            .collect();
        assert_eq!(from_stream, from_objects);
        assert!(from_stream.iter().all(|p| {
            let category = &p.provenance().category;
            articulated::categories::find(category).is_some_and(|c| c.in_split(Split::Train))
        }));
        let resumed = TrainingStream::starting_at(config, 3).expect("stream").next();
        assert_eq!(resumed.expect("a pair").expect("ok").provenance().object_id, 3);
    }

    #[test]
    fn the_stream_runs_past_one_batch_and_stops_when_dropped() {
        let count = TrainingStream::new(small()).expect("stream").take(120).count();
        assert_eq!(count, 120);
    }

    #[test]
    fn scanned_variants_follow_each_objects_full_pairs() {
        let config = GeneratorConfig { scanned_per_pair: 2, ..small() };
        let pairs: Vec<Pair> =
            TrainingStream::new(config).expect("stream").take(15).map(Result::unwrap).collect();
        let kinds: Vec<PairKind> = pairs.iter().map(|p| p.input().kind).collect();
        let expected = [PairKind::Sf2f, PairKind::Sf2p, PairKind::Sp2p].map(|k| [k; 5]).concat();
        assert_eq!(kinds, expected);
        assert!(pairs[5].id().ends_with("-v1") && pairs[10].id().ends_with("-v2"));
        assert!(pairs[5].scans().q.is_some() && pairs[5].scans().p.is_none());
        assert!(pairs[10].scans().p.is_some());
        assert!(pairs.iter().all(|p| p.provenance().object_id == 0));
    }

    #[test]
    fn an_invalid_config_is_refused() {
        let config = GeneratorConfig { points: 2, ..GeneratorConfig::training() };
        assert!(TrainingStream::new(config).is_err());
    }
}
