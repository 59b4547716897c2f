//! The segmentation gallery: for a few fixed pairs per dataset, P coloured by its
//! ground-truth parts and by each row's predicted segments, side by side in one PNG per pair
//! (`reports/gallery/segmentation/<dataset>/<pair>.png`). Predicted segments are relabelled
//! to the ground-truth part they match (Hungarian, as for IoU), so matching colours mean
//! matching parts; unmatched segments take colours past the parts'.

use std::path::{Path, PathBuf};

use generator::gallery::{render_labelled, PANEL};
use image::{imageops, Rgb, RgbImage};
use pairs::metrics::matched_iou;
use pairs::Pair;

use crate::boards::leaderboard::Scored;
use crate::datasets::LoadedDataset;
use crate::error::EvalError;
use crate::rows::registry::Board;

/// Splat radius for clouds of a few hundred points at the gallery's panel size.
const SPLAT: i32 = 3;

/// One picture of the gallery.
#[derive(Debug, Clone, PartialEq)]
pub struct GalleryPicture {
    /// The file written.
    pub path: PathBuf,
    /// The pair's id.
    pub pair: String,
    /// The panels from left to right: `ground truth`, then row names.
    pub panels: Vec<String>,
}

/// Segment ids renamed to the ground-truth part each matches; unmatched ones get ids from
/// the number of parts on.
fn match_colours(segments: &[u32], truth: &[u8]) -> Vec<u32> {
    let Ok(matching) = matched_iou(segments, truth) else {
        return segments.to_vec();
    };
    let parts = matching.segment.len() as u32;
    let mut extra = Vec::new();
    segments
        .iter()
        .map(|s| match matching.segment.iter().position(|m| *m == Some(*s)) {
            Some(part) => part as u32,
            None => {
                let k = extra.iter().position(|e| e == s).unwrap_or_else(|| {
                    extra.push(*s);
                    extra.len() - 1
                });
                parts + k as u32
            }
        })
        .collect()
}

/// Draws the picture of `pair` with one panel per `(row name, segments of P)`.
pub fn write_picture(
    dir: &Path,
    dataset: &str,
    pair: &Pair,
    rows: &[(String, Vec<u32>)],
) -> Result<GalleryPicture, EvalError> {
    let truth = &pair.truth().part_p;
    let points = &pair.input().p.points;
    let mut panels = vec![("ground truth".to_owned(), pairs::parts::part_segments(truth))];
    panels.extend(rows.iter().map(|(name, s)| (name.clone(), match_colours(s, truth))));
    let mut image = RgbImage::from_pixel(PANEL * panels.len() as u32, PANEL, Rgb([255; 3]));
    for (i, (_, labels)) in panels.iter().enumerate() {
        let panel = render_labelled(points, labels, SPLAT);
        imageops::replace(&mut image, &panel, i64::from(i as u32 * PANEL), 0);
    }
    let path = dir.join(dataset).join(format!("{}.png", pair.id()));
    let fail = |message: String| EvalError::Plot { path: path.clone(), message };
    std::fs::create_dir_all(dir.join(dataset)).map_err(|e| fail(e.to_string()))?;
    image.save(&path).map_err(|e| fail(e.to_string()))?;
    Ok(GalleryPicture {
        path,
        pair: pair.id().to_owned(),
        panels: panels.into_iter().map(|(name, _)| name).collect(),
    })
}

/// One picture per gallery pair and dataset, with a panel per segmentation row.
pub fn write_gallery(
    reports: &Path,
    gallery_pairs: usize,
    loaded: &[&LoadedDataset],
    scored: &[Scored],
) -> Result<Vec<GalleryPicture>, EvalError> {
    let dir = reports.join("gallery").join("segmentation");
    let mut pictures = Vec::new();
    for dataset in loaded {
        for pair in dataset.pairs.iter().take(gallery_pairs) {
            let rows: Vec<(String, Vec<u32>)> = scored
                .iter()
                .filter(|s| s.dataset == dataset.name && s.entry.board != Board::Flow)
                .filter_map(|s| {
                    let segments = s.result.meta.gallery.get(pair.id())?;
                    Some((s.entry.name.clone(), segments.clone()))
                })
                .collect();
            pictures.push(write_picture(&dir, &dataset.name, pair, &rows)?);
        }
    }
    Ok(pictures)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matched_segments_take_their_parts_colours() {
        // Segment 7 is part 1, segment 2 is part 0, segment 5 matches nothing.
        assert_eq!(match_colours(&[2, 2, 7, 7, 5], &[0, 0, 1, 1, 1]), vec![0, 0, 1, 1, 2]);
    }
}
