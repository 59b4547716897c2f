//! One side of a pair scanned: a viewpoint drawn until it sees enough of the object and of
//! every part, the rendering measured, back-projected and thinned to N points.

use pairs::math::{Point3, Real};
use pairs::parts::part_sizes;
use pairs::sampling::farthest_point_sampling;
use pairs::PartId;
use rand::seq::index;
use rand::Rng as _;

use crate::camera::Camera;
use crate::config::ScanConfig;
use crate::noise::{depth_sigma, observe};
use crate::render::{render, Render};
use crate::scene::PosedScene;
use crate::visibility::is_visible;
use crate::{images, scene};
use articulated::objects::ArticulatedObject;
use articulated::sampling::{SurfacePoint, SurfaceSampler};
use articulated::seed::Rng;

/// Surface samples that estimate the fraction of the object a viewpoint sees.
const VISIBILITY_SAMPLES: usize = 256;
/// Visibility tolerance for noise-free surface points, fraction of the object's diagonal.
pub const SURFACE_TOLERANCE: Real = 2e-3;

/// One side of a pair as the scanner saw it.
pub struct ScannedSide {
    /// The camera of the accepted viewpoint.
    pub camera: Camera,
    /// The N sampled points: link and rest-frame position (noise included), so that they
    /// can be placed in any articulation state like surface samples.
    pub samples: Vec<SurfacePoint>,
    /// Per point: whether it is a flying pixel rather than a surface measurement.
    pub outlier: Vec<bool>,
    /// Per point: standard deviation of its depth noise, object units.
    pub sigma: Vec<Real>,
    /// The noise-free rendering (links and shading for the images).
    pub render: Render,
    /// Per pixel: whether the surface it sees is missing from the scan.
    pub lost: Vec<bool>,
    /// The depth image's values (see [`images::quantise_depth`]).
    pub depth: Vec<u16>,
    /// Object units per unit of `depth`.
    pub depth_scale: Real,
    /// The posed object the scan saw, for visibility queries.
    pub scene: PosedScene,
    /// Viewpoints drawn until one was accepted (1 if the first was).
    pub viewpoints: u32,
}

/// What a scanned side must show: a part id per link and the fewest points per part.
pub struct Requirements<'a> {
    /// Part of each link.
    pub part_of_link: &'a [PartId],
    /// Number of parts.
    pub parts: usize,
    /// Points to sample.
    pub points: usize,
    /// Fewest points every part must get.
    pub min_part_points: usize,
}

/// Scans the object in the state given by `poses` from viewpoints drawn from `rng` until
/// one sees at least `min_visible_fraction` of the surface and gives every part at least
/// `min_part_points` of the N points; `None` after `max_viewpoints` tries.
pub fn scan_side(
    object: &ArticulatedObject,
    sampler: &SurfaceSampler,
    poses: &[pairs::math::Isometry3],
    config: &ScanConfig,
    needs: &Requirements,
    rng: &mut Rng,
) -> Result<Option<ScannedSide>, scene::SceneError> {
    let scene = PosedScene::new(object, poses)?;
    let diagonal = scene.diagonal();
    let probes: Vec<(Point3, PartId)> = sampler
        .sample(object, VISIBILITY_SAMPLES, rng)
        .iter()
        .map(|s| (s.posed(poses), needs.part_of_link[s.link]))
        .collect();
    for attempt in 1..=config.max_viewpoints {
        let camera = Camera::draw(config, &scene.centre(), diagonal, rng);
        if !sees_enough(&scene, &camera, &probes, config, needs) {
            continue;
        }
        let render = render(&scene, &camera);
        let observed = observe(&render, config, diagonal, rng);
        let far = (camera.centre() - scene.centre()).norm() + diagonal;
        let depth_scale = images::depth_scale(far);
        let depth = images::quantise_depth(&observed, depth_scale);
        let pixels = back_project(&camera, &render, &depth, depth_scale);
        if pixels.len() < needs.points {
            continue;
        }
        let chosen = sample_pixels(&pixels, needs.points, config.fps_pool as usize, rng);
        let labels: Vec<PartId> =
            chosen.iter().map(|&i| needs.part_of_link[pixels[i].link]).collect();
        if part_sizes(&labels, needs.parts).into_iter().any(|s| s < needs.min_part_points) {
            continue;
        }
        let multiplier = config.depth_noise as Real;
        let samples = chosen
            .iter()
            .map(|&i| {
                let p = &pixels[i];
                SurfacePoint { link: p.link, rest: poses[p.link].inverse_transform_point(&p.point) }
            })
            .collect();
        let outlier = chosen.iter().map(|&i| observed.outlier[pixels[i].pixel]).collect();
        let sigma =
            chosen.iter().map(|&i| depth_sigma(pixels[i].depth, diagonal, multiplier)).collect();
        return Ok(Some(ScannedSide {
            camera,
            samples,
            outlier,
            sigma,
            render,
            lost: observed.lost,
            depth,
            depth_scale,
            scene,
            viewpoints: attempt,
        }));
    }
    Ok(None)
}

/// Whether a viewpoint sees enough of the surface probes, and some of every part.
fn sees_enough(
    scene: &PosedScene,
    camera: &Camera,
    probes: &[(Point3, PartId)],
    config: &ScanConfig,
    needs: &Requirements,
) -> bool {
    let tolerance = SURFACE_TOLERANCE * scene.diagonal();
    let mut seen_parts = vec![false; needs.parts];
    let mut seen = 0usize;
    for (p, part) in probes {
        if is_visible(scene, camera, p, tolerance, None) {
            seen += 1;
            seen_parts[usize::from(*part)] = true;
        }
    }
    seen as f64 >= config.min_visible_fraction * probes.len() as f64
        && seen_parts.iter().all(|&s| s)
}

/// A pixel with a measured depth, back-projected.
struct PixelPoint {
    pixel: usize,
    link: usize,
    depth: Real,
    point: Point3,
}

/// Back-projects every pixel with a depth value, using the quantised depth so that the
/// points are exactly what the stored depth image gives.
fn back_project(camera: &Camera, render: &Render, depth: &[u16], scale: Real) -> Vec<PixelPoint> {
    let width = render.width as usize;
    depth
        .iter()
        .enumerate()
        .filter(|&(_, &d)| d > 0)
        .map(|(pixel, &d)| {
            let z = Real::from(d) * scale;
            let (u, v) = ((pixel % width) as Real, (pixel / width) as Real);
            let local = camera.intrinsics.back_project(u, v, z);
            PixelPoint {
                pixel,
                link: render.link[pixel] as usize,
                depth: z,
                point: camera.pose * local,
            }
        })
        .collect()
}

/// Indices of `n` pixels: farthest point sampling from a random start over a random pool
/// of at most `pool * n` of them.
fn sample_pixels(pixels: &[PixelPoint], n: usize, pool: usize, rng: &mut Rng) -> Vec<usize> {
    let size = pixels.len().min(pool.saturating_mul(n).max(n));
    let mut subset = index::sample(rng, pixels.len(), size).into_vec();
    subset.sort_unstable();
    let points: Vec<Point3> = subset.iter().map(|&i| pixels[i].point).collect();
    let start = rng.random_range(0..points.len());
    if points.len() <= n {
        return subset;
    }
    farthest_point_sampling(&points, n, start).into_iter().map(|i| subset[i]).collect()
}
