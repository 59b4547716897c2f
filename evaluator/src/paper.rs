//! The paper's published numbers (Yi et al. 2018, Tables 1, 2 and 5), keyed to our rows so
//! `LEADERBOARD.md` can print them beside ours, always labelled as the paper's.

/// A number of the paper for one of our rows on one dataset.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PaperFigure {
    /// Our dataset name.
    pub dataset: &'static str,
    /// Our row name.
    pub row: &'static str,
    /// The paper's name for the row.
    pub paper_row: &'static str,
    /// Which table.
    pub table: &'static str,
    /// EPE, when the table gives one.
    pub epe: Option<f64>,
    /// Rand index (0 to 1), when given.
    pub ri: Option<f64>,
    /// IoU (0 to 1), when given.
    pub iou: Option<f64>,
}

const fn flow(
    dataset: &'static str,
    row: &'static str,
    paper_row: &'static str,
    epe: f64,
) -> PaperFigure {
    PaperFigure { dataset, row, paper_row, table: "Table 1", epe: Some(epe), ri: None, iou: None }
}

const fn seg(
    dataset: &'static str,
    row: &'static str,
    paper_row: &'static str,
    ri: f64,
    iou: f64,
) -> PaperFigure {
    PaperFigure {
        dataset,
        row,
        paper_row,
        table: "Table 2",
        epe: None,
        ri: Some(ri),
        iou: Some(iou),
    }
}

/// Our single forward pass is the paper's "1 iter" column of Table 5.
const fn one_iteration(dataset: &'static str, epe: f64, ri: f64, iou: f64) -> PaperFigure {
    PaperFigure {
        dataset,
        row: "net",
        paper_row: "Ours, 1 iteration",
        table: "Table 5",
        epe: Some(epe),
        ri: Some(ri),
        iou: Some(iou),
    }
}

/// Every figure we compare with. The paper's segmentation baselines ran on its network's
/// flow, so they face our `@net-flow` rows; FPFH stands in for its 3DMatch row.
pub const FIGURES: [PaperFigure; 18] = [
    flow("sf2f", "ed", "ED", 0.0481),
    flow("sf2f", "nrr", "NRR", 0.0394),
    flow("sf2f", "fpfh", "3DMatch (FPFH stands in)", 0.0715),
    flow("sf2p", "ed", "ED", 0.0805),
    flow("sf2p", "nrr", "NRR", 0.0556),
    flow("sf2p", "fpfh", "3DMatch (FPFH stands in)", 0.138),
    seg("sf2f", "seqransac@net-flow", "SeqRANSAC", 0.602, 0.558),
    seg("sf2f", "sc@net-flow", "SC", 0.806, 0.694),
    seg("sf2f", "jlc@net-flow", "JLC", 0.747, 0.673),
    seg("sf2f", "nrr", "NRR", 0.741, 0.573),
    seg("sf2p", "seqransac@net-flow", "SeqRANSAC", 0.482, 0.376),
    seg("sf2p", "sc@net-flow", "SC", 0.670, 0.556),
    seg("sf2p", "jlc@net-flow", "JLC", 0.662, 0.582),
    seg("sf2p", "nrr", "NRR", 0.727, 0.539),
    one_iteration("sf2f", 0.0377, 0.741, 0.631),
    one_iteration("sf2p", 0.0522, 0.701, 0.577),
    PaperFigure {
        dataset: "sf2f",
        row: "net",
        paper_row: "Ours, 9 iterations (full pipeline, issue 8)",
        table: "Tables 1, 2, 5",
        epe: Some(0.0210),
        ri: Some(0.838),
        iou: Some(0.773),
    },
    PaperFigure {
        dataset: "sf2p",
        row: "net",
        paper_row: "Ours, 9 iterations (full pipeline, issue 8)",
        table: "Tables 1, 2, 5",
        epe: Some(0.0422),
        ri: Some(0.756),
        iou: Some(0.666),
    },
];

/// The paper's figures for `row` on `dataset`.
pub fn figures_for(dataset: &str, row: &str) -> Vec<&'static PaperFigure> {
    FIGURES.iter().filter(|f| f.dataset == dataset && f.row == row).collect()
}
