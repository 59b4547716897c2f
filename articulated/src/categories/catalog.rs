//! What a category is, the named splits, and look-ups over the built-in library.

use serde::{Deserialize, Serialize};

use super::CATEGORIES;
use crate::objects::ArticulatedObject;
use crate::seed::Rng;

/// A named split of the category library. Training and validation categories are disjoint
/// from test categories but for laptop, which the paper's training and test sets share too.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Split {
    /// Categories (and random assemblies) that models and baselines learn or tune on.
    Train,
    /// Held-out training-like categories for choosing hyper-parameters and thresholds.
    Validation,
    /// Held-out test categories: the benchmark's default datasets use only these.
    Test,
}

impl Split {
    /// Every split, in a fixed order.
    pub const ALL: [Split; 3] = [Split::Train, Split::Validation, Split::Test];

    /// The split's name in configs and manifests.
    pub fn as_str(self) -> &'static str {
        match self {
            Split::Train => "train",
            Split::Validation => "validation",
            Split::Test => "test",
        }
    }
}

impl std::str::FromStr for Split {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Split::ALL
            .into_iter()
            .find(|split| split.as_str().eq_ignore_ascii_case(s))
            .ok_or_else(|| format!("unknown split {s:?} (train, validation or test)"))
    }
}

impl std::fmt::Display for Split {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Test categories only.
pub const TEST: &[Split] = &[Split::Test];
/// Training categories only.
pub const TRAIN: &[Split] = &[Split::Train];
/// Validation categories only.
pub const VALIDATION: &[Split] = &[Split::Validation];
/// A category shared by training and test, as laptop is in the paper.
pub const TRAIN_AND_TEST: &[Split] = &[Split::Train, Split::Test];

/// A procedural category: a name and a builder of random instances.
#[derive(Debug, Clone, Copy)]
pub struct Category {
    /// Name used in configs, manifests and provenance.
    pub name: &'static str,
    /// One sentence on what the objects look like and how they move.
    pub description: &'static str,
    /// The splits the category belongs to.
    pub splits: &'static [Split],
    /// Builds one random instance; the same generator state gives the same object.
    pub build: fn(&mut Rng) -> ArticulatedObject,
}

impl Category {
    /// Whether the category belongs to `split`.
    pub fn in_split(&self, split: Split) -> bool {
        self.splits.contains(&split)
    }
}

/// The built-in category called `name`.
pub fn find(name: &str) -> Option<&'static Category> {
    CATEGORIES.iter().find(|c| c.name == name)
}

/// The built-in categories of `split`, in library order.
pub fn of_split(split: Split) -> Vec<&'static Category> {
    CATEGORIES.iter().filter(|c| c.in_split(split)).collect()
}

/// Names of the categories of every split, for the manifest.
pub fn split_table() -> std::collections::BTreeMap<String, Vec<String>> {
    Split::ALL
        .iter()
        .map(|&s| (s.as_str().to_string(), of_split(s).iter().map(|c| c.name.into()).collect()))
        .collect()
}
