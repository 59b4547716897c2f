//! Why generation failed.

use pairs::{DatasetError, PairError};

use crate::config::ConfigError;
use crate::generate::{PARTNER_ATTEMPTS, SET_ATTEMPTS};
use articulated::objects::ObjectError;
use scanner::scene::SceneError;

/// Why generation failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum GenerateError {
    /// The configuration is invalid.
    #[error("invalid config: {0}")]
    Config(#[from] ConfigError),
    /// A category built an object that breaks the model's rules.
    #[error("object {object}: {source}")]
    Object {
        /// Object index.
        object: u32,
        /// The broken rule.
        source: ObjectError,
    },
    /// An object could not give enough valid pairs (parts too small to be sampled).
    #[error("object {object} ({category}): only {found} of {wanted} pairs have every part with at least {min} points; raise `points` or lower `min_part_points`")]
    TooFewPairs {
        /// Object index.
        object: u32,
        /// Its category.
        category: String,
        /// Valid pairs found.
        found: usize,
        /// Pairs wanted.
        wanted: usize,
        /// The config's `min_part_points`.
        min: u32,
    },
    /// No second instance of the object's category could be matched to it part for part
    /// (cross-instance kinds).
    #[error("object {object} ({category}): none of {PARTNER_ATTEMPTS} other instances of its category has the same links and joints and gives the pairs wanted")]
    NoPartner {
        /// Object index.
        object: u32,
        /// Its category.
        category: String,
    },
    /// An object could not give a set: no draw of K distinct states had every set part
    /// seen in every view.
    #[error("object {object} ({category}): none of {SET_ATTEMPTS} draws of {views} distinct states gives a set whose every part has at least {min} points in every view; lower `sets.views` or `min_part_points`, or raise `points`")]
    TooFewSets {
        /// Object index.
        object: u32,
        /// Its category.
        category: String,
        /// Views per set.
        views: u32,
        /// The config's `min_part_points`.
        min: u32,
    },
    /// The pair of two views would merge links that the set keeps apart (a generator bug).
    #[error("object {object}: the pair of views {i} and {j} groups links across set parts")]
    SetParts {
        /// Object index.
        object: u32,
        /// View taken as P.
        i: usize,
        /// View taken as Q.
        j: usize,
    },
    /// A generated pair broke an invariant (a generator bug).
    #[error("generated an invalid pair: {0}")]
    Pair(#[from] PairError),
    /// A generated set broke an invariant (a generator bug).
    #[error("generated an invalid set: {0}")]
    Set(#[from] pairs::SetError),
    /// Writing the dataset failed.
    #[error(transparent)]
    Dataset(#[from] DatasetError),
    /// The posed object could not be ray cast.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// Encoding a scan's images failed.
    #[error("encoding a scan image: {0}")]
    Image(#[from] image::ImageError),
    /// A shard was asked for that does not exist, or shards do not fit together.
    #[error(transparent)]
    Shard(#[from] crate::shard::ShardError),
}
