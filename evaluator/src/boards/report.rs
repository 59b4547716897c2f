//! `reports/LEADERBOARD.md`: the leaderboards as Markdown tables, the paper's numbers for the
//! same rows beside them (labelled as the paper's), links to the PCC plots and the
//! segmentation gallery, and the timings. Written from the same tables as the CSVs, with
//! nothing that changes between reruns except through the data.

use std::fmt::Write as _;
use std::path::Path;

use polars::prelude::{AnyValue, DataFrame};

use crate::boards::gallery::GalleryPicture;
use crate::boards::leaderboard::Leaderboards;
use crate::boards::paper::{figures_for, Metric, PaperFigure, FIGURES};
use crate::boards::plots::colour_hex;
use crate::boards::sets::SetBoardRow;
use crate::error::EvalError;
use crate::rows::external::EXTERNAL;
use crate::tuning::Sweep;
use pairs::atomic::replace_bytes;

fn cell(value: AnyValue) -> String {
    match value {
        AnyValue::Null => "–".into(),
        AnyValue::Float64(v) => format!("{v:.4}"),
        AnyValue::String(s) => s.to_owned(),
        // A column whose rows are all equal can come back as one owned scalar.
        AnyValue::StringOwned(s) => s.to_string(),
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

/// The paper's figures of `metrics` for our `row` on `dataset`, one group per table
/// (`RI 0.838, IoU 0.773 (Table 2)`).
fn quoted(dataset: &str, row: &str, metrics: &[Metric]) -> String {
    let figures: Vec<&PaperFigure> =
        metrics.iter().flat_map(|&m| figures_for(dataset, row, m)).collect();
    let mut tables: Vec<u8> = figures.iter().map(|f| f.table).collect();
    tables.sort_unstable();
    tables.dedup();
    let groups: Vec<String> = tables
        .iter()
        .map(|&t| {
            let values: Vec<String> = figures
                .iter()
                .filter(|f| f.table == t)
                .map(|f| {
                    format!(
                        "{} {}",
                        f.metric.as_str().to_uppercase().replace("IOU", "IoU"),
                        number(f)
                    )
                })
                .collect();
            let real = figures.iter().any(|f| f.table == t && f.beside == Some(dataset));
            let on = if real { ", RF2P: real scans of other objects" } else { "" };
            format!("{} (Table {t}{on})", values.join(", "))
        })
        .collect();
    if groups.is_empty() {
        "–".into()
    } else {
        groups.join("; ")
    }
}

/// A figure as the paper prints it (EPE to four places, RI and IoU to three).
fn number(f: &PaperFigure) -> String {
    match f.metric {
        Metric::Epe => format!("{:.4}", f.value),
        _ => format!("{:.3}", f.value),
    }
}

/// Our table with a last column holding the paper's figures for the same row.
fn with_paper(frame: &DataFrame, metrics: &[Metric]) -> (Vec<String>, Vec<Vec<String>>) {
    let mut head = header(frame);
    head.push("paper (same row)".into());
    let rows = cells(frame)
        .into_iter()
        .map(|mut row| {
            let q = quoted(&row[0], &row[1], metrics);
            row.push(q);
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
    sweeps: &[Sweep],
    sets: &[SetBoardRow],
) -> Result<(), EvalError> {
    let mut out = String::from(
        "# Leaderboard\n\nMade by `cargo run --release -p evaluator -- --all`; the same tables \
         are in `leaderboard_flow.csv` and `leaderboard_seg.csv`, timings in `timings.csv`. \
         Metric definitions: [docs/METRICS.md](../docs/METRICS.md). Rand index is the \
         unweighted pair-counting index over P's points, higher is better. Rows named \
         `segmenter@source` run a segmenter on a flow source's flow: `gt-flow` is the true \
         flow (an oracle row, marked in the `oracle` column), `net-flow` the network's single \
         pass, `net-iter-flow` its iterative procedure's final flow (the protocol of the \
         paper's Table 2) and `ed-flow` embedded deformation's (an all-classical pipeline). \
         `gt` returns the ground truth and must score perfectly. Motion errors average over \
         the matched parts only; `matched_per_pair` says how many there are. Failed pairs are \
         left out of the means and counted in `failed`. Joints are in `joints.csv`, every \
         row per category and per joint type in `leaderboard_by_category.csv`.\n\n\
         `net-iter` runs the paper's inference procedure (model/README.md). The authors' \
         release adds three steps (a rigid alignment of each segment, per-segment \
         sub-problems under geodesic attention masks, and snapping the final SF2F flow to \
         Q); `model procedures` measured each with the shipped weights on 960 validation \
         pairs and each lowered the IoU (model/TRAINING.md), so the row leaves them out.\n\n\
         `xf2f` and `xf2p` are cross-instance sets: P and Q are two different objects of one \
         category (full to full, full to a scan), parts matched by their role; no flow is \
         defined between two shapes, so these sets are on the segmentation board only, \
         without the rows that need the true flow.\n\n\
         The last column quotes the **paper's** numbers (Yi et al. 2018) for the same row on \
         the paper's own data, for orientation only: our datasets are generated, not the \
         paper's. Beside `xf2p` it quotes the paper's RF2P (a CAD model to a real scan of \
         another object), measured on real scans.\n\n## Flow\n\n",
    );
    let external = [&boards.flow, &boards.seg].iter().any(|frame| {
        cells(frame).iter().any(|row| row.get(2).map(String::as_str) == Some(EXTERNAL))
    });
    if external {
        out.insert_str(
            out.len() - "## Flow\n\n".len(),
            "Rows whose `flow_source` is `external` were scored from prediction files that \
             another program wrote (`evaluator score`; docs/FORMAT.md, \"Prediction files\"), \
             by the same code as every other row; `external_rows.json` lists their files.\n\n",
        );
    }
    let (head, rows) = with_paper(&boards.flow, &[Metric::Epe]);
    table(&mut out, &head, &rows);
    out.push_str("## Segmentation\n\n");
    let (head, rows) = with_paper(&boards.seg, &[Metric::Ri, Metric::Iou]);
    table(&mut out, &head, &rows);
    if !sets.is_empty() {
        out.push_str(
            "## Sets\n\nK observations of one object (the MultiBodySync setting; \
             `leaderboard_sets.csv`). Every segmentation row runs on the pairs (view 0, view k) \
             of each set and its labels are carried to the set by one rule (docs/METRICS.md, \
             \"Sets\"): view 0 keeps the segments of the pair (0, 1), view k takes the view-0 \
             label its segment overlaps most. Multi-scan mIoU matches parts to segments once for \
             all K views, so a label must name the same part in every view; per-scan mIoU \
             matches each view on its own. Means over sets; failed sets are left out and \
             counted. Rotation and translation errors are those of each matched part's motion \
             from view 0 to every other view (the motion of the pair (0, k)'s segment that \
             overlaps the label most), averaged over all of them; empty for a row without \
             motions.\n\n",
        );
        let head: Vec<String> = [
            "dataset",
            "row",
            "oracle",
            "K",
            "multi-scan mIoU",
            "per-scan mIoU",
            "multi-scan RI",
            "per-scan RI",
            "rotation° ↓",
            "translation ↓",
            "sets",
            "failed",
        ]
        .map(String::from)
        .into();
        let cell = |v: f64| if v.is_finite() { format!("{v:.4}") } else { "–".into() };
        let rows: Vec<Vec<String>> = sets
            .iter()
            .map(|r| {
                vec![
                    r.dataset.clone(),
                    format!("`{}`", r.row),
                    r.oracle.to_string(),
                    r.views.to_string(),
                    cell(r.multi_scan_miou),
                    cell(r.per_scan_miou),
                    cell(r.multi_scan_ri),
                    cell(r.per_scan_ri),
                    cell(r.rotation_deg),
                    cell(r.translation),
                    r.sets.to_string(),
                    r.failed.to_string(),
                ]
            })
            .collect();
        table(&mut out, &head, &rows);
    }
    if let Some(section) = super::render_joints::section(dir) {
        out.push_str(&section);
    }
    if !sweeps.is_empty() {
        out.push_str(
            "## Tuned parameters\n\nEach baseline's parameters were chosen for each flow source \
             on the validation sets (`val-sf2f`, `val-sf2p`, `val-sp2p`: validation categories \
             only, never a test pair), on the flow the row is scored on, by IoU with the Rand \
             index as tie-break; one setting per row serves all test sets. The whole sweep of \
             each row is in `tuning/<row>.csv`.\n\n",
        );
        let head: Vec<String> =
            ["row", "chosen", "validation IoU", "validation RI", "candidates", "pairs"]
                .map(String::from)
                .into();
        let rows: Vec<Vec<String>> = sweeps
            .iter()
            .map(|s| {
                let c = &s.candidates[s.chosen];
                vec![
                    format!("`{}`", s.row),
                    s.chosen_label(),
                    format!("{:.4}", c.iou),
                    format!("{:.4}", c.ri),
                    s.candidates.len().to_string(),
                    s.pairs.to_string(),
                ]
            })
            .collect();
        table(&mut out, &head, &rows);
    }
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
    out.push_str(
        "## The paper's tables (Yi et al. 2018, quoted)\n\nEvery number of the paper's Tables 1, \
         2, 4 and 5, with the row of ours that follows the same protocol where there is one: \
         the paper's \"Ours\" in Tables 1, 2 and 5 is its full iterative pipeline (`net-iter`), \
         Table 4's first column its single pass (`net`); its segmentation baselines ran on its \
         network's final flow (`@net-iter-flow`); its RF2P row (\"RF2S\") faces our `xf2p` \
         rows. RI and IoU as fractions (Table 2 prints percent).\n\n",
    );
    let head: Vec<String> =
        ["table", "dataset", "paper row", "metric", "value", "our row"].map(String::from).into();
    let rows: Vec<Vec<String>> = FIGURES
        .iter()
        .map(|f| {
            vec![
                format!("Table {}", f.table),
                f.dataset.into(),
                f.paper_row.into(),
                f.metric.as_str().into(),
                number(f),
                f.row.map_or("–".into(), |r| format!("`{r}`")),
            ]
        })
        .collect();
    table(&mut out, &head, &rows);
    out.push_str("## Timings (this machine; not part of the reproducible tables)\n\n");
    table(&mut out, &header(&boards.timings), &cells(&boards.timings));
    let path = dir.join("LEADERBOARD.md");
    Ok(replace_bytes(&path, out.as_bytes())?)
}
