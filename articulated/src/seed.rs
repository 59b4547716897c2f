//! Seeded random streams: every random choice comes from the dataset seed and the item it
//! concerns, never from thread order.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// The random generator used everywhere in the generator.
pub type Rng = ChaCha8Rng;

/// What a stream is used for; each purpose of each object gets its own stream.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stream {
    /// Building the object (proportions, options).
    Object,
    /// Drawing the object's articulation states and choosing its pairs.
    States,
    /// Everything of the pair with this index within its object (poses, samples).
    Pair(u32),
    /// The scanner's viewpoints and noise for a candidate pair, in one variant.
    Scan(u32, u32),
    /// The seed of the `k`-th second instance tried for a cross-instance pair.
    Partner(u32),
    /// Choosing the states of the set with this index within its object.
    Set(u32),
    /// Everything of view `k` of candidate set `c` (pose, samples, scan): `View(c, k)`.
    View(u32, u32),
    /// The rendered states of an object (`generator render`).
    RenderStates,
    /// The material and texture an object is rendered with (`generator render`).
    Appearance,
}

/// The random stream for `purpose` of object `object` in a dataset with `seed`.
pub fn rng_for(seed: u64, object: u64, purpose: Stream) -> Rng {
    let mut rng = Rng::seed_from_u64(seed);
    let purpose = match purpose {
        Stream::Object => 0,
        Stream::States => 1,
        Stream::Pair(k) => 2 + u64::from(k),
        // Bit 23 set, then 7 bits of variant and 16 of pair: apart from every `Pair(k)`.
        Stream::Scan(k, v) => 1 << 23 | (u64::from(v) & 0x7f) << 16 | (u64::from(k) & 0xffff),
        // Bit 22 set (under bit 23): apart from every `Pair(k)` below 2^22 and every `Scan`.
        Stream::Partner(k) => 1 << 22 | (u64::from(k) & 0xffff),
        // Bit 21 alone among the high bits: apart from `Pair(k)` below 2^20 and the above.
        Stream::Set(s) => 1 << 21 | (u64::from(s) & 0xffff),
        // Bit 20 under a clear bit 21: 12 bits of candidate set, 8 of view.
        Stream::View(c, k) => 1 << 20 | (u64::from(c) & 0xfff) << 8 | (u64::from(k) & 0xff),
        // Bit 19 under clear bits 20 to 23: apart from `Pair(k)` below 2^19 and the above.
        Stream::RenderStates => 1 << 19,
        Stream::Appearance => 1 << 19 | 1,
    };
    // ChaCha's 64-bit stream id: 24 bits of purpose under 40 bits of object index.
    rng.set_stream((object << 24) | (purpose & 0xff_ffff));
    rng
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::Rng as _;

    #[test]
    fn streams_differ_and_repeat() {
        let draw = |o, p| rng_for(1, o, p).random::<u64>();
        assert_eq!(draw(3, Stream::Pair(2)), draw(3, Stream::Pair(2)));
        assert_ne!(draw(3, Stream::Pair(2)), draw(3, Stream::Pair(1)));
        assert_ne!(draw(3, Stream::Object), draw(4, Stream::Object));
        assert_ne!(draw(3, Stream::Scan(2, 0)), draw(3, Stream::Scan(2, 1)));
        assert_ne!(draw(3, Stream::Scan(2, 0)), draw(3, Stream::Pair(2)));
        assert_ne!(draw(3, Stream::Partner(0)), draw(3, Stream::Partner(1)));
        assert_ne!(draw(3, Stream::Partner(0)), draw(3, Stream::Pair(0)));
        assert_ne!(draw(3, Stream::Set(0)), draw(3, Stream::View(0, 0)));
        assert_ne!(draw(3, Stream::View(0, 1)), draw(3, Stream::View(1, 0)));
        assert_ne!(draw(3, Stream::View(0, 0)), draw(3, Stream::Pair(0)));
        assert_ne!(draw(3, Stream::RenderStates), draw(3, Stream::Appearance));
        assert_ne!(draw(3, Stream::Appearance), draw(3, Stream::States));
    }
}
