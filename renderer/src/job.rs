//! An object ready to render ([`RenderJob`]): its states, parts, cameras and materials,
//! drawn from the seed and the object id.

use assets::SourcedObject;
use pairs::math::{Isometry3, Point3, Real};
use pairs::{JointKind, PartId};
use rand::Rng as _;
use serde::Serialize;

use crate::appearance::{Appearance, Material};
use crate::cameras;
use crate::layout;
use crate::scene::RenderScene;
use crate::shade::{shade, Shading, ViewImages};
use crate::{RenderConfig, RenderError};
use articulated::kinematics::link_poses;
use articulated::objects::ArticulatedObject;
use articulated::seed::{rng_for, Stream};
use scanner::camera::Camera;

/// A joint in every rendered state.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct JointStates {
    /// Joint name.
    pub name: String,
    /// Revolute or prismatic.
    #[serde(rename = "type")]
    pub kind: JointKind,
    /// Parent link index.
    pub parent: usize,
    /// Child link index.
    pub child: usize,
    /// Part of the child link.
    pub part: PartId,
    /// Whether its value differs between states.
    pub moves: bool,
    /// Lower and upper limit (radians or object units).
    pub limits: [Real; 2],
    /// Value in each state.
    pub value: Vec<Real>,
    /// Unit axis in each state, object frame.
    pub axis: Vec<[Real; 3]>,
    /// A point of the axis in each state, object frame.
    pub pivot: Vec<[Real; 3]>,
}

/// An object ready to render: its states, parts, cameras and materials.
pub struct RenderJob {
    /// The object and where it came from.
    pub object: SourcedObject,
    /// Folder name (`<object id, 6 digits>_<category>`).
    pub name: String,
    /// Joint values of each state.
    pub states: Vec<Vec<Real>>,
    /// The posed object of each state.
    pub scenes: Vec<RenderScene>,
    /// Part of each link: a link starts a part when its joint's value differs between
    /// states.
    pub part_of_link: Vec<PartId>,
    /// Number of parts.
    pub parts: usize,
    /// The cameras, shared by every state.
    pub cameras: Vec<Camera>,
    /// The materials.
    pub appearance: Appearance,
    /// Object units per unit of the 16-bit depth images: fits the farthest depth any view
    /// can see.
    pub depth_scale: Real,
}

impl RenderJob {
    /// Draws the states and materials of `object` (from `seed` and its id), poses it, and
    /// places the cameras (`cameras`, or the config's placement around every state's
    /// bounding sphere) with the layout's intrinsics. For a layout of one moving part
    /// (PARIS), only the object's first driven joint (and the joints that mimic it) moves;
    /// the others keep their values of state 0.
    pub fn new(
        config: &RenderConfig,
        seed: u64,
        object: SourcedObject,
        cameras: Option<&[Camera]>,
        layout: layout::Layout,
    ) -> Result<Self, RenderError> {
        let name = object.folder_name();
        let id = u64::from(object.object_id);
        let mut states = draw_states(
            &object.object,
            config.states,
            &mut rng_for(seed, id, Stream::RenderStates),
        );
        if layout.one_joint() {
            hold_all_but_first(&object.object, &mut states);
        }
        let scenes = states
            .iter()
            .map(|values| RenderScene::new(&object.object, &link_poses(&object.object, values)))
            .collect::<Result<Vec<_>, _>>()
            .map_err(|source| RenderError::Scene { object: name.clone(), source })?;
        let (lo, hi) = bounds(&scenes);
        let centre = nalgebra::center(&lo, &hi);
        let radius = 0.5 * (hi - lo).norm();
        let cameras = match cameras {
            Some(c) => c.to_vec(),
            None => {
                let k = layout.intrinsics(config);
                let distance = cameras::fitting_distance(&k, radius, config.fill as Real);
                cameras::placed(k, config.placement, config.views, &centre, distance)
            }
        };
        let far =
            cameras.iter().map(|c| (c.centre() - centre).norm() + radius).fold(0.0, Real::max);
        let (part_of_link, parts) = parts_over_states(&object.object, &states);
        let diagonal = scenes[0].diagonal();
        let material = Material::draw(&mut rng_for(seed, id, Stream::Appearance), diagonal);
        let appearance =
            Appearance::single(material, object.object.links.len()).with_surfaces(&object.surfaces);
        Ok(Self {
            object,
            name,
            states,
            scenes,
            part_of_link,
            parts,
            cameras,
            appearance,
            depth_scale: far / 65534.0,
        })
    }

    /// Renders view `view` of state `state`.
    pub fn view(&self, config: &RenderConfig, state: usize, view: usize) -> ViewImages {
        self.view_from(config, state, &self.cameras[view])
    }

    /// Renders state `state` through any camera.
    pub fn view_from(&self, config: &RenderConfig, state: usize, camera: &Camera) -> ViewImages {
        let shading = Shading {
            appearance: &self.appearance,
            lighting: &config.lighting,
            part_of_link: &self.part_of_link,
            background: config.background.map(|c| Real::from(c) / 255.0),
        };
        shade(&self.scenes[state], camera, &shading)
    }

    /// Every joint in every state (axis and pivot placed by the parent link's pose).
    pub fn joints(&self) -> Vec<JointStates> {
        let object = &self.object.object;
        object
            .joints
            .iter()
            .enumerate()
            .map(|(j, joint)| {
                let value: Vec<Real> = self.states.iter().map(|s| s[j]).collect();
                let parent_pose = |s: usize| self.scenes[s].poses()[joint.parent];
                JointStates {
                    name: joint.name.clone(),
                    kind: joint.kind,
                    parent: joint.parent,
                    child: joint.child,
                    part: self.part_of_link[joint.child],
                    moves: value.iter().any(|&v| v != value[0]),
                    limits: [joint.limits.0, joint.limits.1],
                    axis: (0..self.states.len())
                        .map(|s| (parent_pose(s).rotation * joint.axis).into())
                        .collect(),
                    pivot: (0..self.states.len())
                        .map(|s| (parent_pose(s) * joint.pivot).coords.into())
                        .collect(),
                    value,
                }
            })
            .collect()
    }

    /// Motion of each part from state `a` to state `b` (object frame): the pose change of
    /// the part's links.
    pub fn part_motion(&self, part: PartId, a: usize, b: usize) -> Isometry3 {
        let link = self.part_of_link.iter().position(|&p| p == part).unwrap_or(0);
        self.scenes[b].poses()[link] * self.scenes[a].poses()[link].inverse()
    }
}

/// The states of a render: for each joint, value `s` is drawn in the `s`-th of S equal
/// slices of its range (away from the slice's ends), so every joint moves between any two
/// states and the states are ordered; mimic joints follow their leaders.
pub fn draw_states(
    object: &ArticulatedObject,
    states: u32,
    rng: &mut articulated::seed::Rng,
) -> Vec<Vec<Real>> {
    let n = states as usize;
    let mut values = vec![vec![0.0 as Real; object.joints.len()]; n];
    for (j, joint) in object.joints.iter().enumerate() {
        let (lo, hi) = joint.limits;
        for (s, state) in values.iter_mut().enumerate() {
            let t = (s as Real + rng.random_range(0.15..0.85)) / n as Real;
            state[j] = lo + (hi - lo) * t;
        }
    }
    for state in &mut values {
        object.follow_mimics(state);
    }
    values
}

/// Keeps every joint but the first driven one (not a mimic follower) at its value of state
/// 0; the first driven joint's followers follow it.
fn hold_all_but_first(object: &ArticulatedObject, states: &mut [Vec<Real>]) {
    let followers: Vec<usize> = object.mimics.iter().map(|m| m.joint).collect();
    let Some(driven) = (0..object.joints.len()).find(|j| !followers.contains(j)) else {
        return;
    };
    let first = states[0].clone();
    for state in states.iter_mut() {
        for (j, value) in state.iter_mut().enumerate() {
            if j != driven {
                *value = first[j];
            }
        }
        object.follow_mimics(state);
    }
}

/// Part of each link and the number of parts: a link starts its own part when its joint's
/// value differs between any two states, and joins its parent's part otherwise.
pub fn parts_over_states(object: &ArticulatedObject, states: &[Vec<Real>]) -> (Vec<PartId>, usize) {
    let mut of_link: Vec<PartId> = vec![0; object.links.len()];
    let mut parts = 1;
    for link in 1..object.links.len() {
        of_link[link] = match object.joints.iter().position(|j| j.child == link) {
            Some(j) if states.iter().any(|s| s[j] != states[0][j]) => {
                parts += 1;
                (parts - 1) as PartId
            }
            Some(j) => of_link[object.joints[j].parent],
            None => 0,
        };
    }
    (of_link, parts)
}

/// The triangles of the links of `parts` (all parts when `None`) in state `state`, object
/// frame: vertices and triangles.
pub fn posed_mesh(
    job: &RenderJob,
    state: usize,
    parts: Option<&[PartId]>,
) -> (Vec<Point3>, Vec<[u32; 3]>) {
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    let poses = job.scenes[state].poses();
    for (link, l) in job.object.object.links.iter().enumerate() {
        if parts.is_some_and(|p| !p.contains(&job.part_of_link[link])) {
            continue;
        }
        let first = vertices.len() as u32;
        vertices.extend(l.mesh.vertices.iter().map(|v| poses[link] * v));
        triangles.extend(l.mesh.triangles.iter().map(|t| t.map(|i| i + first)));
    }
    (vertices, triangles)
}

/// Bounding box (lowest and highest corner) of an object over its posed states.
pub fn bounds(scenes: &[RenderScene]) -> (Point3, Point3) {
    pairs::math::bounds(scenes.iter().flat_map(|s| s.corners()))
        .unwrap_or((Point3::origin(), Point3::origin()))
}
