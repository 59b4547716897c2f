//! The layouts a render can be written in, by name.

use serde::Serialize;

use super::gt;
use crate::{RenderConfig, RenderJob};
use pairs::renders::WorldFrame;

/// A folder layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Layout {
    /// Ours: every image kind, cameras and joints in one JSON per object (docs/FORMAT.md,
    /// "Renders").
    Native,
    /// PARIS's `data/sapien/<category>/<id>` tree.
    Paris,
    /// DigitalTwinArt's tree.
    Dta,
    /// ArtGS's tree (its own, not DigitalTwinArt's; the same `gt/` folder).
    Artgs,
}

impl Layout {
    /// The name `--layout` takes.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Native => "native",
            Self::Paris => "paris",
            Self::Dta => "dta",
            Self::Artgs => "artgs",
        }
    }

    /// Whether only one joint moves (PARIS models one moving part).
    pub fn one_joint(self) -> bool {
        self == Self::Paris
    }

    /// The states a layout holds, if fixed.
    pub fn states(self) -> Option<u32> {
        match self {
            Self::Native => None,
            Self::Paris | Self::Dta | Self::Artgs => Some(2),
        }
    }

    /// The world a layout writes in: our object frame for `native` and `dta` (which
    /// normalises the scene itself), PARIS's Z-up frame with the object centred and its
    /// largest half extent 1 for `paris` and `artgs`.
    pub fn frame(self, job: &RenderJob) -> WorldFrame {
        match self {
            Self::Native | Self::Dta => WorldFrame::identity(),
            Self::Paris | Self::Artgs => gt::normalised_frame(job, true),
        }
    }

    /// The intrinsics of a layout's cameras from a config: DigitalTwinArt puts the
    /// principal point at `(W/2, H/2)` with pixel centres at integer coordinates
    /// (`nerf_utils.py:20,28`); the others at the image's centre, pixel centres at half
    /// integers (PARIS `models/ray_utils.py:9-19`, ArtGS's field of view).
    pub fn intrinsics(self, config: &RenderConfig) -> pairs::Intrinsics {
        let mut k = config.intrinsics();
        if self == Self::Dta {
            k.cx = 0.5 * k.width as pairs::math::Real;
            k.cy = 0.5 * k.height as pairs::math::Real;
        }
        k
    }
}

impl std::str::FromStr for Layout {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "native" => Ok(Self::Native),
            "paris" => Ok(Self::Paris),
            "dta" | "digitaltwinart" => Ok(Self::Dta),
            "artgs" => Ok(Self::Artgs),
            _ => Err(format!("unknown layout {s:?}: native, paris, dta or artgs")),
        }
    }
}
