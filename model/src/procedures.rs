//! The iterative procedure's variants side by side (`model procedures`): the paper's
//! (`net-iter` as the board runs it) and the authors' release's three changes to it, each
//! alone and all together ([`InferenceParams::global_alignments`],
//! [`InferenceParams::sub_problems`], [`InferenceParams::full_matching`]), scored on the same
//! pairs, with each variant's paired-bootstrap difference from the paper's.

use std::time::Instant;

use pairs::{Pair, PairKind};
use rayon::prelude::*;

use crate::inference::method::NetworkMethod;
use crate::inference::InferenceParams;
use crate::network::PartInductionNet;
use crate::train::validation::{compare, Comparison, PairScores, ScoreError, Scores};

/// One named inference procedure.
#[derive(Debug, Clone, PartialEq)]
pub struct Variant {
    /// Short name (`paper`, `+align`, `+sub`, `+full`, `release`).
    pub name: &'static str,
    /// Its parameters.
    pub params: InferenceParams,
}

/// The paper's procedure, then the release's global alignments (2), per-segment
/// sub-problems and full-Q matching each alone, then all three (the release's procedure,
/// with our hard labels).
pub fn release_variants() -> Vec<Variant> {
    let paper = InferenceParams::iterative();
    vec![
        Variant { name: "paper", params: paper },
        Variant { name: "+align", params: InferenceParams { global_alignments: 2, ..paper } },
        Variant { name: "+sub", params: InferenceParams { sub_problems: true, ..paper } },
        Variant { name: "+full", params: InferenceParams { full_matching: true, ..paper } },
        Variant {
            name: "release",
            params: InferenceParams {
                global_alignments: 2,
                sub_problems: true,
                full_matching: true,
                ..paper
            },
        },
    ]
}

/// One variant's scores on every pair (in order), its mean passes and its seconds.
#[derive(Debug, Clone)]
pub struct VariantScores {
    /// The variant's name.
    pub name: &'static str,
    /// Per pair, in the pairs' order; the support IoU is not scored (NaN).
    pub pairs: Vec<PairScores>,
    /// Passes the procedure made on each pair.
    pub passes: Vec<usize>,
    /// Wall-clock seconds for all pairs.
    pub seconds: f64,
}

/// Runs `params` on every pair (in parallel, one network copy per thread) and scores the
/// last pass's flow and P's labels.
pub fn score_procedure(
    net: &PartInductionNet,
    pairs: &[Pair],
    variant: &Variant,
) -> Result<VariantScores, ScoreError> {
    let method = NetworkMethod::with_params(variant.name, net.clone(), variant.params);
    let started = Instant::now();
    let scored: Vec<(PairScores, usize)> = pairs
        .par_iter()
        .map(|pair| {
            let inference = method.infer(pair.input())?;
            let scores = PairScores::of(pair, &inference.prediction(), f64::NAN)?;
            Ok((scores, inference.iterations.len()))
        })
        .collect::<Result<_, ScoreError>>()?;
    let (pairs, passes) = scored.into_iter().unzip();
    Ok(VariantScores {
        name: variant.name,
        pairs,
        passes,
        seconds: started.elapsed().as_secs_f64(),
    })
}

/// One line of the table: a variant on one group of pairs (a kind, or all).
#[derive(Debug, Clone, PartialEq)]
pub struct Line {
    /// The variant.
    pub variant: &'static str,
    /// `all`, or a kind (`SF2F`, ...).
    pub group: String,
    /// Pairs in the group.
    pub pairs: usize,
    /// Mean scores (support IoU unscored).
    pub scores: Scores,
    /// Mean passes.
    pub passes: f64,
    /// The difference from the first variant on the same pairs (none for the first).
    pub against_first: Option<Comparison>,
}

/// The table: every variant on all pairs and on each kind present, with its paired-bootstrap
/// difference from the first variant (`resamples` draws from `seed`).
pub fn table(
    pairs: &[Pair],
    variants: &[VariantScores],
    resamples: usize,
    seed: u64,
) -> Result<Vec<Line>, crate::train::validation::CompareError> {
    let mut groups: Vec<(String, Vec<usize>)> = vec![("all".into(), (0..pairs.len()).collect())];
    for kind in [PairKind::Sf2f, PairKind::Sf2p, PairKind::Sp2p] {
        let members: Vec<usize> =
            (0..pairs.len()).filter(|&i| pairs[i].input().kind == kind).collect();
        if !members.is_empty() && members.len() < pairs.len() {
            groups.push((kind.as_str().to_string(), members));
        }
    }
    let mut lines = Vec::new();
    for (group, members) in &groups {
        let pick = |v: &VariantScores| -> Vec<PairScores> {
            members.iter().map(|&i| v.pairs[i]).collect()
        };
        let first = variants.first().map(pick);
        for (k, v) in variants.iter().enumerate() {
            let own = pick(v);
            let against_first = match (&first, k) {
                (Some(first), k) if k > 0 => Some(compare(&own, first, resamples, seed)?),
                _ => None,
            };
            let passes = members.iter().map(|&i| v.passes[i] as f64).sum::<f64>()
                / members.len().max(1) as f64;
            lines.push(Line {
                variant: v.name,
                group: group.clone(),
                pairs: members.len(),
                scores: Scores::of(&own),
                passes,
                against_first,
            });
        }
    }
    Ok(lines)
}

/// The table as CSV: one row per line, the differences as value, low, high.
pub fn to_csv(lines: &[Line]) -> String {
    let mut out = String::from(
        "variant,group,pairs,epe,rand_index,iou,passes,\
         d_epe,d_epe_low,d_epe_high,d_ri,d_ri_low,d_ri_high,d_iou,d_iou_low,d_iou_high\n",
    );
    for l in lines {
        let d = |x: Option<crate::train::validation::Difference>| {
            x.map_or(",,".to_string(), |d| format!("{:.6},{:.6},{:.6}", d.value, d.low, d.high))
        };
        let c = l.against_first;
        out.push_str(&format!(
            "{},{},{},{:.6},{:.6},{:.6},{:.3},{},{},{}\n",
            l.variant,
            l.group,
            l.pairs,
            l.scores.epe,
            l.scores.rand_index,
            l.scores.iou,
            l.passes,
            d(c.map(|c| c.epe)),
            d(c.map(|c| c.rand_index)),
            d(c.map(|c| c.iou)),
        ));
    }
    out
}
