//! Generator configuration: the built-in defaults, a TOML file, or command-line flags.

use serde::{Deserialize, Serialize};

use pairs::{PairKind, SetMode};

use articulated::categories::{self, Category, Split};
pub use assets::ImportOptions;
pub use scanner::config::ScanConfig;

/// Everything that determines a generated dataset; together with the generator version it
/// makes the dataset reproducible byte for byte.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct GeneratorConfig {
    /// Kind of pairs: `SF2F` (full to full), `SF2P` (full to scan) or `SP2P` (scan to scan).
    pub kind: PairKind,
    /// Number of objects (the paper: 175).
    pub objects: u32,
    /// Articulation states drawn per object (the paper: 10).
    pub states_per_object: u32,
    /// Pairs of distinct states per object (the paper: 5).
    pub pairs_per_object: u32,
    /// Points per cloud N (the paper: 512).
    pub points: u32,
    /// Dataset seed.
    pub seed: u64,
    /// Category split to draw objects from (`test` for benchmarks, `train` for training).
    pub split: Split,
    /// Categories to draw objects from, in turn; empty means every category of `split`.
    pub categories: Vec<String>,
    /// Largest global rotation applied to each shape, degrees.
    pub pose_rotation_deg: f64,
    /// Largest global translation applied to each shape along each axis, object units.
    pub pose_translation: f64,
    /// Probability that a joint sits at its rest value (closed) in a drawn state.
    pub rest_probability: f64,
    /// Fewest points any part may have in either cloud (the paper drops parts under 10).
    pub min_part_points: u32,
    /// The virtual scanner, for the scanned kinds (built-in defaults when absent; a scanned
    /// dataset's manifest always records the values used).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub scan: Option<ScanConfig>,
    /// Training streams only: scanned pairs made after each full pair, from new
    /// viewpoints of the same two shapes (the paper's mix: 5), alternating SF2P and SP2P.
    #[serde(skip_serializing_if = "is_zero")]
    pub scanned_per_pair: u32,
    /// How user assets are read (`generator --assets`; built-in defaults when absent).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub import: Option<ImportOptions>,
    /// Present for a set dataset (`generator --kind sets`): K views of each object instead
    /// of pairs; `kind` and `pairs_per_object` do not apply.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sets: Option<SetsConfig>,
}

/// A set dataset: K observations of one object in K distinct articulation states (the
/// MultiBodySync setting).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SetsConfig {
    /// Views K per set, 2 to [`MAX_VIEWS`].
    pub views: u32,
    /// `full` (every view a full shape), `scan` (every view a virtual scan) or `mixed`
    /// (view 0 full, the others scans).
    pub mode: SetMode,
    /// Sets per object, each of K distinct states drawn from the object's states.
    pub per_object: u32,
}

/// Most views a set may have.
pub const MAX_VIEWS: u32 = 16;

impl Default for SetsConfig {
    fn default() -> Self {
        Self { views: 4, mode: SetMode::Full, per_object: 1 }
    }
}

fn is_zero(n: &u32) -> bool {
    *n == 0
}

impl Default for GeneratorConfig {
    fn default() -> Self {
        Self {
            kind: PairKind::Sf2f,
            objects: 175,
            states_per_object: 10,
            pairs_per_object: 5,
            points: 512,
            seed: 0,
            split: Split::Test,
            categories: Vec::new(),
            pose_rotation_deg: 15.0,
            pose_translation: 0.05,
            rest_probability: 0.3,
            min_part_points: 10,
            scan: None,
            scanned_per_pair: 0,
            import: None,
            sets: None,
        }
    }
}

/// A configuration that cannot generate a dataset.
#[derive(Debug, thiserror::Error, PartialEq)]
#[non_exhaustive]
pub enum ConfigError {
    /// A named category is not built in.
    #[error("unknown category {name:?}; known: {known}")]
    UnknownCategory {
        /// The name given.
        name: String,
        /// The built-in names, comma-separated.
        known: String,
    },
    /// A count or range is out of bounds.
    #[error("field `{field}`: {reason}")]
    Invalid {
        /// Config field.
        field: &'static str,
        /// What is wrong.
        reason: String,
    },
}

impl GeneratorConfig {
    /// The defaults with the training split: what the training stream and
    /// `generator --split train` use unless told otherwise.
    pub fn training() -> Self {
        Self { split: Split::Train, ..Self::default() }
    }

    /// The built-in defaults for a kind: the paper's protocol, with the scanner's
    /// defaults written out for the scanned kinds.
    pub fn of_kind(kind: PairKind) -> Self {
        Self { kind, ..Self::default() }.resolved()
    }

    /// The import settings in force: the config's, or the built-in defaults.
    pub fn importer(&self) -> ImportOptions {
        self.import.clone().unwrap_or_default()
    }

    /// The scanner settings in force: the config's, or the built-in defaults.
    pub fn scanner(&self) -> ScanConfig {
        self.scan.clone().unwrap_or_default()
    }

    /// The config with every value it uses written out: the scanner's settings for the
    /// scanned kinds (a full-shape config keeps none), so manifests record all of them.
    pub fn resolved(&self) -> Self {
        let scanned = match &self.sets {
            Some(sets) => sets.mode != SetMode::Full,
            None => self.kind.scanned_q(),
        };
        let scan = scanned.then(|| self.scanner());
        Self { scan, ..self.clone() }
    }

    /// Checks every field; the first problem is returned.
    pub fn validate(&self) -> Result<(), ConfigError> {
        let invalid =
            |field, reason: &str| Err(ConfigError::Invalid { field, reason: reason.into() });
        if self.objects == 0 {
            return invalid("objects", "must be at least 1");
        }
        if self.states_per_object < 2 {
            return invalid("states_per_object", "must be at least 2");
        }
        let possible = self.states_per_object * (self.states_per_object - 1) / 2;
        let pairs = self.sets.is_none();
        if pairs && (self.pairs_per_object == 0 || self.pairs_per_object > possible) {
            return invalid(
                "pairs_per_object",
                &format!("must be 1 to {possible} (pairs of distinct states)"),
            );
        }
        if self.points < 8 {
            return invalid("points", "must be at least 8");
        }
        if self.min_part_points > self.points / 2 {
            return invalid("min_part_points", "must be at most half of `points`");
        }
        if !(0.0..1.0).contains(&self.rest_probability) {
            return invalid("rest_probability", "must be in [0, 1)");
        }
        if !(0.0..=180.0).contains(&self.pose_rotation_deg) {
            return invalid("pose_rotation_deg", "must be in [0, 180]");
        }
        if !(self.pose_translation >= 0.0 && self.pose_translation.is_finite()) {
            return invalid("pose_translation", "must be finite and non-negative");
        }
        if let Some(sets) = &self.sets {
            if !(2..=MAX_VIEWS).contains(&sets.views) {
                return invalid("sets.views", &format!("must be 2 to {MAX_VIEWS}"));
            }
            if sets.per_object == 0 || sets.per_object > 64 {
                return invalid("sets.per_object", "must be 1 to 64");
            }
            if self.kind.cross_instance() {
                return invalid("kind", "a set dataset observes one object (not XF2F or XF2P)");
            }
        }
        self.scanner()
            .validate()
            .map_err(|e| ConfigError::Invalid { field: e.field, reason: e.reason })?;
        if let Some(import) = &self.import {
            if let Err(reason) = import.continuous_range() {
                return Err(ConfigError::Invalid { field: "import.continuous_range_deg", reason });
            }
        }
        self.categories().map(|_| ())
    }

    /// The categories objects are drawn from, in turn.
    pub fn categories(&self) -> Result<Vec<&'static Category>, ConfigError> {
        if self.categories.is_empty() {
            return Ok(categories::of_split(self.split));
        }
        self.categories
            .iter()
            .map(|name| {
                categories::find(name).ok_or_else(|| ConfigError::UnknownCategory {
                    name: name.clone(),
                    known: categories::CATEGORIES
                        .iter()
                        .map(|c| c.name)
                        .collect::<Vec<_>>()
                        .join(", "),
                })
            })
            .collect()
    }

    /// Number of pairs the dataset will hold (of sets, for a set dataset).
    pub fn total_pairs(&self) -> u64 {
        u64::from(self.objects) * u64::from(self.items_per_object())
    }

    /// Pairs (or sets) each object gives.
    pub fn items_per_object(&self) -> u32 {
        self.sets.as_ref().map_or(self.pairs_per_object, |s| s.per_object)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_the_paper_protocol_and_valid() {
        let c = GeneratorConfig::default();
        c.validate().expect("defaults are valid");
        assert_eq!(c.total_pairs(), 875);
    }

    #[test]
    fn the_committed_default_config_matches_the_built_in_one() {
        let text = include_str!("../../datasets/sf2f.toml");
        let parsed: GeneratorConfig = toml::from_str(text).expect("parses");
        assert_eq!(parsed, GeneratorConfig::default());
        for (text, kind) in [
            (include_str!("../../datasets/sf2p.toml"), PairKind::Sf2p),
            (include_str!("../../datasets/sp2p.toml"), PairKind::Sp2p),
        ] {
            let parsed: GeneratorConfig = toml::from_str(text).expect("parses");
            assert_eq!(parsed, GeneratorConfig::of_kind(kind));
        }
    }

    #[test]
    fn bad_configs_name_the_field() {
        let cases = [
            (GeneratorConfig { objects: 0, ..Default::default() }, "objects"),
            (GeneratorConfig { pairs_per_object: 50, ..Default::default() }, "pairs_per_object"),
            (
                GeneratorConfig { categories: vec!["toaster".into()], ..Default::default() },
                "toaster",
            ),
            (
                GeneratorConfig {
                    scan: Some(ScanConfig { dropout: 1.5, ..Default::default() }),
                    ..Default::default()
                },
                "dropout",
            ),
        ];
        for (config, needle) in cases {
            let err = config.validate().expect_err(needle).to_string();
            assert!(err.contains(needle), "{err}");
        }
        assert!(toml::from_str::<GeneratorConfig>("pointz = 3").is_err());
    }
}
