//! A guard before `mcap::parse_record` on a Channel record: the mcap crate reserves the
//! length a string field claims before it checks that the record holds that many bytes, so
//! a corrupt length (found by fuzzing the readers) would allocate gigabytes. Every length
//! field of the record is checked against the record's own size first.

/// Whether every length field of a Channel record's body (`id` u16, `schema_id` u16,
/// `topic` and `message_encoding` strings, `metadata` map of strings, each a u32 length
/// then the bytes) stays within `data`.
pub(crate) fn channel_lengths_fit(data: &[u8]) -> bool {
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
