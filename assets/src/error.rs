//! Why an asset could not be imported. Every variant names what broke (the file, the link,
//! the joint or the field) so that the message alone tells the user what to fix.

use std::path::PathBuf;

use articulated::objects::ObjectError;

/// An asset that cannot become an articulated object.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ImportError {
    /// A file could not be read (missing, unreadable). Fix: check the path.
    #[error("reading {path}: {error}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's error (in the message, so that a manifest's error text
        /// is complete on its own).
        error: std::io::Error,
    },
    /// A text file (URDF, OBJ, sidecar, glTF JSON) is not UTF-8; names must be UTF-8.
    #[error("{path} is not UTF-8 text (first bad byte at offset {offset})")]
    NotUtf8 {
        /// The file.
        path: PathBuf,
        /// Byte offset of the first invalid sequence.
        offset: usize,
    },
    /// A file does not parse as its format.
    #[error("{path}: not valid {format}: {reason}")]
    Parse {
        /// The file.
        path: PathBuf,
        /// `URDF`, `OBJ`, `STL`, `glTF`, `GLB` or `joints sidecar`.
        format: &'static str,
        /// The parser's message.
        reason: String,
    },
    /// The file's extension is not one of `.urdf`, `.obj`, `.gltf`, `.glb`.
    #[error("{path}: unknown asset format (expected .urdf, .obj with a .joints.json sidecar, .gltf or .glb)")]
    UnknownFormat {
        /// The file.
        path: PathBuf,
    },
    /// An OBJ asset has no `<name>.joints.json` next to it.
    #[error("{path}: no joints sidecar {sidecar} (docs/FORMAT.md, \"Joints sidecar\")")]
    MissingSidecar {
        /// The OBJ file.
        path: PathBuf,
        /// Where the sidecar was looked for.
        sidecar: PathBuf,
    },
    /// A link's mesh file does not exist at any place it was looked for.
    #[error("link {link:?}: mesh {reference:?} not found (tried {tried:?})")]
    MissingMesh {
        /// The link.
        link: String,
        /// The file name as the asset gives it.
        reference: String,
        /// Every path tried.
        tried: Vec<PathBuf>,
    },
    /// A link's mesh file exists but cannot be read: an unsupported format (DAE, PLY, ...)
    /// or a broken file. Fix: convert the mesh to OBJ or STL.
    #[error("link {link:?}: cannot read mesh {file}: {reason}")]
    MeshFile {
        /// The link.
        link: String,
        /// The mesh file.
        file: PathBuf,
        /// What is wrong.
        reason: String,
    },
    /// A link (or part, or node) has no triangles once its fixed children are welded in.
    #[error("link {link:?} has no triangles")]
    EmptyMesh {
        /// The link.
        link: String,
    },
    /// A joint type this generator does not know (`ball`, a typo).
    #[error(
        "joint {joint:?}: unknown joint type {found:?} (revolute, continuous, prismatic or fixed)"
    )]
    UnknownJointType {
        /// The joint.
        joint: String,
        /// The type given.
        found: String,
    },
    /// A known joint type the model cannot represent (`floating`, `planar`, `spherical`).
    #[error(
        "joint {joint:?}: type {kind} is not supported (revolute, continuous, prismatic or fixed)"
    )]
    UnsupportedJoint {
        /// The joint.
        joint: String,
        /// The type given.
        kind: String,
    },
    /// A joint record lacks a field its type needs (`axis`, `parent`, `child`).
    #[error("joint {joint:?}: missing field `{field}`")]
    MissingField {
        /// The joint.
        joint: String,
        /// The field.
        field: &'static str,
    },
    /// A joint names a link (part, node) that does not exist.
    #[error("joint {joint:?}: no link called {link:?}")]
    UnknownLink {
        /// The joint.
        joint: String,
        /// The missing name.
        link: String,
    },
    /// Two links or two joints share a name.
    #[error("two {what}s are called {name:?}")]
    DuplicateName {
        /// `link` or `joint`.
        what: &'static str,
        /// The name.
        name: String,
    },
    /// A link is the child of two joints.
    #[error("link {link:?} is the child of two joints, {first:?} and {second:?}")]
    MultipleParents {
        /// The link.
        link: String,
        /// One joint.
        first: String,
        /// The other.
        second: String,
    },
    /// The joints form a cycle: following parents from this link comes back to it.
    #[error("the joint graph has a cycle through link {link:?}")]
    Cycle {
        /// A link on the cycle.
        link: String,
    },
    /// Not exactly one link is without a parent joint.
    #[error("expected one root link (a link that is no joint's child), found {roots:?}")]
    Roots {
        /// The links without a parent joint.
        roots: Vec<String>,
    },
    /// A number that must be finite is NaN or infinite.
    #[error("{item:?}: {field} is not finite")]
    NonFinite {
        /// The joint, link or mesh.
        item: String,
        /// The field (`axis`, `origin`, `lower`, `vertex`, ...).
        field: &'static str,
    },
    /// A moving joint's axis has (almost) zero length.
    #[error("joint {joint:?}: the axis has zero length")]
    ZeroAxis {
        /// The joint.
        joint: String,
    },
    /// A revolute or prismatic joint without limits, or with `lower >= upper`.
    #[error("joint {joint:?}: limits [{lower}, {upper}] are missing or not increasing")]
    BadLimits {
        /// The joint.
        joint: String,
        /// Lower limit given (0 when absent).
        lower: f64,
        /// Upper limit given (0 when absent).
        upper: f64,
    },
    /// A mimic joint that cannot be followed (unknown, fixed, or a cycle of mimics).
    #[error("joint {joint:?}: mimic {reason}")]
    Mimic {
        /// The following joint.
        joint: String,
        /// What is wrong.
        reason: String,
    },
    /// A glTF buffer is missing, claims more bytes than it holds, or cannot be decoded.
    #[error("glTF buffer {index}: {reason}")]
    Buffer {
        /// Buffer index.
        index: usize,
        /// What is wrong.
        reason: String,
    },
    /// A glTF mesh's accessor does not fit its buffer or has the wrong type.
    #[error("glTF node {node:?}: {reason}")]
    Accessor {
        /// The node whose mesh it is.
        node: String,
        /// What is wrong.
        reason: String,
    },
    /// The import options are unusable.
    #[error("import options: {0}")]
    Options(String),
    /// The assembled object breaks the model's rules.
    #[error(transparent)]
    Object(#[from] ObjectError),
}
