//! The render joints board (`joints_renders.csv`): joints-only predictions for a render
//! (`generator render`, any layout) scored in every family's convention
//! ([`pairs::metrics::render_joints`]; docs/METRICS.md, "Joints of a render"). One line per
//! render, method and variant; `evaluator score` adds or replaces a method's lines and
//! keeps every other line.

use std::io::Write as _;
use std::path::Path;

use pairs::atomic::replace_file;
use pairs::metrics::render_joints::{score_object, Variant, VariantScores};
use std::collections::BTreeMap;

use pairs::renders::{read_predictions, read_truth, RenderJoint, RenderTruth};

use crate::error::EvalError;

/// The file of the board under the reports folder.
pub const RENDER_JOINTS_FILE: &str = "joints_renders.csv";

/// The board's header.
pub const HEADER: &str = "render,method,variant,joints,matched,type_accuracy,axis_angle_deg,\
                          axis_distance,state_revolute_deg,state_prismatic";

/// One method's scores on one render in one variant.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderJointRow {
    /// The render's name (its folder's).
    pub render: String,
    /// The method.
    pub method: String,
    /// The variant.
    pub variant: Variant,
    /// The summed errors.
    pub scores: VariantScores,
}

impl RenderJointRow {
    /// The CSV line (no newline).
    pub fn line(&self) -> String {
        let s = &self.scores;
        let f = |x: f64| if x.is_nan() { String::new() } else { format!("{x:.6}") };
        format!(
            "{},{},{},{},{},{},{},{},{},{}",
            self.render,
            self.method,
            self.variant.as_str(),
            s.joints,
            s.matched,
            f(s.type_accuracy()),
            f(s.angle()),
            f(s.distance()),
            f(s.revolute_state()),
            f(s.prismatic_state())
        )
    }
}

/// Scores a joints-only prediction file on the render in `dir`, in every variant, as the
/// method `name` (default: the file's own).
pub fn score_render(
    dir: &Path,
    predictions: &Path,
    name: Option<&str>,
) -> Result<Vec<RenderJointRow>, EvalError> {
    let truth = read_truth(dir)?;
    let file = read_predictions(predictions, &truth)?;
    let render = dir
        .file_name()
        .map_or_else(|| dir.display().to_string(), |n| n.to_string_lossy().into_owned());
    let method = name.unwrap_or(&file.method).to_string();
    if method.contains(',') || render.contains(',') {
        return Err(EvalError::PredictionsMismatch {
            path: predictions.into(),
            message: format!("the names {render:?} and {method:?} must not hold commas"),
        });
    }
    Ok(score_joints(&truth, &file.objects, &render, &method))
}

/// The board's lines of `method`'s joints (per object folder) on a render's `truth`, one
/// per variant.
pub fn score_joints(
    truth: &RenderTruth,
    predicted: &BTreeMap<String, Vec<RenderJoint>>,
    render: &str,
    method: &str,
) -> Vec<RenderJointRow> {
    Variant::ALL
        .iter()
        .map(|&variant| {
            let mut scores = VariantScores::default();
            for object in &truth.objects {
                let guess = predicted.get(&object.folder).map_or(&[][..], Vec::as_slice);
                let joints: Vec<RenderJoint> =
                    object.joints.iter().map(|j| j.joint.clone()).collect();
                scores.add(&score_object(variant, guess, &joints, object.diagonal));
            }
            RenderJointRow { render: render.into(), method: method.into(), variant, scores }
        })
        .collect()
}

/// Adds `rows` to the board in `reports`, replacing the lines of the same render and
/// method, keeping the others (sorted by render, method, then variant order).
pub fn upsert(reports: &Path, rows: &[RenderJointRow]) -> Result<(), EvalError> {
    let path = reports.join(RENDER_JOINTS_FILE);
    let mut lines: Vec<String> = match std::fs::read_to_string(&path) {
        Ok(text) => {
            let mut it = text.lines();
            if it.next() != Some(HEADER) {
                return Err(EvalError::Csv {
                    path,
                    message: "not the render joints board's header".into(),
                });
            }
            it.filter(|l| {
                let mut f = l.split(',');
                let (r, m) = (f.next().unwrap_or(""), f.next().unwrap_or(""));
                !rows.iter().any(|row| row.render == r && row.method == m)
            })
            .map(str::to_string)
            .collect()
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Vec::new(),
        Err(source) => return Err(EvalError::Io { path, source }),
    };
    lines.extend(rows.iter().map(RenderJointRow::line));
    let order = |l: &String| {
        let f: Vec<&str> = l.splitn(4, ',').collect();
        let v =
            Variant::ALL.iter().position(|v| Some(&v.as_str()) == f.get(2)).unwrap_or(usize::MAX);
        (f.first().map(|s| s.to_string()), f.get(1).map(|s| s.to_string()), v)
    };
    lines.sort_by_key(order);
    std::fs::create_dir_all(reports)
        .map_err(|source| EvalError::Io { path: reports.into(), source })?;
    replace_file(&path, |out| {
        writeln!(out, "{HEADER}").map_err(pairs::atomic::at(&path))?;
        for l in &lines {
            writeln!(out, "{l}").map_err(pairs::atomic::at(&path))?;
        }
        Ok::<(), EvalError>(())
    })
}

/// A printed table of `rows`.
pub fn table(rows: &[RenderJointRow]) -> Vec<String> {
    let mut out = vec![format!(
        "{:<8} {:>7} {:>9} {:>10} {:>10} {:>12} {:>12}",
        "variant", "joints", "type acc", "angle deg", "distance", "state deg", "state dist"
    )];
    for r in rows {
        let s = &r.scores;
        out.push(format!(
            "{:<8} {:>3}/{:<3} {:>9.3} {:>10.3} {:>10.4} {:>12.3} {:>12.4}",
            r.variant.as_str(),
            s.matched,
            s.joints,
            s.type_accuracy(),
            s.angle(),
            s.distance(),
            s.revolute_state(),
            s.prismatic_state()
        ));
    }
    out
}

/// The LEADERBOARD.md section of the board in `reports` (`None` when there is no board):
/// per render and method, the right-type fraction and the mean errors in each convention.
pub fn section(reports: &Path) -> Option<String> {
    let text = std::fs::read_to_string(reports.join(RENDER_JOINTS_FILE)).ok()?;
    let mut lines = text.lines();
    if lines.next() != Some(HEADER) {
        return None;
    }
    // (render, method) -> variant -> fields, in board order.
    type Fields = BTreeMap<String, Vec<String>>;
    let mut rows: Vec<((String, String), Fields)> = Vec::new();
    for line in lines {
        let f: Vec<String> = line.split(',').map(str::to_string).collect();
        if f.len() != 10 {
            continue;
        }
        let key = (f[0].clone(), f[1].clone());
        let at = match rows.iter().position(|(k, _)| *k == key) {
            Some(i) => i,
            None => {
                rows.push((key, BTreeMap::new()));
                rows.len() - 1
            }
        };
        rows[at].1.insert(f[2].clone(), f);
    }
    let mut out = String::from(
        "## Joints of renders\n\nJoints on renders for image-based methods (`generator render`; \
         `joints_renders.csv`, docs/METRICS.md \"Joints of a render\"). On the default render \
         (`datasets/render`: the 26 test objects, two states, eight views at 320 x 240) every \
         row that runs on a pair's input sees two clouds of 512 points back-projected from the \
         depth images of each state; its joints are its segments' motions relative to its \
         largest segment, in the object frame. Rows scored with `evaluator score` from a \
         joints-only file sit beside them. The same errors in four conventions: ours \
         (distances over the object's diagonal), PARIS's (0 for parallel axes), \
         DigitalTwinArt's (distances x 10) and ArtGS's (DigitalTwinArt's, matching joints of \
         the same type only). Angles and states in degrees; distances in world units.\n\n\
         | render | row | joints | type acc. | angle° | distance | state° | PARIS dist. | PARIS state° | DTA dist. | DTA state° | ArtGS dist. | ArtGS state° |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    let cell = |v: Option<&String>| match v {
        Some(s) if !s.is_empty() => {
            s.parse::<f64>().map_or_else(|_| s.clone(), |x| format!("{x:.3}"))
        }
        _ => "–".into(),
    };
    for ((render, method), variants) in rows {
        let get =
            |variant: &str, column: usize| cell(variants.get(variant).and_then(|f| f.get(column)));
        let joints =
            variants.get("ours").map_or_else(String::new, |f| format!("{}/{}", f[4], f[3]));
        out.push_str(&format!(
            "| {render} | `{method}` | {joints} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
            get("ours", 5),
            get("ours", 6),
            get("ours", 7),
            get("ours", 8),
            get("paris", 7),
            get("paris", 8),
            get("dta", 7),
            get("dta", 8),
            get("artgs", 7),
            get("artgs", 8),
        ));
    }
    out.push('\n');
    Some(out)
}
