//! The PNG images of a scan: 16-bit depth, 8-bit part labels, and colour with one shade
//! per part. Encoding is fixed (fast deflate, one filter), so the bytes repeat exactly.

use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{ExtendedColorType, ImageEncoder};
use pairs::dataset::viz::part_colour;
use pairs::math::Real;
use pairs::scan::ScanImages;
use pairs::PartId;

use super::noise::Observed;
use super::render::{Render, NO_LINK};

/// Largest value of the 16-bit depth image; 0 means no return.
const DEPTH_MAX: Real = 65535.0;
/// Background of the colour image.
const BACKGROUND: [u8; 3] = [255, 255, 255];

/// The depth scale (object units per PNG unit) that fits depths up to `far`.
pub fn depth_scale(far: Real) -> Real {
    far / (DEPTH_MAX - 1.0)
}

/// The depth image's values: measured depth over `scale`, rounded, at least 1 where
/// something was measured; 0 where nothing was.
pub fn quantise_depth(observed: &Observed, scale: Real) -> Vec<u16> {
    observed
        .depth
        .iter()
        .map(|&z| if z > 0.0 { (z / scale).round().clamp(1.0, DEPTH_MAX) as u16 } else { 0 })
        .collect()
}

/// PNG bytes of the three images of one scan, with links mapped to parts by `part_of_link`.
pub fn encode(
    render: &Render,
    depth: &[u16],
    part_of_link: &[PartId],
) -> Result<ScanImages<Vec<u8>>, image::ImageError> {
    let part = |link: u32| (link != NO_LINK).then(|| part_of_link[link as usize]);
    let depth_bytes: Vec<u8> = depth.iter().flat_map(|d| d.to_ne_bytes()).collect();
    let labels: Vec<u8> = render.link.iter().map(|&l| part(l).map_or(0, |k| k + 1)).collect();
    let colour: Vec<u8> = render
        .link
        .iter()
        .zip(&render.facing)
        .flat_map(|(&l, &facing)| match part(l) {
            None => BACKGROUND,
            Some(k) => part_colour(k).map(|c| (Real::from(c) * (0.3 + 0.7 * facing)) as u8),
        })
        .collect();
    let (w, h) = (render.width, render.height);
    Ok(ScanImages {
        depth: png(&depth_bytes, w, h, ExtendedColorType::L16)?,
        labels: png(&labels, w, h, ExtendedColorType::L8)?,
        colour: png(&colour, w, h, ExtendedColorType::Rgb8)?,
    })
}

/// PNG bytes of one image, written the same way everywhere (fixed compression and filter)
/// so that image files are byte-identical across runs.
pub fn png(
    data: &[u8],
    width: u32,
    height: u32,
    colour: ExtendedColorType,
) -> Result<Vec<u8>, image::ImageError> {
    let mut out = Vec::new();
    PngEncoder::new_with_quality(&mut out, CompressionType::Fast, FilterType::Up)
        .write_image(data, width, height, colour)?;
    Ok(out)
}
