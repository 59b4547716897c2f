//! The one way our MCAP files (datasets, set datasets, prediction files) are written, so that
//! the same records give the same bytes on every machine: zstd chunks compressed on one
//! thread (multithreaded zstd output depends on the machine's core count), chunks of a
//! fixed uncompressed size (bounding the writer's memory whatever the file's size), and no
//! profile or library string that would change with the writer's version.

use std::fs::File;
use std::io::BufWriter;

use mcap::{Compression, McapResult, WriteOptions, Writer};

/// Uncompressed chunk size.
pub const CHUNK_BYTES: u64 = 4 << 20;

/// An MCAP writer on `file` with the settings above.
pub fn reproducible_writer(file: File) -> McapResult<Writer<BufWriter<File>>> {
    WriteOptions::new()
        .compression(Some(Compression::Zstd))
        .compression_threads(0)
        .chunk_size(Some(CHUNK_BYTES))
        .profile("")
        .create(BufWriter::new(file))
}
