//! The dataset folder format (docs/FORMAT.md): `pairs.mcap` (or `sets.mcap`), `index.csv`,
//! `manifest.json`.

pub mod index;
pub mod manifest;
pub mod reader;
pub(crate) mod records;
pub mod schema;
pub mod set_schema;
pub mod viz;
pub mod writer;

pub use index::IndexRow;
pub use manifest::{AssetRecord, Counts, DatasetOrigin, FileEntry, Manifest, Shard, MANIFEST_FILE};
pub use reader::{Dataset, PairReader, SetReader};
pub use schema::{decode_record, encode_pair, PairRecord};
pub use set_schema::{decode_set_record, encode_set, SetRecord};
pub use writer::{DatasetWriter, INDEX_FILE, PAIRS_FILE, SETS_FILE};
