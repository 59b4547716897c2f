//! A URDF asset: links with their visual geometry (meshes from OBJ or STL files, boxes,
//! cylinders, spheres, capsules), joints with origins, axes, limits and mimics.
//!
//! Link frames are placed by forward kinematics at all joints 0 (the URDF's rest pose):
//! a child's frame is its parent's frame times the joint's `origin`; a visual's vertices
//! are `frame * visual origin * (scale * v)`; a joint's axis (given in the joint frame) and
//! the joint frame's origin, moved into the rest frame, give the model's axis and pivot.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use nalgebra::{Isometry3, Point3 as P3, Translation3, UnitQuaternion, Vector3 as V3};
use pairs::math::{Point3, Real};

use super::mesh_files::read_mesh_file;
use super::skeleton::{RawJoint, RawKind, RawLink, RawMimic, Skeleton};
use super::surface::{Surface, SurfaceMaterial};
use super::{text, ImportError, ImportOptions};
use articulated::mesh::Mesh;

/// Segments of the cylinders, spheres and capsules of URDF primitive geometry.
const SEGMENTS: u32 = 24;

/// The skeleton of the URDF at `path` and the mesh files it read.
pub fn read_urdf_asset(
    path: &Path,
    options: &ImportOptions,
) -> Result<(Skeleton, Vec<PathBuf>), ImportError> {
    let text = text::read_text(path)?;
    let base = path.parent().unwrap_or(Path::new("."));
    urdf_skeleton(path, &text, &MeshSearch { base, options })
}

/// Where a URDF's mesh references are looked for.
#[derive(Debug, Clone, Copy)]
pub struct MeshSearch<'a> {
    /// The URDF's folder.
    pub base: &'a Path,
    /// Extra package folders.
    pub options: &'a ImportOptions,
}

/// The skeleton of URDF text (`path` names it in errors and gives the default category).
pub fn urdf_skeleton(
    path: &Path,
    text: &str,
    search: &MeshSearch,
) -> Result<(Skeleton, Vec<PathBuf>), ImportError> {
    let robot = urdf_rs::read_from_string(text).map_err(|e| parse_error(path, text, e))?;
    let names: Vec<&str> = robot.links.iter().map(|l| l.name.as_str()).collect();
    let ends: Vec<(&str, &str, &str)> = robot
        .joints
        .iter()
        .map(|j| (j.name.as_str(), j.parent.link.as_str(), j.child.link.as_str()))
        .collect();
    let tree = super::skeleton::check_tree(&names, &ends)?;
    // Rest frames, root first: a link's frame needs its parent's.
    let mut frames: Vec<Option<Isometry3<f64>>> = vec![None; names.len()];
    frames[tree.root] = Some(Isometry3::identity());
    let mut joint_frames = vec![Isometry3::identity(); robot.joints.len()];
    let mut pending: Vec<usize> = (0..robot.joints.len()).collect();
    while !pending.is_empty() {
        let before = pending.len();
        pending.retain(|&j| {
            let (parent, child) = tree.ends[j];
            let Some(parent_frame) = frames[parent] else { return true };
            let joint = &robot.joints[j];
            joint_frames[j] = parent_frame * pose(&joint.origin.xyz.0, &joint.origin.rpy.0);
            frames[child] = Some(joint_frames[j]);
            false
        });
        if pending.len() == before {
            // check_tree rules this out; kept so that a bug cannot loop forever.
            return Err(ImportError::Cycle { link: names[tree.root].into() });
        }
    }
    let mut files = Vec::new();
    let mut links = Vec::with_capacity(robot.links.len());
    for (l, link) in robot.links.iter().enumerate() {
        let frame = frames[l].unwrap_or_else(Isometry3::identity);
        let mut mesh = Mesh::default();
        let mut surface = Surface::default();
        for visual in &link.visual {
            let origin = &visual.origin;
            if !finite(&origin.xyz.0) || !finite(&origin.rpy.0) {
                return Err(ImportError::NonFinite {
                    item: link.name.clone(),
                    field: "visual origin",
                });
            }
            let place = frame * pose(&origin.xyz.0, &origin.rpy.0);
            let (m, mut s) = geometry(&link.name, &visual.geometry, &place, search, &mut files)?;
            if let Some(colour) = visual_colour(visual.material.as_ref(), &robot.materials) {
                s = s.with_default(&colour);
            }
            mesh.append(m);
            surface.append(s);
        }
        links.push(RawLink { name: link.name.clone(), mesh, surface });
    }
    let mut joints = Vec::with_capacity(robot.joints.len());
    for (j, joint) in robot.joints.iter().enumerate() {
        if !finite(&joint.origin.xyz.0) || !finite(&joint.origin.rpy.0) {
            return Err(ImportError::NonFinite { item: joint.name.clone(), field: "origin" });
        }
        let kind = RawKind::parse(&joint.name, joint_type(&joint.joint_type))?;
        let frame = joint_frames[j];
        let axis = frame.rotation * V3::from(joint.axis.xyz.0);
        let limits = matches!(kind, RawKind::Revolute | RawKind::Prismatic)
            .then_some((joint.limit.lower, joint.limit.upper));
        joints.push(RawJoint {
            name: joint.name.clone(),
            kind,
            parent: joint.parent.link.clone(),
            child: joint.child.link.clone(),
            origin: frame.translation.vector.into(),
            // A zero or NaN axis stays so under rotation; `assemble` reports it.
            axis: if finite(&joint.axis.xyz.0) { axis.into() } else { joint.axis.xyz.0 },
            limits,
            mimic: joint.mimic.as_ref().map(|m| RawMimic {
                leader: m.joint.clone(),
                multiplier: m.multiplier.unwrap_or(1.0),
                offset: m.offset.unwrap_or(0.0),
            }),
        });
    }
    let category = if robot.name.trim().is_empty() {
        super::obj_groups::category(path, None)
    } else {
        robot.name.clone()
    };
    Ok((Skeleton { category, links, joints }, files))
}

/// The URDF joint type's name.
fn joint_type(t: &urdf_rs::JointType) -> &'static str {
    use urdf_rs::JointType as T;
    match t {
        T::Revolute => "revolute",
        T::Continuous => "continuous",
        T::Prismatic => "prismatic",
        T::Fixed => "fixed",
        T::Floating => "floating",
        T::Planar => "planar",
        T::Spherical => "spherical",
    }
}

/// A parse failure; an unknown joint type gets its own typed error.
fn parse_error(path: &Path, text: &str, e: urdf_rs::UrdfError) -> ImportError {
    let reason = e.to_string();
    if let Some(found) = unknown_variant(&reason) {
        if let Some(joint) = joint_with_type(text, found) {
            return ImportError::UnknownJointType { joint, found: found.into() };
        }
    }
    ImportError::Parse { path: path.into(), format: "URDF", reason }
}

/// The variant serde names in "unknown variant `x`, expected ...".
fn unknown_variant(reason: &str) -> Option<&str> {
    let rest = reason.split_once("unknown variant `")?.1;
    Some(rest.split_once('`')?.0)
}

/// The name of the first `<joint>` whose `type` attribute is `kind`, from the raw text.
fn joint_with_type(text: &str, kind: &str) -> Option<String> {
    text.split("<joint").skip(1).find_map(|element| {
        let head = element.split('>').next()?;
        let attribute = |key: &str| {
            let rest = head.split_once(&format!("{key}=\""))?.1;
            Some(rest.split_once('"')?.0.to_string())
        };
        (attribute("type")?.trim() == kind).then(|| attribute("name")).flatten()
    })
}

/// The isometry of a URDF `origin`: translation `xyz`, rotation `rpy` (roll about x, then
/// pitch about y, then yaw about z, all about fixed axes).
pub fn pose(xyz: &[f64; 3], rpy: &[f64; 3]) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(xyz[0], xyz[1], xyz[2]),
        UnitQuaternion::from_euler_angles(rpy[0], rpy[1], rpy[2]),
    )
}

fn finite(v: &[f64]) -> bool {
    v.iter().all(|c| c.is_finite())
}

/// One visual's geometry placed by `place` in the rest frame.
/// The colour of a visual's `<material>`: its own `<color rgba>`, or that of the robot's
/// material of the same name.
fn visual_colour(
    material: Option<&urdf_rs::Material>,
    robot: &[urdf_rs::Material],
) -> Option<Arc<SurfaceMaterial>> {
    let material = material?;
    let color = material
        .color
        .as_ref()
        .or_else(|| robot.iter().find(|m| m.name == material.name)?.color.as_ref())?;
    let rgba = color.rgba.0;
    if !finite(&rgba) {
        return None;
    }
    Some(Arc::new(SurfaceMaterial {
        name: material.name.clone(),
        colour: [rgba[0], rgba[1], rgba[2]].map(|c| c.clamp(0.0, 1.0) as f32),
        texture: None,
    }))
}

/// A visual's geometry placed by `place` (mesh file, box, cylinder, capsule or sphere),
/// with its surface.
fn geometry(
    link: &str,
    geometry: &urdf_rs::Geometry,
    place: &Isometry3<f64>,
    search: &MeshSearch,
    files: &mut Vec<PathBuf>,
) -> Result<(Mesh, Surface), ImportError> {
    use urdf_rs::Geometry as G;
    let positive = |values: &[f64]| {
        if values.iter().all(|v| v.is_finite() && *v > 0.0) {
            Ok(())
        } else {
            Err(ImportError::EmptyMesh { link: link.into() })
        }
    };
    let mut file_surface = None;
    let (local, scale) = match geometry {
        G::Mesh { filename, scale } => {
            let file = resolve(link, filename, search)?;
            let (mesh, surface) = read_mesh_file(link, &file)?;
            file_surface = Some(surface);
            files.push(file);
            let scale = scale.map_or([1.0; 3], |s| s.0);
            if !finite(&scale) {
                return Err(ImportError::NonFinite { item: link.into(), field: "mesh scale" });
            }
            (mesh, scale)
        }
        G::Box { size } => {
            positive(&size.0)?;
            let h = size.0.map(|s| (s * 0.5) as Real);
            (Mesh::cuboid(Point3::new(-h[0], -h[1], -h[2]), Point3::from(h)), [1.0; 3])
        }
        G::Cylinder { radius, length } => {
            positive(&[*radius, *length])?;
            let h = (*length * 0.5) as Real;
            let (a, b) = (Point3::new(0.0, 0.0, -h), Point3::new(0.0, 0.0, h));
            (Mesh::cylinder(a, b, *radius as Real, SEGMENTS), [1.0; 3])
        }
        G::Capsule { radius, length } => {
            positive(&[*radius, *length])?;
            let (h, r) = ((*length * 0.5) as Real, *radius as Real);
            let (a, b) = (Point3::new(0.0, 0.0, -h), Point3::new(0.0, 0.0, h));
            let parts = [
                Mesh::cylinder(a, b, r, SEGMENTS),
                Mesh::sphere(a, r, SEGMENTS),
                Mesh::sphere(b, r, SEGMENTS),
            ];
            (Mesh::union(parts), [1.0; 3])
        }
        G::Sphere { radius } => {
            positive(&[*radius])?;
            (Mesh::sphere(Point3::origin(), *radius as Real, SEGMENTS), [1.0; 3])
        }
    };
    let surface = file_surface.unwrap_or_else(|| Surface::plain(&local.vertices, &local.triangles));
    let mut mesh = local;
    let transform = |v: &Point3| {
        let scaled = P3::new(
            f64::from(v.x) * scale[0],
            f64::from(v.y) * scale[1],
            f64::from(v.z) * scale[2],
        );
        (place * scaled).cast::<Real>()
    };
    for v in &mut mesh.vertices {
        *v = transform(v);
    }
    let mirror = scale.iter().product::<f64>() < 0.0;
    if mirror {
        // A mirroring scale turns the triangles inside out.
        mesh.triangles.iter_mut().for_each(|t| t.swap(1, 2));
    }
    Ok((mesh, surface.map(transform, mirror)))
}

/// The file a mesh reference names: `package://name/rest`, `file://path`, an absolute
/// path, or a path relative to the URDF (see [`ImportOptions::package_paths`]).
fn resolve(link: &str, reference: &str, search: &MeshSearch) -> Result<PathBuf, ImportError> {
    let mut tried = Vec::new();
    let extra = search.options.package_paths.iter().map(PathBuf::as_path);
    if let Some(rest) = reference.strip_prefix("package://") {
        let (package, inner) = rest.split_once('/').unwrap_or((rest, ""));
        let bases = extra.chain([search.base]).chain(search.base.parent());
        for base in bases {
            tried.push(base.join(package).join(inner));
            tried.push(base.join(inner));
        }
    } else {
        let plain = reference.strip_prefix("file://").unwrap_or(reference);
        let path = Path::new(plain);
        if path.is_absolute() {
            tried.push(path.into());
        } else {
            tried.push(search.base.join(path));
            tried.extend(extra.map(|b| b.join(path)));
        }
    }
    match tried.iter().find(|p| p.is_file()) {
        Some(found) => Ok(found.clone()),
        None => {
            Err(ImportError::MissingMesh { link: link.into(), reference: reference.into(), tried })
        }
    }
}
