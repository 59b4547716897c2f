//! The scanner's noise model (documented on [`ScanConfig`]): flying pixels at depth
//! edges, dropout, and Kinect-like depth noise that grows with distance.

use pairs::math::Real;
use rand::Rng as _;
use rand_distr::{Distribution, Normal};

use super::render::{Render, NO_LINK};
use crate::config::ScanConfig;
use articulated::seed::Rng;

/// Depth jump, as a fraction of the object's diagonal, that makes a depth edge.
const EDGE_JUMP: Real = 0.02;
/// How far behind the object a background neighbour counts, fraction of the diagonal.
const BACKGROUND_GAP: Real = 0.1;

/// What the scanner returned per pixel, after noise.
#[derive(Debug, Clone, PartialEq)]
pub struct Observed {
    /// Measured depth, object units; 0 where nothing was returned.
    pub depth: Vec<Real>,
    /// Whether the pixel's depth is a flying pixel rather than a surface measurement.
    pub outlier: Vec<bool>,
    /// Whether the surface the pixel sees is missing from the scan (dropped, or replaced by
    /// a flying pixel).
    pub lost: Vec<bool>,
}

/// Standard deviation of the depth noise at depth `z` for an object of diagonal
/// `diagonal`: the Kinect v1 axial model on the object scaled to a 1 m diagonal.
pub fn depth_sigma(z: Real, diagonal: Real, multiplier: Real) -> Real {
    let z = z / diagonal;
    multiplier * diagonal * (0.0012 + 0.0019 * (z - 0.4).powi(2))
}

/// Applies the noise model of `config` to a rendering of an object of diagonal `diagonal`,
/// drawing from `rng` pixel by pixel in row-major order.
pub fn observe(render: &Render, config: &ScanConfig, diagonal: Real, rng: &mut Rng) -> Observed {
    let n = render.depth.len();
    let mut out =
        Observed { depth: render.depth.clone(), outlier: vec![false; n], lost: vec![false; n] };
    let multiplier = config.depth_noise as Real;
    let unit = Normal::new(0.0, 1.0).expect("the unit normal is valid");
    for i in 0..n {
        if render.link[i] == NO_LINK {
            continue;
        }
        if config.edge_outliers > 0.0 {
            if let Some(far) = far_neighbour(render, i, diagonal) {
                if rng.random_bool(config.edge_outliers) {
                    let z = render.depth[i];
                    out.depth[i] = z + rng.random::<Real>() * (far - z);
                    out.outlier[i] = true;
                    out.lost[i] = true;
                    continue;
                }
            }
        }
        if config.dropout > 0.0 && rng.random_bool(config.dropout) {
            out.depth[i] = 0.0;
            out.lost[i] = true;
            continue;
        }
        if multiplier > 0.0 {
            let z = render.depth[i];
            let noise: Real = unit.sample(rng);
            // Never through the camera: a measurement stays in front of it.
            out.depth[i] = (z + noise * depth_sigma(z, diagonal, multiplier)).max(0.5 * z);
        }
    }
    out
}

/// The depth of the farthest 4-neighbour of pixel `i` if it lies across a depth edge
/// (background counts as [`BACKGROUND_GAP`] behind the pixel).
fn far_neighbour(render: &Render, i: usize, diagonal: Real) -> Option<Real> {
    let (w, h) = (render.width as usize, render.height as usize);
    let (u, v) = (i % w, i / w);
    let z = render.depth[i];
    let neighbours = [
        (u > 0).then(|| i - 1),
        (u + 1 < w).then(|| i + 1),
        (v > 0).then(|| i - w),
        (v + 1 < h).then(|| i + w),
    ];
    neighbours
        .into_iter()
        .flatten()
        .map(|j| {
            if render.link[j] == NO_LINK {
                z + BACKGROUND_GAP * diagonal
            } else {
                render.depth[j]
            }
        })
        .filter(|&d| d - z > EDGE_JUMP * diagonal)
        .max_by(Real::total_cmp)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    fn step_render() -> Render {
        // A 4 x 1 strip: background, near, near, far.
        Render {
            width: 4,
            height: 1,
            depth: vec![0.0, 1.0, 1.0, 2.0],
            link: vec![NO_LINK, 0, 0, 1],
            facing: vec![0.0, 1.0, 1.0, 1.0],
        }
    }

    #[test]
    fn noise_free_config_returns_the_rendering() {
        let render = step_render();
        let out = observe(&render, &ScanConfig::noise_free(), 1.0, &mut Rng::seed_from_u64(0));
        assert_eq!(out.depth, render.depth);
        assert!(!out.lost.iter().any(|&l| l));
    }

    #[test]
    fn only_pixels_at_depth_edges_fly_and_they_stay_between_the_surfaces() {
        let render = step_render();
        let config = ScanConfig { edge_outliers: 0.999, ..ScanConfig::noise_free() };
        let out = observe(&render, &config, 1.0, &mut Rng::seed_from_u64(1));
        // Pixel 1 borders the background, pixel 2 the far surface; pixel 3 borders nothing
        // farther.
        assert_eq!(out.outlier, vec![false, true, true, false]);
        assert!(out.depth[1] >= 1.0 && out.depth[1] <= 1.1);
        assert!(out.depth[2] >= 1.0 && out.depth[2] <= 2.0);
    }

    #[test]
    fn depth_noise_grows_with_distance() {
        assert!(depth_sigma(3.0, 1.0, 1.0) > depth_sigma(1.0, 1.0, 1.0));
        assert!((depth_sigma(0.4, 1.0, 1.0) - 0.0012).abs() < 1e-7);
        assert!((depth_sigma(0.8, 2.0, 1.0) - 0.0024).abs() < 1e-7);
    }
}
