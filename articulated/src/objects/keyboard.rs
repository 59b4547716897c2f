//! Piano keyboards: a keybed with 52 white and 36 black keys between two cheek blocks, in
//! front of a case face, and the fallboard that closes over the keys and folds up against
//! that face.

use pairs::math::{Point3, Real, Vector3};

use super::articulated::Joint;
use crate::mesh::Mesh;

/// Where a keyboard sits: the keys span x from `-half` to `half`, their tops are at height
/// `keys`, they reach `depth` forward from the case face at z = 0, and cheek blocks `cheek`
/// wide flank them.
#[derive(Debug, Clone, Copy)]
pub struct Keyboard {
    /// Half the width of the 52 white keys.
    pub half: Real,
    /// Height of the white keys' tops.
    pub keys: Real,
    /// How far the keys reach in front of the case face.
    pub depth: Real,
    /// Width of each cheek block.
    pub cheek: Real,
}

/// Height of the black keys above the white ones.
const BLACK_RISE: Real = 0.012;
/// How far the keybed reaches in front of the keys.
const KEYBED_LEDGE: Real = 0.03;
/// Depth of the keybed's underside below the keys' tops.
pub const KEYBED_DROP: Real = 0.06;

impl Keyboard {
    /// Keybed, keys and cheeks.
    pub fn mesh(&self) -> Mesh {
        let Keyboard { half, keys, depth, cheek } = *self;
        let front = depth + KEYBED_LEDGE;
        let white = 2.0 * half / 52.0;
        let mut mesh = Mesh::union([
            Mesh::cuboid(
                Point3::new(-half - cheek, keys - KEYBED_DROP, 0.0),
                Point3::new(half + cheek, keys - 0.02, front),
            ),
            Mesh::cuboid(Point3::new(-half, keys - 0.02, 0.0), Point3::new(half, keys, depth)),
        ]);
        for side in [-1.0, 1.0] {
            let (a, b) = (side * half, side * (half + cheek));
            mesh.append(Mesh::cuboid(
                Point3::new(a.min(b), keys - 0.02, 0.0),
                Point3::new(a.max(b), keys + 0.06, front),
            ));
        }
        // Black keys follow the white ones from A0: a sharp after A, C, D, F and G.
        mesh.append(Mesh::union((0..51).filter(|i| [0, 2, 3, 5, 6].contains(&(i % 7))).map(|i| {
            let x = -half + white * (i + 1) as Real;
            Mesh::cuboid(
                Point3::new(x - 0.28 * white, keys, 0.0),
                Point3::new(x + 0.28 * white, keys + BLACK_RISE, 0.6 * depth),
            )
        })));
        mesh
    }

    /// The fallboard: a board `thickness` thick over the keys with a lip down over the front
    /// of the keybed, and the hinge along its back-bottom edge that folds it up against the
    /// case face by `max_angle` (at most a right angle, where it lies flat on the face).
    pub fn fallboard(&self, thickness: Real, max_angle: Real) -> (Mesh, Joint) {
        let Keyboard { half, keys, depth, .. } = *self;
        let (y0, z0) = (keys + BLACK_RISE + 0.01, depth + KEYBED_LEDGE);
        let mesh = Mesh::union([
            Mesh::cuboid(
                Point3::new(-half, y0, thickness),
                Point3::new(half, y0 + thickness, z0 + thickness),
            ),
            Mesh::cuboid(
                Point3::new(-half, keys - KEYBED_DROP, z0),
                Point3::new(half, y0, z0 + thickness),
            ),
        ]);
        (mesh, Joint::hinge(Point3::new(0.0, y0, thickness), -Vector3::x(), max_angle))
    }
}
