//! `reports/LEADERBOARD.md`: the leaderboards as Markdown tables, the paper's numbers for the
//! same rows beside them (labelled as the paper's), links to the PCC plots and the
//! segmentation gallery, and the timings. Written from the same tables as the CSVs, with
//! nothing that changes between reruns except through the data.

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

use polars::prelude::{AnyValue, DataFrame};

use crate::error::EvalError;
use crate::files::replace_file;
use crate::gallery::GalleryPicture;
use crate::leaderboard::Leaderboards;
use crate::paper::{figures_for, FIGURES};
use crate::plots::colour_hex;

fn cell(value: AnyValue) -> String {
    match value {
        AnyValue::Null => "–".into(),
        AnyValue::Float64(v) => format!("{v:.4}"),
        AnyValue::String(s) => s.to_owned(),
        other => other.to_string(),
    }
}

/// The frame's rows as strings.
fn cells(frame: &DataFrame) -> Vec<Vec<String>> {
    (0..frame.height())
        .map(|row| {
            frame.columns().iter().map(|c| c.get(row).map_or_else(|_| "?".into(), cell)).collect()
        })
        .collect()
}

fn table(out: &mut String, header: &[String], rows: &[Vec<String>]) {
    let _ = writeln!(out, "| {} |", header.join(" | "));
    let _ = writeln!(out, "|{}", header.iter().map(|_| "---|").collect::<String>());
    for row in rows {
        let _ = writeln!(out, "| {} |", row.join(" | "));
    }
    out.push('\n');
}

fn header(frame: &DataFrame) -> Vec<String> {
    frame.get_column_names().iter().map(|s| s.to_string()).collect()
}

/// Our table with a last column holding the paper's figures for the same row.
fn with_paper(
    frame: &DataFrame,
    paper: impl Fn(&crate::paper::PaperFigure) -> Option<String>,
) -> (Vec<String>, Vec<Vec<String>>) {
    let mut head = header(frame);
    head.push("paper (same row)".into());
    let rows = cells(frame)
        .into_iter()
        .map(|mut row| {
            let quoted: Vec<String> = figures_for(&row[0], &row[1])
                .into_iter()
                .filter_map(|f| paper(f).map(|v| format!("{v} ({}, {})", f.paper_row, f.table)))
                .collect();
            row.push(if quoted.is_empty() { "–".into() } else { quoted.join("; ") });
            row
        })
        .collect();
    (head, rows)
}

/// Writes `LEADERBOARD.md` into `dir`.
pub fn write_report(
    dir: &Path,
    boards: &Leaderboards,
    gallery: &[GalleryPicture],
) -> Result<(), EvalError> {
    let mut out = String::from(
        "# Leaderboard\n\nMade by `cargo run --release -p evaluator -- --all`; the same tables \
         are in `leaderboard_flow.csv` and `leaderboard_seg.csv`, timings in `timings.csv`. \
         Metric definitions: [docs/METRICS.md](../docs/METRICS.md). Rand index is the \
         unweighted pair-counting index over P's points, higher is better. Rows named \
         `segmenter@source` run a segmenter on a flow source's flow: `gt-flow` is an oracle \
         row, `net-flow` is the paper's protocol. `gt` returns the ground truth and must score \
         perfectly. Failed pairs are left out of the means and counted in `failed`.\n\n\
         The last column quotes the **paper's** numbers (Yi et al. 2018) for the same row on \
         the paper's own data, for orientation only: our datasets are generated, not the \
         paper's.\n\n## Flow\n\n",
    );
    let (head, rows) = with_paper(&boards.flow, |f| f.epe.map(|v| format!("EPE {v:.4}")));
    table(&mut out, &head, &rows);
    out.push_str("## Segmentation\n\n");
    let (head, rows) = with_paper(&boards.seg, |f| {
        f.ri.zip(f.iou).map(|(ri, iou)| format!("RI {ri:.3} / IoU {iou:.3}"))
    });
    table(&mut out, &head, &rows);
    out.push_str("## PCC curves\n\n");
    let mut datasets: Vec<&str> = boards.curves.iter().map(|c| c.dataset.as_str()).collect();
    datasets.dedup();
    for dataset in datasets {
        let _ =
            writeln!(out, "![PCC on {dataset}](pcc_{dataset}.svg) ([PNG](pcc_{dataset}.png))\n");
        let legend: Vec<String> = boards
            .curves
            .iter()
            .filter(|c| c.dataset == dataset)
            .enumerate()
            .map(|(i, c)| format!("`{}` {}", colour_hex(i), c.method))
            .collect();
        let _ = writeln!(out, "Colours: {}.\n", legend.join(", "));
    }
    if !gallery.is_empty() {
        out.push_str(
            "## Segmentation gallery\n\nP coloured by ground-truth part and by each row's \
             segments (a segment takes the colour of the part it is matched to).\n\n",
        );
        for picture in gallery {
            let file = picture.path.strip_prefix(dir).unwrap_or(&picture.path);
            let _ = writeln!(
                out,
                "- `{}`, panels left to right: {}\n\n  ![{}]({})\n",
                picture.pair,
                picture.panels.join(", "),
                picture.pair,
                file.display()
            );
        }
    }
    out.push_str("## The paper's tables (Yi et al. 2018, quoted)\n\n");
    let head: Vec<String> =
        ["table", "dataset", "paper row", "our row", "EPE", "RI", "IoU"].map(String::from).into();
    let opt = |v: Option<f64>| v.map_or("–".into(), |v| format!("{v:.4}"));
    let rows: Vec<Vec<String>> = FIGURES
        .iter()
        .map(|f| {
            vec![
                f.table.into(),
                f.dataset.into(),
                f.paper_row.into(),
                format!("`{}`", f.row),
                opt(f.epe),
                opt(f.ri),
                opt(f.iou),
            ]
        })
        .collect();
    table(&mut out, &head, &rows);
    out.push_str("## Timings (this machine; not part of the reproducible tables)\n\n");
    table(&mut out, &header(&boards.timings), &cells(&boards.timings));
    let path = dir.join("LEADERBOARD.md");
    replace_file(&path, |file| {
        file.write_all(out.as_bytes())
            .map_err(|source| EvalError::Io { path: path.clone(), source })
    })
}
