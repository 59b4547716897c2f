//! The render settings (`[render]` of `generator render`, docs/FORMAT.md's render
//! settings) and their ranges.

use pairs::math::Real;
use pairs::Intrinsics;
use serde::{Deserialize, Serialize};

use crate::appearance::Lighting;
use crate::cameras::Placement;
use crate::RenderError;

/// Largest image side a render accepts.
pub const MAX_SIDE: u32 = 8192;

/// How objects are rendered (the `[render]` settings of `generator render`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RenderConfig {
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Vertical field of view, degrees (square pixels, principal point at the centre).
    pub fov_y_deg: f64,
    /// Cameras per state (the same cameras see every state).
    pub views: u32,
    /// Where the cameras stand.
    pub placement: Placement,
    /// Fraction of the narrower field of view the object's bounding sphere (over all its
    /// states) fills.
    pub fill: f64,
    /// Articulation states per object, at least 2.
    pub states: u32,
    /// Background colour, 8-bit RGB.
    pub background: [u8; 3],
    /// The lights.
    pub lighting: Lighting,
}

impl Default for RenderConfig {
    fn default() -> Self {
        Self {
            width: 640,
            height: 480,
            fov_y_deg: 40.0,
            views: 24,
            placement: Placement::Sphere,
            fill: 0.9,
            states: 2,
            background: [255, 255, 255],
            lighting: Lighting::default(),
        }
    }
}

impl RenderConfig {
    /// Checks every field's range.
    pub fn validate(&self) -> Result<(), RenderError> {
        let bad = |field: &str, reason: String| RenderError::Config { field: field.into(), reason };
        for (field, v) in [("width", self.width), ("height", self.height)] {
            if v == 0 || v > MAX_SIDE {
                return Err(bad(field, format!("{v} is not in 1..={MAX_SIDE}")));
            }
        }
        if !(self.fov_y_deg > 1.0 && self.fov_y_deg < 179.0) {
            return Err(bad("fov_y_deg", format!("{} is not in (1, 179)", self.fov_y_deg)));
        }
        if self.views == 0 || self.views > 10_000 {
            return Err(bad("views", format!("{} is not in 1..=10000", self.views)));
        }
        if !(self.fill > 0.0 && self.fill <= 1.0) {
            return Err(bad("fill", format!("{} is not in (0, 1]", self.fill)));
        }
        if !(2..=64).contains(&self.states) {
            return Err(bad("states", format!("{} is not in 2..=64", self.states)));
        }
        let l = &self.lighting;
        let lights_ok = l.lights.iter().all(|d| {
            d.intensity.is_finite()
                && d.intensity >= 0.0
                && d.direction.iter().all(|x| x.is_finite())
                && d.direction.iter().any(|&x| x != 0.0)
        });
        if !(l.ambient.is_finite() && l.ambient >= 0.0 && lights_ok) {
            return Err(bad(
                "lighting",
                "ambient and intensities must be finite and >= 0, directions finite and non-zero"
                    .into(),
            ));
        }
        Ok(())
    }

    /// The cameras' intrinsics.
    pub fn intrinsics(&self) -> Intrinsics {
        Intrinsics::with_fov(self.width, self.height, (self.fov_y_deg as Real).to_radians())
    }
}
