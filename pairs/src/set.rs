//! The set record: K >= 2 observations of one object in K articulation states (the
//! MultiBodySync setting), with part ids consistent across all K, and the pair record of
//! any two of them ([`Set::pair`]).
//!
//! A *set part* is a group of links that move rigidly together in all K states. Between
//! two views i and j fewer parts may move apart (a joint that sits at the same value in
//! both states), so the pair (i, j) merges set parts exactly as the pair generator merges
//! links: the record stores, for every ordered pair of views, which set parts form one
//! part of that pair ([`SetTruth::pair_parts`]), and every other field of the pair's
//! ground truth follows from the views' own fields.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::cloud::Cloud;
use crate::error::{PairError, SetError};
use crate::ground_truth::{nearest_of_part, GroundTruth};
use crate::joints::{JointKind, JointTruth};
use crate::math::{Point3, Real, Vector3};
use crate::pair::{Pair, PairInput, PairKind, Pose, Provenance};
use crate::parts::{PartId, MAX_PARTS};
use crate::scan::{Scan, Scans};
use crate::transform::Similarity;

/// Tolerance on view 0's own motions, which must be the identity.
const IDENTITY_TOLERANCE: Real = 1e-5;
/// Tolerance on a rotation matrix's deviation from orthonormality (the pair record's).
const ROTATION_TOLERANCE: Real = 1e-3;
/// How far the motions of set parts grouped into one part of a pair may differ between its
/// two views (rotation and translation differences, summed; normalised units).
const GROUP_TOLERANCE: Real = 1e-3;
/// Tolerance on a stored flow against the motion it should equal, normalised units (the
/// pair record's).
const FLOW_TOLERANCE: Real = 1e-4;

/// How one view of a set was observed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ViewKind {
    /// A full shape: area-weighted surface samples.
    Full,
    /// A virtual scan from one camera.
    Scan,
}

impl ViewKind {
    /// Lower-case name, as written in files.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Full => "full",
            Self::Scan => "scan",
        }
    }
}

/// What the views of a set are: every one full, every one scanned, or view 0 full and the
/// others scanned (the SF2P setting with K views).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum SetMode {
    /// Every view a full shape.
    #[default]
    Full,
    /// Every view a virtual scan.
    Scan,
    /// View 0 a full shape, the others virtual scans.
    Mixed,
}

impl SetMode {
    /// Every mode, in the order docs list them.
    pub const ALL: [SetMode; 3] = [Self::Full, Self::Scan, Self::Mixed];

    /// Lower-case name, as written in files.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Full => "full",
            Self::Scan => "scan",
            Self::Mixed => "mixed",
        }
    }

    /// How view `k` is observed.
    pub fn view(self, k: usize) -> ViewKind {
        match self {
            Self::Full => ViewKind::Full,
            Self::Scan => ViewKind::Scan,
            Self::Mixed if k == 0 => ViewKind::Full,
            Self::Mixed => ViewKind::Scan,
        }
    }

    /// The mode of a sequence of view kinds, if it is one of the three.
    pub fn of(kinds: &[ViewKind]) -> Option<Self> {
        Self::ALL.into_iter().find(|m| kinds.iter().enumerate().all(|(k, &v)| m.view(k) == v))
    }
}

impl std::str::FromStr for SetMode {
    type Err = String;

    /// Parses a mode's name, in either case.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|m| m.as_str().eq_ignore_ascii_case(s))
            .ok_or_else(|| format!("unknown set mode {s:?}; expected one of full, scan, mixed"))
    }
}

/// One observation of a set as a method sees it.
#[derive(Debug, Clone, PartialEq)]
pub struct View {
    /// Full shape or scan.
    pub kind: ViewKind,
    /// The cloud, in its own normalised frame.
    pub cloud: Cloud,
}

/// A set as a method sees it: its K views, without any ground truth.
#[derive(Debug, Clone, PartialEq)]
pub struct SetInput {
    /// Unique id within the dataset.
    pub id: String,
    /// The K observations, view 0 first.
    pub views: Vec<View>,
}

/// The joint between two set parts, seen in every view.
#[derive(Debug, Clone, PartialEq)]
pub struct SetJoint {
    /// The joint's name (the exported URDF's).
    pub name: String,
    /// The set part it moves.
    pub part: PartId,
    /// The set part it moves it against.
    pub parent: PartId,
    /// Revolute or prismatic.
    pub kind: JointKind,
    /// Per view: unit axis direction, the view's normalised frame.
    pub axis: Vec<Vector3>,
    /// Per view: a point on the axis, the view's normalised frame.
    pub pivot: Vec<Point3>,
    /// Per view: the joint's value (radians or object units, see [`JointKind`]).
    pub value: Vec<Real>,
}

/// Everything a method must recover for one set.
#[derive(Debug, Clone, PartialEq)]
pub struct SetTruth {
    /// Per view, per point: its set part. Part 0 holds the root link; part k in one view is
    /// part k in every view.
    pub parts: Vec<Vec<PartId>>,
    /// `motions[k][s]` maps set part s from view 0's normalised frame to view k's; the
    /// parts of one view share one scale, and view 0's motions are the identity.
    pub motions: Vec<Vec<Similarity>>,
    /// `flows[k]`: per point of view 0, `motions[k][parts[0][i]](x_i) - x_i` (all zero for
    /// k = 0), view k's normalised units.
    pub flows: Vec<Vec<Vector3>>,
    /// `presence[i][j]`: per point of view i, whether the point moved to view j's state is
    /// present in view j (always for a full view j; for a scan, visible from its camera and
    /// not lost); `presence[i][i]` is all true.
    pub presence: Vec<Vec<Vec<bool>>>,
    /// `pair_parts[i][j][s]`: the part of the pair (i, j) that set part s belongs to (set
    /// parts that did not move relative to each other between the two states are one part
    /// of the pair, numbered by first appearance); `pair_parts[i][i]` is `0..parts`.
    pub pair_parts: Vec<Vec<Vec<PartId>>>,
    /// The joints between set parts, in the object's joint order.
    pub joints: Vec<SetJoint>,
}

impl SetTruth {
    /// Number of set parts.
    pub fn num_parts(&self) -> usize {
        self.motions.first().map_or(0, Vec::len)
    }
}

/// Where one view came from.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct ViewProvenance {
    /// Index of the view's articulation state among the object's states.
    pub articulation: u32,
    /// Every joint of the object by name, with its value in the view's state.
    pub joints: BTreeMap<String, Real>,
    /// The view's global pose: the object's rest frame into the view's object frame.
    pub pose: Option<Pose>,
}

/// Where a set came from, so that it can be regenerated.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct SetProvenance {
    /// Object category.
    pub category: String,
    /// Index of the object within its dataset.
    pub object_id: u32,
    /// Index of the set among the object's sets.
    pub set_index: u32,
    /// Seed of the dataset the set belongs to.
    pub seed: u64,
    /// Version of the generator that made it.
    pub generator_version: String,
    /// Per view.
    pub views: Vec<ViewProvenance>,
}

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

/// The shapes and ids of a set: everything [`Set::pair`] indexes, so that it cannot panic.
fn validate(
    input: &SetInput,
    truth: &SetTruth,
    provenance: &SetProvenance,
    scans: &[Option<Scan>],
) -> Result<(), SetError> {
    let set = input.id.as_str();
    let bad = |field: &'static str, index: usize, reason: String| SetError::Invalid {
        set: set.into(),
        field,
        index,
        reason,
    };
    let views = input.views.len();
    if views < 2 {
        return Err(bad("views", 0, format!("{views} views (a set has at least 2)")));
    }
    let kinds: Vec<ViewKind> = input.views.iter().map(|v| v.kind).collect();
    if SetMode::of(&kinds).is_none() {
        let reason = "views must be all full, all scanned, or view 0 full and the others \
                      scanned"
            .to_string();
        return Err(bad("views", 0, reason));
    }
    let per_view = [
        ("parts", truth.parts.len()),
        ("motions", truth.motions.len()),
        ("flows", truth.flows.len()),
        ("presence", truth.presence.len()),
        ("pair_parts", truth.pair_parts.len()),
        ("provenance.views", provenance.views.len()),
        ("scans", scans.len()),
    ];
    for (field, found) in per_view {
        if found != views {
            return Err(bad(field, 0, format!("{found} entries for {views} views")));
        }
    }
    let parts = truth.num_parts();
    if parts == 0 || parts > MAX_PARTS {
        return Err(bad("motions", 0, format!("{parts} parts (1 to {MAX_PARTS})")));
    }
    let n0 = input.views[0].cloud.len();
    for (k, view) in input.views.iter().enumerate() {
        let n = view.cloud.len();
        if n == 0 {
            return Err(bad("views", k, "empty cloud".into()));
        }
        if truth.parts[k].len() != n {
            return Err(bad("parts", k, format!("{} ids for {n} points", truth.parts[k].len())));
        }
        if let Some(i) = truth.parts[k].iter().position(|&s| usize::from(s) >= parts) {
            return Err(bad("parts", k, format!("point {i} holds part {}", truth.parts[k][i])));
        }
        if truth.motions[k].len() != parts {
            return Err(bad("motions", k, format!("{} motions", truth.motions[k].len())));
        }
        if truth.flows[k].len() != n0 {
            return Err(bad("flows", k, format!("{} vectors", truth.flows[k].len())));
        }
        if (view.kind == ViewKind::Scan) != scans[k].is_some() {
            return Err(bad("scans", k, "a scanned view has a camera, a full view none".into()));
        }
        let (presence, groups) = (&truth.presence[k], &truth.pair_parts[k]);
        if presence.len() != views || groups.len() != views {
            return Err(bad("presence", k, format!("rows for {views} views expected")));
        }
        for j in 0..views {
            if presence[j].len() != n || (j == k && !presence[j].iter().all(|&p| p)) {
                let reason = format!("row {j}: {n} flags expected (all 1 for its own view)");
                return Err(bad("presence", k, reason));
            }
            pair_groups(&groups[j], parts, j == k).map_err(|r| bad("pair_parts", k, r))?;
        }
    }
    for (k, motions) in truth.motions.iter().enumerate() {
        let scale = motions[0].scale;
        let broken = motions.iter().position(|m| {
            !m.is_finite() || m.rotation_defect() > ROTATION_TOLERANCE || m.scale != scale
        });
        if let Some(s) = broken {
            let reason = format!("part {s}: not finite, not a rotation, or another scale");
            return Err(bad("motions", k, reason));
        }
        if scale.is_nan() || scale <= 0.0 {
            return Err(bad("motions", k, format!("scale {scale} is not positive")));
        }
    }
    // Set parts grouped into one part of a pair must move alike between its two views.
    for i in 0..views {
        for j in (0..views).filter(|&j| j != i) {
            let groups = &truth.pair_parts[i][j];
            let between = |s: usize| truth.motions[j][s].compose(&truth.motions[i][s].inverse());
            for (s, &g) in groups.iter().enumerate() {
                let first = groups.iter().position(|&x| x == g).unwrap_or(s);
                let (a, b) = (between(s), between(first));
                let apart =
                    (a.rotation - b.rotation).norm() + (a.translation - b.translation).norm();
                if apart.is_nan() || apart > GROUP_TOLERANCE {
                    let reason = format!(
                        "row {j}: set parts {first} and {s} form one part but move apart by {apart}"
                    );
                    return Err(bad("pair_parts", i, reason));
                }
            }
        }
    }
    let identity = Similarity::identity();
    let off = |m: &Similarity| {
        (m.rotation - identity.rotation).norm() + m.translation.norm() + (m.scale - 1.0).abs()
    };
    if let Some(s) = truth.motions[0].iter().position(|m| off(m) > IDENTITY_TOLERANCE) {
        return Err(bad("motions", 0, format!("view 0's motion of part {s} is not the identity")));
    }
    let view0 = &input.views[0].cloud.points;
    for (k, (flow, motions)) in truth.flows.iter().zip(&truth.motions).enumerate() {
        for (i, ((x, f), &s)) in view0.iter().zip(flow).zip(&truth.parts[0]).enumerate() {
            let err = (motions[usize::from(s)].apply(x) - x - f).norm();
            // A NaN flow fails too: it is not within the tolerance.
            if err.is_nan() || err > FLOW_TOLERANCE * (1.0 + x.coords.norm()) {
                let reason =
                    format!("view {k}'s flow of point {i} differs from the motion by {err}");
                return Err(bad("flows", k, reason));
            }
        }
    }
    for (index, joint) in truth.joints.iter().enumerate() {
        let (part, parent) = (usize::from(joint.part), usize::from(joint.parent));
        if part >= parts || parent >= parts || part == parent {
            let reason = format!("joins parts {part} and {parent} of {parts}");
            return Err(bad("joints", index, reason));
        }
        let lengths = [joint.axis.len(), joint.pivot.len(), joint.value.len()];
        if lengths.iter().any(|&l| l != views) {
            return Err(bad("joints", index, format!("per-view lengths {lengths:?}, not {views}")));
        }
        let finite = joint.value.iter().all(|v| v.is_finite())
            && joint.pivot.iter().all(|p| p.coords.iter().all(|c| c.is_finite()))
            && joint.axis.iter().all(|a| (a.norm() - 1.0).abs() <= 1e-3);
        if !finite {
            let reason = "values and pivots must be finite and axes unit".to_string();
            return Err(bad("joints", index, reason));
        }
    }
    Ok(())
}

/// A row of `pair_parts`: one id per set part, numbered by first appearance from 0 (the
/// identity on a view's own row).
fn pair_groups(groups: &[PartId], parts: usize, own: bool) -> Result<(), String> {
    if groups.len() != parts {
        return Err(format!("{} ids for {parts} parts", groups.len()));
    }
    let mut next = 0usize;
    for (s, &g) in groups.iter().enumerate() {
        let g = usize::from(g);
        if g > next || (own && g != s) {
            return Err(format!("part {s} in pair part {g}: not numbered by first appearance"));
        }
        next = next.max(g + 1);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synthetic;

    #[test]
    fn modes_name_their_views() {
        assert_eq!(
            SetMode::of(&[ViewKind::Full, ViewKind::Scan, ViewKind::Scan]),
            Some(SetMode::Mixed)
        );
        assert_eq!(SetMode::of(&[ViewKind::Scan, ViewKind::Full]), None);
        assert_eq!("MIXED".parse::<SetMode>(), Ok(SetMode::Mixed));
        assert!("both".parse::<SetMode>().unwrap_err().contains("full, scan, mixed"));
    }

    #[test]
    fn pair_groups_number_by_first_appearance() {
        assert!(pair_groups(&[0, 1, 0, 2], 4, false).is_ok());
        assert!(pair_groups(&[0, 2, 1], 3, false).is_err());
        assert!(pair_groups(&[0, 0], 2, true).is_err());
        assert!(pair_groups(&[0], 2, false).is_err());
    }

    #[test]
    fn a_hinge_set_slices_into_its_pairs() {
        let angles = [0.0, 0.4, 0.4, -0.3];
        let set = synthetic::hinge_set("h", 4, &angles);
        assert_eq!((set.len(), set.mode(), set.truth().num_parts()), (4, SetMode::Full, 2));
        // Views 1 and 2 hold the same state: their pair has one part and no joint.
        let still = set.pair(1, 2).expect("a pair");
        assert_eq!(still.truth().num_parts(), 1);
        assert!(still.truth().joints.is_empty());
        for (i, j) in [(0, 1), (1, 3), (3, 0), (2, 1)] {
            let pair = set.pair(i, j).expect("a pair");
            let (input, truth) = (pair.input(), pair.truth());
            assert_eq!(pair.id(), format!("h-{i}-{j}"));
            // Every view holds the same samples in the same order: the flow carries each
            // point of P onto its own sample in Q, which is its correspondence.
            let flow = truth.flow.as_ref().expect("a flow");
            for (k, (p, f)) in input.p.points.iter().zip(flow).enumerate() {
                assert!((p + f - input.q.points[k]).norm() < 1e-5, "({i}, {j}) point {k}");
                assert_eq!(truth.corr_index[k], k as i32);
            }
            let moving = angles[i] != angles[j];
            assert_eq!(truth.num_parts(), if moving { 2 } else { 1 });
            if moving {
                assert!(
                    (truth.joints[0].value_q - truth.joints[0].value_p - (angles[j] - angles[i]))
                        .abs()
                        < 1e-6
                );
            }
        }
    }

    #[test]
    fn bad_sets_are_refused_by_field() {
        let set = synthetic::hinge_set("h", 3, &[0.0, 0.5, 1.0]);
        let err = set.pair(0, 3).unwrap_err().to_string();
        assert!(err.contains("view 3") && err.contains("3 views"), "{err}");
        assert!(set.pair(1, 1).is_err());
        let (input, truth, prov, scans) = set.clone().into_parts();
        let mut broken = truth.clone();
        broken.pair_parts[0][1] = vec![1, 0];
        let err = Set::new(input.clone(), broken, prov.clone(), scans.clone()).unwrap_err();
        assert!(err.to_string().contains("pair_parts"), "{err}");
        // Parts 0 and 1 turn apart between views 0 and 1: they cannot be one part there.
        let mut broken = truth.clone();
        broken.pair_parts[0][1] = vec![0, 0];
        let err = Set::new(input.clone(), broken, prov.clone(), scans.clone()).unwrap_err();
        assert!(err.to_string().contains("move apart"), "{err}");
        let mut broken = truth.clone();
        broken.motions[2][1].scale *= 2.0;
        let err = Set::new(input.clone(), broken, prov.clone(), scans.clone()).unwrap_err();
        assert!(err.to_string().contains("motions"), "{err}");
        let mut broken = truth.clone();
        broken.parts[2].pop();
        let err = Set::new(input.clone(), broken, prov.clone(), scans.clone()).unwrap_err();
        assert!(err.to_string().contains("parts"), "{err}");
        let mut broken = truth;
        broken.flows[1][0].x += 0.5;
        let err = Set::new(input, broken, prov, scans).unwrap_err().to_string();
        assert!(err.contains("flow") || err.contains("flows"), "{err}");
    }
}
