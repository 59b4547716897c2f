//! Per-pass scores of an iterative row (`net-iter`: every pass of the network's procedure),
//! made while the row runs and cached beside its runs file as `<row>.passes.csv`: one line
//! per pair and pass with the pass's EPE, Rand index, summed IoU and part count, and its
//! joint scores. The iteration board ([`crate::boards::iterations`], the paper's Table 4) is written
//! from them, so no pass is ever run twice. A pair whose prediction or any pass's scoring
//! failed has no lines (its failure is in the runs file).

use std::path::{Path, PathBuf};

use pairs::metrics::{score_pair, JointScores};
use pairs::{Pair, Prediction};
use serde::{Deserialize, Serialize};

use crate::error::EvalError;
use crate::running::record::read_csv;
use pairs::atomic::replace_file;

/// The scores of one pass on one pair.
#[derive(Debug, Clone, PartialEq)]
pub struct PassScore {
    /// End-point error of the pass's flow.
    pub epe: f64,
    /// Rand index of P's segments.
    pub rand_index: f64,
    /// Sum of the matched IoU over the pair's ground-truth parts.
    pub iou_sum: f64,
    /// Ground-truth parts of P.
    pub parts: usize,
    /// The joints estimated from the pass's segments and motions.
    pub joints: JointScores,
}

/// Every pass's scores on one pair, the first pass first.
#[derive(Debug, Clone, PartialEq)]
pub struct PairPasses {
    /// The pair's id.
    pub pair: String,
    /// One score per pass.
    pub passes: Vec<PassScore>,
}

/// Scores each of `passes` (predictions of one pair, the first pass first) against the
/// pair's ground truth with [`score_pair`], the score of every row.
pub fn score_passes(pair: &Pair, passes: &[Prediction]) -> Result<Vec<PassScore>, String> {
    passes
        .iter()
        .map(|p| {
            let score = score_pair(p, pair.input(), pair.truth()).map_err(|e| e.to_string())?;
            Ok(PassScore {
                // A cross-instance pair has no true flow: its EPE is not a number, and its
                // dataset gets no iteration table.
                epe: score.flow.as_ref().map_or(f64::NAN, |f| f.epe),
                rand_index: score.p.rand_index,
                iou_sum: score.p.iou_sum,
                parts: score.p.parts as usize,
                joints: JointScores::of(&score.joints),
            })
        })
        .collect()
}

/// The passes file beside the runs file `runs_file` (`net-iter.csv` → `net-iter.passes.csv`).
pub fn passes_path(runs_file: &Path) -> PathBuf {
    runs_file.with_extension("passes.csv")
}

/// One line of a passes file: one pass of one pair (serde; lists `;`-separated).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct PassRow {
    pair: String,
    /// 1 for the first pass.
    pass: usize,
    epe: f64,
    ri: f64,
    iou_sum: f64,
    parts: usize,
    joints: usize,
    type_correct: usize,
    #[serde(with = "semicolons")]
    axis_errors: Vec<f64>,
    #[serde(with = "semicolons")]
    pivot_distances: Vec<f64>,
}

/// The columns of a passes file, [`PassRow`]'s fields.
const HEADER: [&str; 10] = [
    "pair",
    "pass",
    "epe",
    "ri",
    "iou_sum",
    "parts",
    "joints",
    "type_correct",
    "axis_errors",
    "pivot_distances",
];

/// A list of numbers as one cell, `;`-separated, each round-trip exact.
mod semicolons {
    use serde::{de::Error, Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(values: &[f64], s: S) -> Result<S::Ok, S::Error> {
        let cells: Vec<String> = values.iter().map(|&v| crate::running::record::num(v)).collect();
        s.serialize_str(&cells.join(";"))
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<f64>, D::Error> {
        let cell = String::deserialize(d)?;
        if cell.is_empty() {
            return Ok(Vec::new());
        }
        cell.split(';')
            .map(|v| v.parse().map_err(|_| D::Error::custom(format!("{v:?} is not a number"))))
            .collect()
    }
}

/// Writes `pairs`' passes to `path`, replacing an old file only once the new one is complete.
pub fn write_passes(path: &Path, pairs: &[PairPasses]) -> Result<(), EvalError> {
    let bad = |e: csv::Error| EvalError::Csv { path: path.to_path_buf(), message: e.to_string() };
    replace_file(path, |out| {
        let mut writer = csv::Writer::from_writer(out);
        for p in pairs {
            for (k, s) in p.passes.iter().enumerate() {
                let row = PassRow {
                    pair: p.pair.clone(),
                    pass: k + 1,
                    epe: s.epe,
                    ri: s.rand_index,
                    iou_sum: s.iou_sum,
                    parts: s.parts,
                    joints: s.joints.joints,
                    type_correct: s.joints.type_correct,
                    axis_errors: s.joints.axis_errors.clone(),
                    pivot_distances: s.joints.pivot_distances.clone(),
                };
                writer.serialize(row).map_err(bad)?;
            }
        }
        if pairs.iter().all(|p| p.passes.is_empty()) {
            writer.write_record(HEADER).map_err(bad)?;
        }
        writer.flush().map_err(|source| EvalError::Io { path: path.to_path_buf(), source })
    })
}

/// Reads a passes file: every pair's passes in file order, each pair's numbered 1, 2, ...
pub fn read_passes(path: &Path) -> Result<Vec<PairPasses>, EvalError> {
    let header: Vec<String> = HEADER.iter().map(|h| h.to_string()).collect();
    let mut pairs: Vec<PairPasses> = Vec::new();
    for (line, row) in read_csv::<PassRow>(path, &header)? {
        let out_of_order = |pair: &str, pass| EvalError::Csv {
            path: path.to_path_buf(),
            message: format!("line {line}: pass {pass} of pair {pair} is out of order"),
        };
        let score = PassScore {
            epe: row.epe,
            rand_index: row.ri,
            iou_sum: row.iou_sum,
            parts: row.parts,
            joints: JointScores {
                joints: row.joints,
                type_correct: row.type_correct,
                axis_errors: row.axis_errors,
                pivot_distances: row.pivot_distances,
            },
        };
        let (pair, pass) = (row.pair, row.pass);
        match pairs.last_mut() {
            Some(last) if last.pair == pair && pass == last.passes.len() + 1 => {
                last.passes.push(score)
            }
            _ if pass == 1 => pairs.push(PairPasses { pair, passes: vec![score] }),
            _ => return Err(out_of_order(&pair, pass)),
        }
    }
    Ok(pairs)
}

#[cfg(test)]
mod tests {
    use super::*;
    use pairs::segments::complete_prediction;
    use pairs::synthetic::hinge_pair;

    #[test]
    fn the_true_answer_scores_perfectly_and_the_file_reads_back_exactly() {
        let pair = hinge_pair("h", 8, 0.7);
        let (input, truth) = (pair.input(), pair.truth());
        let right =
            complete_prediction(input, truth.flow.as_deref().expect("a flow"), &truth.part_p, true);
        let one_part = complete_prediction(
            input,
            truth.flow.as_deref().expect("a flow"),
            &vec![0u8; truth.part_p.len()],
            true,
        );
        let scores = score_passes(&pair, &[one_part, right]).expect("scored");
        assert_eq!(scores.len(), 2);
        assert_eq!((scores[1].epe, scores[1].rand_index), (0.0, 1.0));
        assert_eq!((scores[1].iou_sum, scores[1].parts), (2.0, 2));
        assert!(scores[0].rand_index < 1.0 && scores[0].iou_sum < 2.0);
        assert_eq!((scores[1].joints.joints, scores[1].joints.type_correct), (1, 1));
        let dir = tempfile::tempdir().expect("a temporary folder");
        let path = passes_path(&dir.path().join("net-iter.csv"));
        assert!(path.ends_with("net-iter.passes.csv"));
        let mut third = scores[0].clone();
        third.epe = 0.1 + 0.2; // not exactly representable in a short decimal
        let written = vec![
            PairPasses { pair: "a".into(), passes: scores.clone() },
            PairPasses { pair: "b".into(), passes: vec![third] },
        ];
        write_passes(&path, &written).expect("written");
        assert_eq!(read_passes(&path).expect("read"), written);
    }

    #[test]
    fn a_malformed_file_names_the_line() {
        let dir = tempfile::tempdir().expect("a temporary folder");
        let path = dir.path().join("x.passes.csv");
        let head = HEADER.join(",");
        std::fs::write(
            &path,
            format!("{head}\na,1,0.1,0.9,1.0,1,0,0,,\na,3,0.1,0.9,1.0,1,0,0,,\n"),
        )
        .expect("written");
        let err = read_passes(&path).expect_err("pass 3 after pass 1").to_string();
        assert!(err.contains("line 3") && err.contains("out of order"), "{err}");
        std::fs::write(&path, format!("{head}\na,1,x,0.9,1.0,1,0,0,,\n")).expect("written");
        let err = read_passes(&path).expect_err("not a number").to_string();
        assert!(err.contains("line 2") && err.contains("epe"), "{err}");
        std::fs::write(&path, "pair,pass\n").expect("written");
        assert!(read_passes(&path).is_err(), "another header");
    }
}
