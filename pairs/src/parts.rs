//! Part identifiers: the per-point labels of the rigid parts of a pair.

/// Identifier of a rigid part within one pair; part `k` in P is part `k` in Q.
///
/// Part 0 is the part that holds the object's root link (the base).
pub type PartId = u8;

/// Identifier of a predicted segment of a cloud ([`crate::Prediction`]'s `segments_p` and
/// `segments_q`). Segments are a method's answer, not parts: a method may find more
/// segments than the [`MAX_PARTS`] a pair can have, so the type is wider than [`PartId`].
pub type SegmentId = u32;

/// The segmentation that labels every point with its true part: what a perfect method
/// returns (the oracle rows, the gallery's ground-truth panel, tests).
pub fn part_segments(parts: &[PartId]) -> Vec<SegmentId> {
    parts.iter().map(|&k| SegmentId::from(k)).collect()
}

/// Largest number of parts a pair may have (ids `0..MAX_PARTS`).
pub const MAX_PARTS: usize = PartId::MAX as usize + 1;

/// Number of points of each part, for ids below `parts`; ids out of range are ignored.
pub fn part_sizes(ids: &[PartId], parts: usize) -> Vec<usize> {
    let mut sizes = vec![0; parts];
    for &id in ids {
        if let Some(size) = sizes.get_mut(usize::from(id)) {
            *size += 1;
        }
    }
    sizes
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_count_each_part() {
        assert_eq!(part_sizes(&[0, 1, 1, 2, 1], 3), vec![1, 3, 1]);
        assert_eq!(part_sizes(&[0, 5], 2), vec![1, 0]);
    }
}
