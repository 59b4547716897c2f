//! PCC curves per dataset, one line per row of the flow leaderboard: an SVG with axes,
//! labels and a legend, and a PNG of the same chart without text (plotters draws PNG text
//! only with a font stack, which this project leaves out; the SVG and `LEADERBOARD.md`
//! name the colours).

use std::path::{Path, PathBuf};

use pairs::metrics::PCC_STEP;
use plotters::coord::Shift;
use plotters::prelude::*;

use crate::boards::leaderboard::PccCurve;
use crate::error::EvalError;

/// Line colours in row order (the tab10 palette), repeated past ten rows.
pub const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// The colour of the `i`-th line, as `#rrggbb`.
pub fn colour_hex(i: usize) -> String {
    let RGBColor(r, g, b) = PALETTE[i % PALETTE.len()];
    format!("#{r:02x}{g:02x}{b:02x}")
}

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    dataset: &str,
    curves: &[&PccCurve],
    text: bool,
) -> Result<(), String> {
    let fail = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(fail)?;
    let mut builder = ChartBuilder::on(&root);
    builder.margin(20);
    if text {
        builder
            .caption(format!("PCC on {dataset}"), ("sans-serif", 22))
            .x_label_area_size(40)
            .y_label_area_size(50);
    }
    let mut chart = builder.build_cartesian_2d(0.0..0.25, 0.0..1.0).map_err(fail)?;
    let mut mesh = chart.configure_mesh();
    if text {
        mesh.x_desc("flow error threshold (normalised units)").y_desc("fraction of points");
    } else {
        mesh.x_labels(0).y_labels(0);
    }
    mesh.draw().map_err(fail)?;
    for (i, curve) in curves.iter().enumerate() {
        let colour = PALETTE[i % PALETTE.len()];
        let points = curve.values.iter().enumerate().map(|(k, &v)| (k as f64 * PCC_STEP, v));
        let series =
            chart.draw_series(LineSeries::new(points, colour.stroke_width(2))).map_err(fail)?;
        if text {
            series.label(curve.method.clone()).legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
            });
        }
    }
    if text {
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerRight)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .draw()
            .map_err(fail)?;
    }
    root.present().map_err(fail)
}

/// Writes `pcc_<dataset>.svg` and `.png` into `dir` for every dataset in `curves`; returns
/// the files written.
pub fn write_pcc_plots(dir: &Path, curves: &[PccCurve]) -> Result<Vec<PathBuf>, EvalError> {
    let mut datasets: Vec<&str> = curves.iter().map(|c| c.dataset.as_str()).collect();
    datasets.dedup();
    let mut written = Vec::new();
    for dataset in datasets {
        let lines: Vec<&PccCurve> = curves.iter().filter(|c| c.dataset == dataset).collect();
        let svg = dir.join(format!("pcc_{dataset}.svg"));
        let png = dir.join(format!("pcc_{dataset}.png"));
        let plot_err = |path: &Path| {
            let path = path.to_path_buf();
            move |message| EvalError::Plot { path, message }
        };
        draw(SVGBackend::new(&svg, (800, 560)).into_drawing_area(), dataset, &lines, true)
            .map_err(plot_err(&svg))?;
        draw(BitMapBackend::new(&png, (800, 560)).into_drawing_area(), dataset, &lines, false)
            .map_err(plot_err(&png))?;
        written.extend([svg, png]);
    }
    Ok(written)
}
