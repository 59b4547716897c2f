//! Pictures of the category library: each category closed and opened, drawn as shaded
//! point splats coloured by link, for docs/DATASETS.md and for checking a new category by eye.

use std::path::{Path, PathBuf};

use image::{Rgb, RgbImage};
use pairs::dataset::viz::part_colour;
use pairs::math::{Point3, Real, Rotation3};

use articulated::categories::{Category, CATEGORIES};
use articulated::kinematics::link_poses;
use articulated::objects::ArticulatedObject;
use articulated::sampling::SurfaceSampler;
use articulated::seed::{rng_for, Stream};

/// Side of one square panel, pixels; a category's picture is two panels side by side.
pub const PANEL: u32 = 200;
/// Surface points drawn per panel.
const POINTS: usize = 9000;
/// Splat radius, pixels.
const SPLAT: i32 = 2;
/// Thumbnails per row of the overview picture.
const COLUMNS: u32 = 4;

/// Why the gallery could not be written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum GalleryError {
    /// A picture could not be encoded or written.
    #[error("writing {path}: {source}")]
    Image {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        source: image::ImageError,
    },
    /// The folder or the index could not be written.
    #[error("writing {path}: {source}")]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// What went wrong.
        source: std::io::Error,
    },
}

/// The two states drawn: every joint at rest, and every joint 70% of the way from rest to
/// its farther limit.
pub fn closed_and_open(object: &ArticulatedObject) -> [Vec<Real>; 2] {
    let rest = object.joints.iter().map(|j| j.rest).collect();
    let open = object
        .joints
        .iter()
        .map(|j| {
            let far =
                if j.limits.1 - j.rest >= j.rest - j.limits.0 { j.limits.1 } else { j.limits.0 };
            j.rest + 0.7 * (far - j.rest)
        })
        .collect();
    [rest, open]
}

/// Instance `seed` of `category` closed (left) and opened (right), seen from the front,
/// right and above, both panels at one scale.
pub fn render_category(category: &Category, seed: u64) -> RgbImage {
    let object = (category.build)(&mut rng_for(seed, 0, Stream::Object));
    let samples =
        SurfaceSampler::new(&object).sample(&object, POINTS, &mut rng_for(seed, 0, Stream::States));
    let view = view();
    let states = closed_and_open(&object);
    let views: Vec<Vec<(Point3, usize)>> = states
        .iter()
        .map(|values| {
            let poses = link_poses(&object, values);
            samples.iter().map(|s| (view * s.posed(&poses), s.link)).collect()
        })
        .collect();
    let bounds = pairs::math::bounds(views.iter().flatten().map(|(p, _)| p))
        .unwrap_or((Point3::origin(), Point3::origin()));
    let mut image = RgbImage::from_pixel(2 * PANEL, PANEL, Rgb([255, 255, 255]));
    for (panel, points) in views.iter().enumerate() {
        draw_panel(&mut image, panel as u32 * PANEL, points, bounds, SPLAT);
    }
    image
}

/// One `PANEL`-sized picture of `points` from the gallery's viewpoint, coloured by `labels`
/// with the datasets' part palette (a segmentation of a pair's cloud, for example), drawn
/// with splats of radius `splat` pixels.
pub fn render_labelled(points: &[Point3], labels: &[u32], splat: i32) -> RgbImage {
    let viewed: Vec<(Point3, usize)> =
        points.iter().zip(labels).map(|(p, &l)| (view() * p, l as usize)).collect();
    let bounds = pairs::math::bounds(viewed.iter().map(|(p, _)| p))
        .unwrap_or((Point3::origin(), Point3::origin()));
    let mut image = RgbImage::from_pixel(PANEL, PANEL, Rgb([255, 255, 255]));
    draw_panel(&mut image, 0, &viewed, bounds, splat);
    image
}

/// The gallery's viewpoint: from the front, right and above.
fn view() -> Rotation3 {
    Rotation3::from_euler_angles(0.45, -0.6, 0.0)
}

/// Splats `points` (view frame, with their link) into the panel at column `x0`, far points
/// first, shading nearer points lighter; `bounds` maps the view box onto the panel.
fn draw_panel(
    image: &mut RgbImage,
    x0: u32,
    points: &[(Point3, usize)],
    bounds: (Point3, Point3),
    splat: i32,
) {
    let (lo, hi) = bounds;
    let extent = (hi.x - lo.x).max(hi.y - lo.y).max(1e-6);
    let scale = (PANEL as Real - 4.0 * splat as Real - 8.0) / extent;
    let centre = nalgebra::center(&lo, &hi);
    let depth = (hi.z - lo.z).max(1e-6);
    let mut order: Vec<&(Point3, usize)> = points.iter().collect();
    order.sort_by(|a, b| a.0.z.total_cmp(&b.0.z));
    let half = PANEL as Real * 0.5;
    for (p, link) in order {
        let px = (half + (p.x - centre.x) * scale) as i32 + x0 as i32;
        let py = (half - (p.y - centre.y) * scale) as i32;
        let shade = 0.55 + 0.45 * (p.z - lo.z) / depth;
        // The palette of the datasets' Foxglove channels, so a link looks the same in both.
        let colour = Rgb(part_colour((link % 256) as u8).map(|c| (c as Real * shade) as u8));
        for dy in -splat..=splat {
            for dx in -splat..=splat {
                let (x, y) = (px + dx, py + dy);
                let inside =
                    x >= x0 as i32 && x < (x0 + PANEL) as i32 && (0..PANEL as i32).contains(&y);
                if inside && dx * dx + dy * dy <= splat * splat {
                    image.put_pixel(x as u32, y as u32, colour);
                }
            }
        }
    }
}

/// Writes `<category>.png` for every category, `overview.png` (all of them, in library
/// order, four to a row) and `README.md` (a table naming each picture) into `dir`;
/// `progress` is called after each category. Returns the files written.
pub fn write_gallery(
    dir: &Path,
    seed: u64,
    mut progress: impl FnMut(&Category),
) -> Result<Vec<PathBuf>, GalleryError> {
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| GalleryError::Io { path, source }
    };
    std::fs::create_dir_all(dir).map_err(io(dir))?;
    let rows = (CATEGORIES.len() as u32).div_ceil(COLUMNS);
    let mut overview = RgbImage::from_pixel(COLUMNS * 2 * PANEL, rows * PANEL, Rgb([255; 3]));
    let mut written = Vec::new();
    let mut index = String::from(
        "# Category gallery\n\nEach category's first instance (seed 0), closed and opened 70%, \
         coloured by link (grey: the static root). Made by `cargo run -p generator -- --gallery`.\n\n\
         | category | split | picture |\n| --- | --- | --- |\n",
    );
    for (i, category) in CATEGORIES.iter().enumerate() {
        let picture = render_category(category, seed);
        let (col, row) = (i as u32 % COLUMNS, i as u32 / COLUMNS);
        image::imageops::replace(
            &mut overview,
            &picture,
            i64::from(col * 2 * PANEL),
            i64::from(row * PANEL),
        );
        let path = dir.join(format!("{}.png", category.name));
        save(&picture, &path)?;
        let splits: Vec<&str> = category.splits.iter().map(|s| s.as_str()).collect();
        index.push_str(&format!(
            "| **{}**: {} | {} | ![{0}]({0}.png) |\n",
            category.name,
            category.description,
            splits.join(", ")
        ));
        written.push(path);
        progress(category);
    }
    let path = dir.join("overview.png");
    save(&overview, &path)?;
    written.push(path);
    let path = dir.join("README.md");
    std::fs::write(&path, index).map_err(io(&path))?;
    written.push(path);
    Ok(written)
}

/// Saves a PNG, naming the file on failure.
fn save(picture: &RgbImage, path: &Path) -> Result<(), GalleryError> {
    picture.save(path).map_err(|source| GalleryError::Image { path: path.to_path_buf(), source })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_picture_shows_both_states_in_colour_and_repeats() {
        let laptop = articulated::categories::find("laptop").expect("laptop");
        let picture = render_category(laptop, 0);
        assert_eq!(picture.dimensions(), (2 * PANEL, PANEL));
        let painted = |x0: u32| {
            (x0..x0 + PANEL)
                .flat_map(|x| (0..PANEL).map(move |y| (x, y)))
                .filter(|&(x, y)| picture.get_pixel(x, y).0 != [255; 3])
                .count()
        };
        let (closed, open) = (painted(0), painted(PANEL));
        assert!(closed > 2000 && open > closed, "{closed} {open}");
        // The lid (link 1) shows in its part colour, red.
        assert!(picture.pixels().any(|p| u16::from(p.0[0]) > u16::from(p.0[2]) + 60));
        assert_eq!(picture, render_category(laptop, 0));
    }
}
