//! The Channel and Message records of an MCAP byte stream, read forward in bounded memory
//! with every checksum validated: what the dataset reader and the prediction reader share.
//!
//! Before `mcap::parse_record` sees a Channel record, its length fields are checked against
//! the record's own size: the mcap crate reserves the length a string field claims before it
//! checks that the record holds that many bytes, so a corrupt length (found by fuzzing the
//! readers) would allocate gigabytes.
//!
//! Chunks are taken whole from the mcap crate's reader and opened here: decompressed (zstd,
//! or stored), checked against their CRC, and their records split with every length checked
//! against what is left of the chunk. The crate's own chunk reader subtracts an inner
//! record's length from the chunk's remaining size unchecked (a fuzzed stored chunk made it
//! overflow).

use std::io::{ErrorKind, Read};

use mcap::records::{op, Record};
use mcap::sans_io::{LinearReadEvent, LinearReader, LinearReaderOptions};
use mcap::McapError;

/// Largest record the readers buffer; a corrupt length field beyond it is an error, not an
/// allocation.
const RECORD_LIMIT: usize = 256 << 20;

/// Why the next record could not be read.
#[derive(Debug)]
pub(crate) enum StreamError {
    /// Reading the byte stream failed.
    Io(std::io::Error),
    /// The MCAP structure is broken (truncated, a checksum, a record that does not parse).
    Mcap(mcap::McapError),
    /// A Channel record's length fields claim more bytes than it has.
    CorruptChannel,
}

impl StreamError {
    /// What a reader says about a corrupt channel record.
    pub(crate) const CORRUPT_CHANNEL: &'static str =
        "a channel record's length fields exceed it (corrupt)";
}

/// The Channel and Message records of a byte stream, in file order.
pub(crate) struct RecordStream<R> {
    source: R,
    reader: LinearReader,
    /// The records of the chunk being read, and where the next one starts.
    chunk: Option<(Vec<u8>, usize)>,
}

impl<R: Read> RecordStream<R> {
    /// Reads `source` from its start.
    pub(crate) fn new(source: R) -> Self {
        let options = LinearReaderOptions::default()
            .with_validate_chunk_crcs(true)
            .with_validate_summary_section_crc(true)
            .with_validate_data_section_crc(true)
            .with_record_length_limit(RECORD_LIMIT)
            .with_emit_chunks(true);
        Self { source, reader: LinearReader::new_with_options(options), chunk: None }
    }

    /// The next Channel or Message record, `Ok(None)` at the stream's clean end.
    pub(crate) fn next_record(&mut self) -> Result<Option<Record<'static>>, StreamError> {
        loop {
            if let Some(record) = self.next_in_chunk()? {
                return Ok(Some(record));
            }
            let Some((opcode, data)) = self.next_outer()? else { return Ok(None) };
            if opcode == op::CHUNK {
                self.chunk = Some((open_chunk(&data)?, 0));
            } else if let Some(record) = wanted(opcode, &data)? {
                return Ok(Some(record));
            }
        }
    }

    /// The next Channel or Message record of the open chunk; `None` once it is read out.
    fn next_in_chunk(&mut self) -> Result<Option<Record<'static>>, StreamError> {
        while let Some((records, at)) = &mut self.chunk {
            let rest = &records[*at..];
            if rest.is_empty() {
                self.chunk = None;
                break;
            }
            let corrupt = || StreamError::Mcap(McapError::UnexpectedEoc);
            let header = rest.get(..9).ok_or_else(corrupt)?;
            let len = u64::from_le_bytes(header[1..9].try_into().expect("eight bytes"));
            let len =
                usize::try_from(len).ok().filter(|&l| l <= rest.len() - 9).ok_or_else(corrupt)?;
            let (opcode, data) = (header[0], &rest[9..9 + len]);
            *at += 9 + len;
            if let Some(record) = wanted(opcode, data)? {
                return Ok(Some(record));
            }
        }
        Ok(None)
    }

    /// The next record outside chunks (a chunk whole), `None` at the stream's clean end.
    fn next_outer(&mut self) -> Result<Option<(u8, Vec<u8>)>, StreamError> {
        while let Some(event) = self.reader.next_event() {
            match event.map_err(StreamError::Mcap)? {
                LinearReadEvent::ReadRequest(need) => {
                    let buf = self.reader.insert(need);
                    let n = loop {
                        match self.source.read(buf) {
                            Err(e) if e.kind() == ErrorKind::Interrupted => continue,
                            other => break other.map_err(StreamError::Io)?,
                        }
                    };
                    self.reader.notify_read(n);
                }
                LinearReadEvent::Record { opcode, data } => {
                    if opcode == op::CHUNK || opcode == op::CHANNEL || opcode == op::MESSAGE {
                        return Ok(Some((opcode, data.to_vec())));
                    }
                }
            }
        }
        Ok(None)
    }
}

/// A Channel or Message record parsed, `None` for any other record.
fn wanted(opcode: u8, data: &[u8]) -> Result<Option<Record<'static>>, StreamError> {
    if opcode != op::CHANNEL && opcode != op::MESSAGE {
        return Ok(None);
    }
    if opcode == op::CHANNEL && !channel_lengths_fit(data) {
        return Err(StreamError::CorruptChannel);
    }
    let record = mcap::parse_record(opcode, data).map_err(StreamError::Mcap)?;
    Ok(Some(record.into_owned()))
}

/// The records of a chunk: its data decompressed (zstd) or as stored, of the size and CRC
/// its header gives.
fn open_chunk(body: &[u8]) -> Result<Vec<u8>, StreamError> {
    // The header's compression string (u32 length at bytes 28..32) and the records' u64
    // length must fit the record before the mcap crate reserves what the string claims.
    let compression = body.get(28..32).map(|b| u32::from_le_bytes(b.try_into().expect("4")));
    let fits =
        compression.is_some_and(|n| (n as usize).checked_add(40).is_some_and(|e| e <= body.len()));
    if !fits {
        let available = body.len() as u64;
        let header = compression.map_or(0, |n| u64::from(n) + 40);
        return Err(StreamError::Mcap(McapError::BadChunkLength { header, available }));
    }
    let Record::Chunk { header, data } =
        mcap::parse_record(op::CHUNK, body).map_err(StreamError::Mcap)?
    else {
        return Err(StreamError::Mcap(McapError::UnexpectedEoc));
    };
    let mcap = |e: McapError| StreamError::Mcap(e);
    let size = usize::try_from(header.uncompressed_size)
        .ok()
        .filter(|&n| n <= RECORD_LIMIT)
        .ok_or(mcap(McapError::ChunkTooLarge(header.uncompressed_size)))?;
    let records = match header.compression.as_str() {
        "" => data.into_owned(),
        "zstd" => zstd::bulk::decompress(&data, size)
            .map_err(|e| mcap(McapError::DecompressionError(e.to_string())))?,
        other => return Err(mcap(McapError::UnsupportedCompression(other.into()))),
    };
    if records.len() != size {
        let available = records.len() as u64;
        return Err(mcap(McapError::BadChunkLength { header: size as u64, available }));
    }
    let calculated = crc32fast::hash(&records);
    if header.uncompressed_crc != 0 && calculated != header.uncompressed_crc {
        return Err(mcap(McapError::BadChunkCrc { saved: header.uncompressed_crc, calculated }));
    }
    Ok(records)
}

/// Whether every length field of a Channel record's body (`id` u16, `schema_id` u16,
/// `topic` and `message_encoding` strings, `metadata` map of strings, each a u32 length
/// then the bytes) stays within `data`.
fn channel_lengths_fit(data: &[u8]) -> bool {
    /// The u32 length at `at` and the offset after its bytes, if they end by `end`.
    fn field(data: &[u8], at: usize, end: usize) -> Option<usize> {
        let bytes = data.get(at..at.checked_add(4)?)?;
        let len = u32::from_le_bytes(bytes.try_into().ok()?) as usize;
        let after = (at + 4).checked_add(len)?;
        (after <= end).then_some(after)
    }
    let check = || -> Option<()> {
        let end = data.len();
        let topic_end = field(data, 4, end)?;
        let encoding_end = field(data, topic_end, end)?;
        let map_end = field(data, encoding_end, end)?;
        let mut at = encoding_end + 4;
        while at < map_end {
            let key_end = field(data, at, map_end)?;
            at = field(data, key_end, map_end)?;
        }
        Some(())
    };
    check().is_some()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn string(s: &str) -> Vec<u8> {
        [&(s.len() as u32).to_le_bytes()[..], s.as_bytes()].concat()
    }

    #[test]
    fn chunks_are_opened_with_every_length_checked() {
        let records = [&[op::CHANNEL][..], &3u64.to_le_bytes(), b"abc"].concat();
        let chunk = |compression: &[u8], claimed: u32, size: u64, data: &[u8]| {
            [
                &[0u8; 16][..],
                &size.to_le_bytes(),
                &crc32fast::hash(data).to_le_bytes(),
                &claimed.to_le_bytes(),
                compression,
                &(data.len() as u64).to_le_bytes(),
                data,
            ]
            .concat()
        };
        let stored = chunk(b"", 0, records.len() as u64, &records);
        assert_eq!(open_chunk(&stored).expect("a stored chunk"), records);
        // A compression string claimed longer than the record: refused before any
        // allocation of its length.
        let overlong = chunk(b"", u32::MAX, records.len() as u64, &records);
        assert!(open_chunk(&overlong).is_err());
        assert!(open_chunk(&stored[..20]).is_err(), "a truncated header");
        let wrong_size = chunk(b"", 0, 999, &records);
        assert!(open_chunk(&wrong_size).is_err());
        let mut bad_crc = stored.clone();
        bad_crc[24] ^= 1;
        assert!(open_chunk(&bad_crc).is_err());
        assert!(open_chunk(&chunk(b"lz4", 3, records.len() as u64, &records)).is_err());
    }

    #[test]
    fn whole_records_fit_and_overlong_lengths_do_not() {
        let map = [string("schema"), string("x.Pair")].concat();
        let record = [
            &[1, 0, 0, 0][..],
            &string("/pair"),
            &string("cbor"),
            &(map.len() as u32).to_le_bytes(),
            &map,
        ]
        .concat();
        assert!(channel_lengths_fit(&record));
        assert!(!channel_lengths_fit(&record[..record.len() - 1]), "truncated");
        let mut overlong = record.clone();
        overlong[4..8].copy_from_slice(&u32::MAX.to_le_bytes());
        assert!(!channel_lengths_fit(&overlong), "a topic longer than the record");
        let mut inner = record.clone();
        let key = 4 + 9 + 8 + 4;
        inner[key..key + 4].copy_from_slice(&1000u32.to_le_bytes());
        assert!(!channel_lengths_fit(&inner), "a key longer than the map");
    }
}
