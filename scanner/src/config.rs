//! Settings of the virtual scanner: image, viewpoint ranges, noise model and the rules
//! that send a scan back for a new viewpoint. Every default is documented on its field.

use serde::{Deserialize, Serialize};

/// A scanner setting out of its range.
#[derive(Debug, Clone, thiserror::Error, PartialEq)]
#[error("field `{field}`: {reason}")]
pub struct ScanConfigError {
    /// Config field, as written in a config file (`scan.width`).
    pub field: &'static str,
    /// What is wrong.
    pub reason: String,
}

/// The virtual scanner's settings (the `[scan]` table of a config file).
///
/// Viewpoints are drawn around the posed object's bounding-box centre: azimuth about the
/// up axis (+y; 0 looks at the object's front, +z), elevation above the horizontal, and
/// distance as a multiple of the distance at which the bounding sphere just fills the
/// narrower field of view (so at 1.0 nothing of the object leaves the image).
///
/// Noise model, applied in this order to every pixel that sees the object:
/// 1. *edge outliers*: a pixel next to a depth edge (a 4-neighbour that is background or
///    farther by more than 2% of the object's diagonal D) becomes, with probability
///    `edge_outliers`, a flying pixel whose depth lies uniformly between its own and its
///    neighbour's (background counts as 10% of D farther);
/// 2. *dropout*: the pixel returns no depth with probability `dropout`;
/// 3. *depth noise*: Gaussian along the optical axis with the Kinect v1 axial model of
///    Nguyen et al. (2012), σ(z) = 0.0012 + 0.0019 (z - 0.4)² metres, applied to the object
///    scaled to a diagonal of 1 m and multiplied by `depth_noise` (0 turns noise off).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ScanConfig {
    /// Image width, pixels (default 320).
    pub width: u32,
    /// Image height, pixels (default 240).
    pub height: u32,
    /// Vertical field of view, degrees (default 45; square pixels).
    pub fov_y_deg: f64,
    /// Range of the azimuth about +y, degrees; 0 faces the object's front (default the
    /// full circle, -180 to 180).
    pub azimuth_deg: [f64; 2],
    /// Range of the elevation above the horizontal plane, degrees (default -10 to 60).
    pub elevation_deg: [f64; 2],
    /// Range of the distance, as a multiple of the fitting distance (default 1.0 to 1.6).
    pub distance: [f64; 2],
    /// Multiplier of the Kinect depth-noise model (default 1; 0 for noise-free depth).
    pub depth_noise: f64,
    /// Probability that a pixel returns no depth (default 0.02).
    pub dropout: f64,
    /// Probability that a pixel at a depth edge becomes a flying pixel (default 0.1).
    pub edge_outliers: f64,
    /// Fewest fraction of the object's surface a scan must see, else a new viewpoint is
    /// drawn (default 0.15; a single view sees at most about half of a closed surface).
    pub min_visible_fraction: f64,
    /// Viewpoints tried per scan before the pair is given up (default 20).
    pub max_viewpoints: u32,
    /// Farthest point sampling runs on a random subset of this many points per output
    /// point (default 8), which keeps it fast and changes the result little.
    pub fps_pool: u32,
}

impl Default for ScanConfig {
    fn default() -> Self {
        Self {
            width: 320,
            height: 240,
            fov_y_deg: 45.0,
            azimuth_deg: [-180.0, 180.0],
            elevation_deg: [-10.0, 60.0],
            distance: [1.0, 1.6],
            depth_noise: 1.0,
            dropout: 0.02,
            edge_outliers: 0.1,
            min_visible_fraction: 0.15,
            max_viewpoints: 20,
            fps_pool: 8,
        }
    }
}

impl ScanConfig {
    /// Noise-free scans: no depth noise, dropout or outliers.
    pub fn noise_free() -> Self {
        Self { depth_noise: 0.0, dropout: 0.0, edge_outliers: 0.0, ..Self::default() }
    }

    /// Checks every field; the first problem is returned.
    pub fn validate(&self) -> Result<(), ScanConfigError> {
        let invalid = |field, reason: &str| Err(ScanConfigError { field, reason: reason.into() });
        let range = |[lo, hi]: [f64; 2], min: f64, max: f64| {
            lo.is_finite() && hi.is_finite() && min <= lo && lo <= hi && hi <= max
        };
        let probability = |p: f64| (0.0..1.0).contains(&p);
        if !(8..=4096).contains(&self.width) || !(8..=4096).contains(&self.height) {
            return invalid("scan.width/height", "must be 8 to 4096 pixels");
        }
        if !(self.fov_y_deg > 1.0 && self.fov_y_deg < 170.0) {
            return invalid("scan.fov_y_deg", "must be between 1 and 170");
        }
        if !range(self.azimuth_deg, -360.0, 360.0) {
            return invalid("scan.azimuth_deg", "must be [low, high] within -360..360");
        }
        if !range(self.elevation_deg, -80.0, 80.0) {
            return invalid("scan.elevation_deg", "must be [low, high] within -80..80");
        }
        if !range(self.distance, 1.0, 100.0) {
            return invalid("scan.distance", "must be [low, high] within 1..100");
        }
        if !(self.depth_noise >= 0.0 && self.depth_noise <= 100.0) {
            return invalid("scan.depth_noise", "must be in [0, 100]");
        }
        if !probability(self.dropout) {
            return invalid("scan.dropout", "must be in [0, 1)");
        }
        if !probability(self.edge_outliers) {
            return invalid("scan.edge_outliers", "must be in [0, 1)");
        }
        if !probability(self.min_visible_fraction) {
            return invalid("scan.min_visible_fraction", "must be in [0, 1)");
        }
        if self.max_viewpoints == 0 {
            return invalid("scan.max_viewpoints", "must be at least 1");
        }
        if self.fps_pool == 0 {
            return invalid("scan.fps_pool", "must be at least 1");
        }
        Ok(())
    }
}
