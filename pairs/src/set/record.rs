//! The set record ([`Set`]), checked when built, and the pair record of any two of its views
//! ([`Set::pair`]).

use crate::error::{PairError, SetError};
use crate::ground_truth::{nearest_of_part, GroundTruth};
use crate::joints::JointTruth;
use crate::math::Point3;
use crate::pair::{Pair, PairInput, PairKind, Provenance};
use crate::parts::PartId;
use crate::scan::{Scan, Scans};
use crate::set::types::{SetInput, SetMode, SetProvenance, SetTruth, ViewKind};
use crate::set::validate::validate;
use crate::transform::Similarity;

/// A set with its ground truth; constructed only through [`Set::new`], which validates it.
#[derive(Debug, Clone, PartialEq)]
pub struct Set {
    input: SetInput,
    truth: SetTruth,
    provenance: SetProvenance,
    scans: Vec<Option<Scan>>,
}

impl Set {
    /// Builds a set, checking its shapes and ids, and every pair (0, k) as
    /// [`Pair::new`] checks a pair. `scans[k]` is view k's camera (`None` for a full view).
    pub fn new(
        input: SetInput,
        truth: SetTruth,
        provenance: SetProvenance,
        scans: Vec<Option<Scan>>,
    ) -> Result<Self, SetError> {
        validate(&input, &truth, &provenance, &scans)?;
        let set = Self { input, truth, provenance, scans };
        for k in 1..set.len() {
            set.pair(0, k)?;
        }
        Ok(set)
    }

    /// The set's id.
    pub fn id(&self) -> &str {
        &self.input.id
    }

    /// Number of views K.
    pub fn len(&self) -> usize {
        self.input.views.len()
    }

    /// Whether the set has no views (never true for a valid set).
    pub fn is_empty(&self) -> bool {
        self.input.views.is_empty()
    }

    /// The views without ground truth, for methods.
    pub fn input(&self) -> &SetInput {
        &self.input
    }

    /// The ground truth.
    pub fn truth(&self) -> &SetTruth {
        &self.truth
    }

    /// Where the set came from.
    pub fn provenance(&self) -> &SetProvenance {
        &self.provenance
    }

    /// Each view's camera, `None` for a full view.
    pub fn scans(&self) -> &[Option<Scan>] {
        &self.scans
    }

    /// Full, scanned or mixed.
    pub fn mode(&self) -> SetMode {
        let kinds: Vec<ViewKind> = self.input.views.iter().map(|v| v.kind).collect();
        SetMode::of(&kinds).expect("validated on construction")
    }

    /// The id of the pair (i, j): `<set id>-<i>-<j>`.
    pub fn pair_id(&self, i: usize, j: usize) -> String {
        format!("{}-{i}-{j}", self.input.id)
    }

    /// The pair record of views i (as P) and j (as Q), with the ground truth a pair dataset
    /// holds for the same two observations: parts merged where they did not move apart,
    /// motions composed from the views' own (`motions[j] ∘ motions[i]⁻¹`), flow, the
    /// correspondences of the points present in view j, and the joints that move a part of
    /// the pair. A scan as P with a full shape as Q has no pair kind and is refused.
    pub fn pair(&self, i: usize, j: usize) -> Result<Pair, SetError> {
        let views = self.len();
        for view in [i, j] {
            if view >= views {
                return Err(SetError::NoView { set: self.id().into(), view, views });
            }
        }
        let id = self.pair_id(i, j);
        let (vi, vj) = (&self.input.views[i], &self.input.views[j]);
        if i == j {
            let reason = "a pair needs two different views".to_string();
            return Err(SetError::NoPair { set: self.id().into(), i, j, reason });
        }
        let Some(kind) = pair_kind(vi.kind, vj.kind) else {
            let reason = "no pair kind has a scan as P and a full shape as Q".to_string();
            return Err(SetError::NoPair { set: self.id().into(), i, j, reason });
        };
        let t = &self.truth;
        let groups = &t.pair_parts[i][j];
        let relabel = |ids: &[PartId]| -> Vec<PartId> {
            ids.iter().map(|&s| groups[usize::from(s)]).collect()
        };
        let (part_p, part_q) = (relabel(&t.parts[i]), relabel(&t.parts[j]));
        let count = groups.iter().map(|&g| usize::from(g) + 1).max().unwrap_or(0);
        let motions: Vec<Similarity> = (0..count)
            .map(|g| {
                let first = groups.iter().position(|&x| usize::from(x) == g).unwrap_or(0);
                t.motions[j][first].compose(&t.motions[i][first].inverse())
            })
            .collect();
        let (p, q) = (&vi.cloud, &vj.cloud);
        let moved: Vec<Point3> =
            p.points.iter().zip(&part_p).map(|(x, &k)| motions[usize::from(k)].apply(x)).collect();
        let flow = moved.iter().zip(&p.points).map(|(m, x)| m - x).collect();
        let corr_index: Vec<i32> = moved
            .iter()
            .zip(&part_p)
            .zip(&t.presence[i][j])
            .map(
                |((m, &k), &present)| {
                    if present {
                        nearest_of_part(m, k, &q.points, &part_q)
                    } else {
                        -1
                    }
                },
            )
            .collect();
        let corr_mask = corr_index.iter().map(|&c| c >= 0).collect();
        let joints = t
            .joints
            .iter()
            .filter(|joint| groups[usize::from(joint.part)] != groups[usize::from(joint.parent)])
            .map(|joint| JointTruth {
                part: groups[usize::from(joint.part)],
                kind: joint.kind,
                axis_p: joint.axis[i],
                pivot_p: joint.pivot[i],
                axis_q: joint.axis[j],
                pivot_q: joint.pivot[j],
                value_p: joint.value[i],
                value_q: joint.value[j],
            })
            .collect();
        let truth = GroundTruth {
            part_p,
            part_q,
            motions,
            flow: Some(flow),
            corr_mask,
            corr_index,
            joints,
        };
        let prov = &self.provenance;
        let (pi, pj) = (&prov.views[i], &prov.views[j]);
        let provenance = Provenance {
            category: prov.category.clone(),
            object_id: prov.object_id,
            articulation_p: pi.articulation,
            articulation_q: pj.articulation,
            seed: prov.seed,
            seed_q: None,
            generator_version: prov.generator_version.clone(),
            joints_p: pi.joints.clone(),
            joints_q: pj.joints.clone(),
            pose_p: pi.pose,
            pose_q: pj.pose,
        };
        let input = PairInput { id, kind, p: p.clone(), q: q.clone() };
        let scans = Scans { p: self.scans[i].clone(), q: self.scans[j].clone() };
        let slice = |source: PairError| SetError::Pair { set: self.id().into(), i, j, source };
        Pair::new(input, truth, provenance).and_then(|pair| pair.with_scans(scans)).map_err(slice)
    }

    /// Splits the set into its parts.
    pub fn into_parts(self) -> (SetInput, SetTruth, SetProvenance, Vec<Option<Scan>>) {
        (self.input, self.truth, self.provenance, self.scans)
    }
}

/// The kind of the pair of a view of kind `p` (as P) and one of kind `q` (as Q): SF2F,
/// SF2P or SP2P; `None` for a scan as P with a full Q (no kind has it).
pub fn pair_kind(p: ViewKind, q: ViewKind) -> Option<PairKind> {
    match (p, q) {
        (ViewKind::Full, ViewKind::Full) => Some(PairKind::Sf2f),
        (ViewKind::Full, ViewKind::Scan) => Some(PairKind::Sf2p),
        (ViewKind::Scan, ViewKind::Scan) => Some(PairKind::Sp2p),
        (ViewKind::Scan, ViewKind::Full) => None,
    }
}
