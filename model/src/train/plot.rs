//! The loss-curve PNG of a training run. Left: the training loss (log scale, smoothed over
//! 50 steps) against training pairs, coloured by stage (1 blue, 2 orange, 3 green). Right:
//! validation EPE (purple), 1 - IoU (red) and 1 - support IoU (orange, where the log has
//! it) against training pairs, linear scale from 0.
//! Drawn without text, so no font is needed; the CSVs beside it hold the numbers.

use std::path::Path;

use plotters::prelude::*;

/// The series of a run.
#[derive(Debug, Clone, Default)]
pub struct Curves {
    /// (pairs, stage, loss) per step.
    pub loss: Vec<(f64, u8, f64)>,
    /// (pairs, EPE, IoU, support IoU) per validation; the support IoU is NaN in rows
    /// written before it was logged.
    pub validation: Vec<(f64, f64, f64, f64)>,
}

const STAGE_COLOURS: [RGBColor; 3] =
    [RGBColor(31, 119, 180), RGBColor(255, 127, 14), RGBColor(44, 160, 44)];
const SMOOTHING: usize = 50;

/// Draws `curves` into the PNG at `path`.
pub fn draw_loss_curves(curves: &Curves, path: &Path) -> Result<(), String> {
    let root = BitMapBackend::new(path, (1000, 420)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let (left, right) = root.split_horizontally(500);
    let max_pairs = curves.loss.last().map_or(1.0, |l| l.0.max(1.0));
    let smoothed: Vec<(f64, u8, f64)> = curves
        .loss
        .iter()
        .enumerate()
        .map(|(i, &(x, stage, _))| {
            let window = &curves.loss[i.saturating_sub(SMOOTHING - 1)..=i];
            let same: Vec<f64> =
                window.iter().filter(|w| w.1 == stage).map(|w| w.2.max(1e-6)).collect();
            (x, stage, same.iter().sum::<f64>() / same.len() as f64)
        })
        .collect();
    let (lo, hi) = smoothed
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| (lo.min(p.2), hi.max(p.2)));
    let (lo, hi) = if lo.is_finite() { (lo * 0.9, hi * 1.1) } else { (1e-3, 1.0) };
    let mut chart = ChartBuilder::on(&left)
        .margin(20)
        .build_cartesian_2d(0.0..max_pairs, (lo..hi).log_scale())
        .map_err(|e| e.to_string())?;
    chart.configure_mesh().x_labels(0).y_labels(0).draw().map_err(|e| e.to_string())?;
    for stage in 1..=3u8 {
        let points = smoothed.iter().filter(|p| p.1 == stage).map(|p| (p.0, p.2));
        chart
            .draw_series(LineSeries::new(points, &STAGE_COLOURS[usize::from(stage) - 1]))
            .map_err(|e| e.to_string())?;
    }
    let top = curves.validation.iter().map(|v| v.1.max(1.0 - v.2)).fold(0.1, f64::max) * 1.1;
    let mut chart = ChartBuilder::on(&right)
        .margin(20)
        .build_cartesian_2d(0.0..max_pairs, 0.0..top)
        .map_err(|e| e.to_string())?;
    chart.configure_mesh().x_labels(0).y_labels(0).draw().map_err(|e| e.to_string())?;
    let epe = curves.validation.iter().map(|v| (v.0, v.1));
    chart.draw_series(LineSeries::new(epe, &RGBColor(148, 103, 189))).map_err(|e| e.to_string())?;
    let miss = curves.validation.iter().map(|v| (v.0, 1.0 - v.2));
    chart.draw_series(LineSeries::new(miss, &RGBColor(214, 39, 40))).map_err(|e| e.to_string())?;
    let support = curves.validation.iter().filter(|v| v.3.is_finite()).map(|v| (v.0, 1.0 - v.3));
    chart
        .draw_series(LineSeries::new(support, &RGBColor(255, 127, 14)))
        .map_err(|e| e.to_string())?;
    root.present().map_err(|e| e.to_string())
}
