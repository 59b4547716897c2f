//! The paper's published numbers (Yi et al. 2018, `deep-part-induction-yi2018.tex`), one
//! entry per (table, dataset, paper row, metric), each with the counterpart row of ours
//! where there is one, so `LEADERBOARD.md` prints them beside our rows, always labelled as
//! the paper's. Every value also names the cell of the paper's LaTeX table it comes from
//! ([`TexCell`]); a test reads the paper's text and checks each one.
//!
//! The counterparts follow the paper's protocol: its Table 1 and 2 "Ours" and its Table 5
//! are the full iterative pipeline (`net-iter`); its Table 4 "1 iter" column is our single
//! pass (`net`) and its "9iter" column `net-iter`; its segmentation baselines (Table 2) ran on
//! its network's final flow, so they face our `@net-iter-flow` rows; FPFH matching stands in
//! for its learned-descriptor (3DMatch) row. Its RF2P set (Table 2's "RF2S": a CAD model
//! to a real scan of another object) is quoted beside our synthetic XF2P rows, marked as
//! measured on real scans. Rows with no counterpart (3DFlow, LMVCNN, Shao et al., the RS2S
//! real scans, the 2- and 5-iteration columns) are quoted without one.

/// The metric of a figure.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Metric {
    /// End-point error.
    Epe,
    /// Rand index (0 to 1).
    Ri,
    /// Per-part IoU (0 to 1).
    Iou,
}

impl Metric {
    /// The column name of our boards (`epe`, `ri`, `iou`).
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Epe => "epe",
            Self::Ri => "ri",
            Self::Iou => "iou",
        }
    }
}

/// Where a figure sits in the paper's LaTeX source.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TexCell {
    /// The table's `\label`.
    pub label: &'static str,
    /// The row's leading cells, joined by a space (a `\multirow` label carries down).
    pub row: &'static str,
    /// The column's header cell.
    pub column: &'static str,
    /// For `RI/IoU` cells, which of the two (0 or 1).
    pub part: Option<usize>,
    /// Whether the cell is in percent (Table 2).
    pub percent: bool,
}

/// One number of the paper.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PaperFigure {
    /// The paper's table number (1, 2, 4 or 5).
    pub table: u8,
    /// The dataset, by our name where we have it (`sf2f`, `sf2p`, `sp2p`), else the paper's.
    pub dataset: &'static str,
    /// Our dataset whose rows the figure is quoted beside when the paper's set is not one of
    /// ours: the paper's RF2P (a CAD model to a real scan of another object; "RF2S" in its
    /// Table 2) beside our synthetic XF2P, marked as measured on real scans.
    pub beside: Option<&'static str>,
    /// The paper's name for the row (and column, for Table 4).
    pub paper_row: &'static str,
    /// Our counterpart row, if any.
    pub row: Option<&'static str>,
    /// The metric.
    pub metric: Metric,
    /// The value (RI and IoU as fractions).
    pub value: f64,
    /// Its cell in the paper's source.
    pub tex: TexCell,
}

const T1: &str = "tab:flow_eva_baseline";
const T2: &str = "tab:seg_eva_ri_iou";
const T4: &str = "tab:iterative_refine";
const T5: &str = "tab:learning_comp";

/// Table 1: EPE of `column` on `tex_row` (`SF2F`, `SF2P`).
const fn t1(
    dataset: &'static str,
    tex_row: &'static str,
    column: &'static str,
    paper_row: &'static str,
    row: Option<&'static str>,
    value: f64,
) -> PaperFigure {
    PaperFigure {
        table: 1,
        dataset,
        beside: None,
        paper_row,
        row,
        metric: Metric::Epe,
        value,
        tex: TexCell { label: T1, row: tex_row, column, part: None, percent: false },
    }
}

/// Table 2: one half of an `RI/IoU` cell (in percent in the paper).
const fn t2(
    dataset: &'static str,
    tex_row: &'static str,
    column: &'static str,
    row: Option<&'static str>,
    metric: Metric,
    value: f64,
) -> PaperFigure {
    let part = match metric {
        Metric::Iou => 1,
        _ => 0,
    };
    PaperFigure {
        table: 2,
        dataset,
        beside: None,
        paper_row: column,
        row,
        metric,
        value,
        tex: TexCell { label: T2, row: tex_row, column, part: Some(part), percent: true },
    }
}

/// Table 2's RF2P row ("RF2S"): a half of an `RI/IoU` cell, quoted beside our XF2P row
/// `row` (the same protocol on synthetic cross-instance pairs).
const fn t2_rf2p(
    column: &'static str,
    row: &'static str,
    metric: Metric,
    value: f64,
) -> PaperFigure {
    PaperFigure {
        beside: Some("xf2p"),
        ..t2("rf2s (real scans)", "RF2S", column, Some(row), metric, value)
    }
}

/// Table 4: `metric` after `column` iterations.
const fn t4(
    dataset: &'static str,
    tex_row: &'static str,
    column: &'static str,
    paper_row: &'static str,
    row: Option<&'static str>,
    metric: Metric,
    value: f64,
) -> PaperFigure {
    PaperFigure {
        table: 4,
        dataset,
        beside: None,
        paper_row,
        row,
        metric,
        value,
        tex: TexCell { label: T4, row: tex_row, column, part: None, percent: false },
    }
}

/// Table 5 (SP2P, against Shao et al. 2018).
const fn t5(
    tex_row: &'static str,
    column: &'static str,
    paper_row: &'static str,
    row: Option<&'static str>,
    metric: Metric,
    value: f64,
) -> PaperFigure {
    PaperFigure {
        table: 5,
        dataset: "sp2p",
        beside: None,
        paper_row,
        row,
        metric,
        value,
        tex: TexCell { label: T5, row: tex_row, column, part: None, percent: false },
    }
}

use Metric::{Epe, Iou, Ri};

const NET_ITER: Option<&str> = Some("net-iter");
const NET: Option<&str> = Some("net");

/// Every figure of the paper's Tables 1, 2, 4 and 5.
pub const FIGURES: &[PaperFigure] = &[
    // Table 1: EPE.
    t1("sf2f", "SF2F", "Ours", "Ours (full pipeline)", NET_ITER, 0.0210),
    t1("sf2f", "SF2F", "3DFlow", "3DFlow", None, 0.0536),
    t1("sf2f", "SF2F", "ED", "ED", Some("ed"), 0.0481),
    t1("sf2f", "SF2F", "NRR", "NRR", Some("nrr"), 0.0394),
    t1("sf2f", "SF2F", "3DMatch", "3DMatch (FPFH stands in)", Some("fpfh"), 0.0715),
    t1("sf2f", "SF2F", "LMVCNN", "LMVCNN", None, 0.0582),
    t1("sf2p", "SF2P", "Ours", "Ours (full pipeline)", NET_ITER, 0.0422),
    t1("sf2p", "SF2P", "3DFlow", "3DFlow", None, 0.0892),
    t1("sf2p", "SF2P", "ED", "ED", Some("ed"), 0.0805),
    t1("sf2p", "SF2P", "NRR", "NRR", Some("nrr"), 0.0556),
    t1("sf2p", "SF2P", "3DMatch", "3DMatch (FPFH stands in)", Some("fpfh"), 0.138),
    t1("sf2p", "SF2P", "LMVCNN", "LMVCNN", None, 0.093),
    // Table 2: RI / IoU; the baselines segment the network's final flow.
    t2("sf2f", "SF2F", "SeqRANSAC", Some("seqransac@net-iter-flow"), Ri, 0.602),
    t2("sf2f", "SF2F", "SeqRANSAC", Some("seqransac@net-iter-flow"), Iou, 0.558),
    t2("sf2f", "SF2F", "SC", Some("sc@net-iter-flow"), Ri, 0.806),
    t2("sf2f", "SF2F", "SC", Some("sc@net-iter-flow"), Iou, 0.694),
    t2("sf2f", "SF2F", "JLC", Some("jlc@net-iter-flow"), Ri, 0.747),
    t2("sf2f", "SF2F", "JLC", Some("jlc@net-iter-flow"), Iou, 0.673),
    t2("sf2f", "SF2F", "NRR", Some("nrr"), Ri, 0.741),
    t2("sf2f", "SF2F", "NRR", Some("nrr"), Iou, 0.573),
    t2("sf2f", "SF2F", "Ours", NET_ITER, Ri, 0.838),
    t2("sf2f", "SF2F", "Ours", NET_ITER, Iou, 0.773),
    t2("sf2p", "SF2P", "SeqRANSAC", Some("seqransac@net-iter-flow"), Ri, 0.482),
    t2("sf2p", "SF2P", "SeqRANSAC", Some("seqransac@net-iter-flow"), Iou, 0.376),
    t2("sf2p", "SF2P", "SC", Some("sc@net-iter-flow"), Ri, 0.670),
    t2("sf2p", "SF2P", "SC", Some("sc@net-iter-flow"), Iou, 0.556),
    t2("sf2p", "SF2P", "JLC", Some("jlc@net-iter-flow"), Ri, 0.662),
    t2("sf2p", "SF2P", "JLC", Some("jlc@net-iter-flow"), Iou, 0.582),
    t2("sf2p", "SF2P", "NRR", Some("nrr"), Ri, 0.727),
    t2("sf2p", "SF2P", "NRR", Some("nrr"), Iou, 0.539),
    t2("sf2p", "SF2P", "Ours", NET_ITER, Ri, 0.756),
    t2("sf2p", "SF2P", "Ours", NET_ITER, Iou, 0.666),
    t2("rs2s (real scans)", "RS2S", "SeqRANSAC", None, Ri, 0.567),
    t2("rs2s (real scans)", "RS2S", "SeqRANSAC", None, Iou, 0.430),
    t2("rs2s (real scans)", "RS2S", "SC", None, Ri, 0.791),
    t2("rs2s (real scans)", "RS2S", "SC", None, Iou, 0.671),
    t2("rs2s (real scans)", "RS2S", "JLC", None, Ri, 0.804),
    t2("rs2s (real scans)", "RS2S", "JLC", None, Iou, 0.730),
    t2("rs2s (real scans)", "RS2S", "NRR", None, Ri, 0.784),
    t2("rs2s (real scans)", "RS2S", "NRR", None, Iou, 0.655),
    t2("rs2s (real scans)", "RS2S", "Ours", None, Ri, 0.883),
    t2("rs2s (real scans)", "RS2S", "Ours", None, Iou, 0.835),
    t2_rf2p("SeqRANSAC", "seqransac@net-iter-flow", Ri, 0.587),
    t2_rf2p("SeqRANSAC", "seqransac@net-iter-flow", Iou, 0.442),
    t2_rf2p("SC", "sc@net-iter-flow", Ri, 0.719),
    t2_rf2p("SC", "sc@net-iter-flow", Iou, 0.536),
    t2_rf2p("JLC", "jlc@net-iter-flow", Ri, 0.727),
    t2_rf2p("JLC", "jlc@net-iter-flow", Iou, 0.584),
    t2_rf2p("NRR", "nrr", Ri, 0.728),
    t2_rf2p("NRR", "nrr", Iou, 0.547),
    t2_rf2p("Ours", "net-iter", Ri, 0.876),
    t2_rf2p("Ours", "net-iter", Iou, 0.818),
    // Table 4: iterations of the full procedure.
    t4("sf2f", "SF2F EPE (Corrs)", "1 iter", "Ours, 1 iteration", NET, Epe, 0.0377),
    t4("sf2f", "SF2F EPE (Corrs)", "2iter", "Ours, 2 iterations", None, Epe, 0.0283),
    t4("sf2f", "SF2F EPE (Corrs)", "5iter", "Ours, 5 iterations", None, Epe, 0.0222),
    t4("sf2f", "SF2F EPE (Corrs)", "9iter", "Ours, 9 iterations", NET_ITER, Epe, 0.0210),
    t4("sf2f", "SF2F RI (Seg)", "1 iter", "Ours, 1 iteration", NET, Ri, 0.741),
    t4("sf2f", "SF2F RI (Seg)", "2iter", "Ours, 2 iterations", None, Ri, 0.783),
    t4("sf2f", "SF2F RI (Seg)", "5iter", "Ours, 5 iterations", None, Ri, 0.809),
    t4("sf2f", "SF2F RI (Seg)", "9iter", "Ours, 9 iterations", NET_ITER, Ri, 0.838),
    t4("sf2f", "SF2F IoU (Seg)", "1 iter", "Ours, 1 iteration", NET, Iou, 0.631),
    t4("sf2f", "SF2F IoU (Seg)", "2iter", "Ours, 2 iterations", None, Iou, 0.697),
    t4("sf2f", "SF2F IoU (Seg)", "5iter", "Ours, 5 iterations", None, Iou, 0.737),
    t4("sf2f", "SF2F IoU (Seg)", "9iter", "Ours, 9 iterations", NET_ITER, Iou, 0.773),
    t4("sf2p", "SF2P EPE (Corrs)", "1 iter", "Ours, 1 iteration", NET, Epe, 0.0522),
    t4("sf2p", "SF2P EPE (Corrs)", "2iter", "Ours, 2 iterations", None, Epe, 0.0464),
    t4("sf2p", "SF2P EPE (Corrs)", "5iter", "Ours, 5 iterations", None, Epe, 0.0429),
    t4("sf2p", "SF2P EPE (Corrs)", "9iter", "Ours, 9 iterations", NET_ITER, Epe, 0.0422),
    t4("sf2p", "SF2P RI (Seg)", "1 iter", "Ours, 1 iteration", NET, Ri, 0.701),
    t4("sf2p", "SF2P RI (Seg)", "2iter", "Ours, 2 iterations", None, Ri, 0.73),
    t4("sf2p", "SF2P RI (Seg)", "5iter", "Ours, 5 iterations", None, Ri, 0.746),
    t4("sf2p", "SF2P RI (Seg)", "9iter", "Ours, 9 iterations", NET_ITER, Ri, 0.756),
    t4("sf2p", "SF2P IoU (Seg)", "1 iter", "Ours, 1 iteration", NET, Iou, 0.577),
    t4("sf2p", "SF2P IoU (Seg)", "2iter", "Ours, 2 iterations", None, Iou, 0.623),
    t4("sf2p", "SF2P IoU (Seg)", "5iter", "Ours, 5 iterations", None, Iou, 0.653),
    t4("sf2p", "SF2P IoU (Seg)", "9iter", "Ours, 9 iterations", NET_ITER, Iou, 0.666),
    // Table 5: SP2P against Shao et al. 2018.
    t5("\\cite{shao2018motion}", "EPE (Corrs)", "Shao et al. 2018", None, Epe, 0.0862),
    t5("\\cite{shao2018motion}", "RI (Seg)", "Shao et al. 2018", None, Ri, 0.686),
    t5("\\cite{shao2018motion}", "IoU (Seg)", "Shao et al. 2018", None, Iou, 0.563),
    t5("Ours", "EPE (Corrs)", "Ours (full pipeline)", NET_ITER, Epe, 0.0369),
    t5("Ours", "RI (Seg)", "Ours (full pipeline)", NET_ITER, Ri, 0.833),
    t5("Ours", "IoU (Seg)", "Ours (full pipeline)", NET_ITER, Iou, 0.756),
];

/// The paper's figures of `metric` for our `row` on `dataset` (or quoted beside it), in
/// table order.
pub fn figures_for(dataset: &str, row: &str, metric: Metric) -> Vec<&'static PaperFigure> {
    FIGURES
        .iter()
        .filter(|f| f.dataset == dataset || f.beside == Some(dataset))
        .filter(|f| f.row == Some(row) && f.metric == metric)
        .collect()
}

/// The cells of the LaTeX `tabular` just before `\label{label}` in `tex`, by row, with
/// `\textbf`, `\multirow` and `\hline` taken off (a `\multirow` label carries down into the
/// empty first cells below it).
pub fn tex_table(tex: &str, label: &str) -> Option<Vec<Vec<String>>> {
    let at = tex.find(&format!("\\label{{{label}}}"))?;
    let begin = tex[..at].rfind("\\begin{tabular}")?;
    let body_start = begin + tex[begin..].find('\n')?;
    let end = body_start + tex[body_start..].find("\\end{tabular}")?;
    let body = tex[body_start..end].replace("\\hline", "");
    let mut rows = Vec::new();
    let mut carried = String::new();
    for line in body.split("\\\\") {
        let mut cells: Vec<String> = line.split('&').map(clean_cell).collect();
        if cells.iter().all(String::is_empty) {
            continue;
        }
        if line.contains("\\multirow") {
            carried = cells[0].clone();
        } else if cells[0].is_empty() && !rows.is_empty() && !carried.is_empty() {
            cells[0] = carried.clone();
        }
        rows.push(cells);
    }
    Some(rows)
}

/// A cell without `\textbf{..}` or `\multirow{..}{..}{..}` around its text.
fn clean_cell(cell: &str) -> String {
    let mut s = cell.trim().to_owned();
    if let Some(rest) = s.strip_prefix("\\multirow") {
        // The text is the last braced group.
        s = rest.rsplit_once('{').map_or(String::new(), |(_, t)| t.trim_end_matches('}').into());
    }
    while let Some(i) = s.find("\\textbf{") {
        let inner_start = i + "\\textbf{".len();
        let Some(close) = s[inner_start..].find('}') else { break };
        let inner = s[inner_start..inner_start + close].to_owned();
        s.replace_range(i..inner_start + close + 1, &inner);
    }
    s.trim().to_owned()
}

/// The value of `cell` in the paper's source (as a fraction for percent cells).
pub fn tex_value(tex: &str, cell: &TexCell) -> Result<f64, String> {
    let rows = tex_table(tex, cell.label).ok_or_else(|| format!("no table {}", cell.label))?;
    let header = &rows[0];
    let column = header
        .iter()
        .position(|h| h == cell.column)
        .ok_or_else(|| format!("{}: no column {:?} in {header:?}", cell.label, cell.column))?;
    let row = rows[1..]
        .iter()
        .find(|r| {
            let lead: Vec<&str> = r
                .iter()
                .take_while(|c| c.parse::<f64>().is_err() && !c.contains('/'))
                .map(String::as_str)
                .collect();
            lead.join(" ") == cell.row
        })
        .ok_or_else(|| format!("{}: no row {:?}", cell.label, cell.row))?;
    let text = row.get(column).ok_or_else(|| format!("{}: short row {row:?}", cell.label))?;
    let text = match cell.part {
        Some(i) => text.split('/').nth(i).ok_or_else(|| format!("{text:?} has no part {i}"))?,
        None => text.as_str(),
    };
    let value: f64 = text.trim().parse().map_err(|e| format!("{text:?}: {e}"))?;
    Ok(if cell.percent { value / 100.0 } else { value })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The paper's source: `$PAPER_TEX`, or `../shared/paper/` beside the project (where
    /// the developers' machines and CI have it). A clone without it skips the check, saying so.
    fn paper() -> Option<String> {
        let path =
            std::env::var_os("PAPER_TEX").map(std::path::PathBuf::from).unwrap_or_else(|| {
                std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                    .join("../../shared/paper/deep-part-induction-yi2018.tex")
            });
        match std::fs::read_to_string(&path) {
            Ok(text) => Some(text),
            Err(e) => {
                eprintln!("skipped: {} not readable ({e}); set PAPER_TEX to check", path.display());
                None
            }
        }
    }

    #[test]
    fn every_figure_is_the_papers() {
        let Some(tex) = paper() else { return };
        for figure in FIGURES {
            let value = tex_value(&tex, &figure.tex).unwrap_or_else(|e| panic!("{figure:?}: {e}"));
            assert!((value - figure.value).abs() < 1e-9, "{figure:?}: the paper says {value}");
        }
        // Each table is quoted whole: Table 1 has 12 EPEs, Table 2 four rows of five RI/IoU
        // pairs, Table 4 24 cells, Table 5 six.
        let count = |t: u8| FIGURES.iter().filter(|f| f.table == t).count();
        assert_eq!([count(1), count(2), count(4), count(5)], [12, 40, 24, 6]);
    }

    #[test]
    fn the_single_pass_and_the_full_pipeline_carry_their_own_numbers() {
        let net = figures_for("sf2f", "net", Metric::Iou);
        assert_eq!(net.len(), 1);
        assert_eq!((net[0].table, net[0].value), (4, 0.631));
        let full: Vec<(u8, f64)> = figures_for("sf2f", "net-iter", Metric::Iou)
            .iter()
            .map(|f| (f.table, f.value))
            .collect();
        assert_eq!(full, [(2, 0.773), (4, 0.773)]);
        let sp2p: Vec<(u8, f64)> = figures_for("sp2p", "net-iter", Metric::Epe)
            .iter()
            .map(|f| (f.table, f.value))
            .collect();
        assert_eq!(sp2p, [(5, 0.0369)]);
        assert!(figures_for("sf2f", "seqransac@net-flow", Metric::Ri).is_empty());
        // RF2P's real scans are quoted beside XF2P, and nowhere else.
        let rf2p = figures_for("xf2p", "net-iter", Metric::Iou);
        assert_eq!(rf2p.len(), 1);
        assert_eq!((rf2p[0].value, rf2p[0].tex.row), (0.818, "RF2S"));
        assert!(figures_for("xf2f", "net-iter", Metric::Iou).is_empty());
        assert_eq!(figures_for("xf2p", "nrr", Metric::Ri)[0].value, 0.728);
        assert_eq!(figures_for("sf2f", "seqransac@net-iter-flow", Metric::Ri)[0].value, 0.602);
    }

    #[test]
    fn tex_tables_parse_by_hand() {
        let tex = "\\begin{tabular}{|c|c|}\n\\hline\n & A & B \\\\ \\hline\n\\multirow{ 2}{*}{X} & m & \\textbf{0.5} & 1/2 \\\\\n & n & 3 & 4 \\\\\\hline\n\\end{tabular}\n\\label{t}";
        let rows = tex_table(tex, "t").expect("parses");
        assert_eq!(rows[1], ["X", "m", "0.5", "1/2"]);
        assert_eq!(rows[2], ["X", "n", "3", "4"]);
    }
}
