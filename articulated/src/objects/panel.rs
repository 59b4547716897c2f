//! Framed panels: a border frame around a recessed pane, the glazed doors of ovens and
//! microwaves and the sashes of windows.

use pairs::math::{Point3, Real};

use crate::mesh::Mesh;

/// A panel over `x0..x1`, `y0..y1`, from `z0` to `z0 + thickness`: four rails whose
/// widths are `border` (left, right, bottom, top) around a pane `pane` thick, set back
/// from the frame's front face.
pub fn framed_panel(
    (x0, x1): (Real, Real),
    (y0, y1): (Real, Real),
    z0: Real,
    thickness: Real,
    border: [Real; 4],
    pane: Real,
) -> Mesh {
    let [left, right, bottom, top] = border;
    let z1 = z0 + thickness;
    let (ix0, ix1, iy0, iy1) = (x0 + left, x1 - right, y0 + bottom, y1 - top);
    let zp = z0 + 0.5 * (thickness - pane);
    Mesh::union([
        Mesh::cuboid(Point3::new(x0, y0, z0), Point3::new(x1, iy0, z1)),
        Mesh::cuboid(Point3::new(x0, iy1, z0), Point3::new(x1, y1, z1)),
        Mesh::cuboid(Point3::new(x0, iy0, z0), Point3::new(ix0, iy1, z1)),
        Mesh::cuboid(Point3::new(ix1, iy0, z0), Point3::new(x1, iy1, z1)),
        Mesh::cuboid(Point3::new(ix0, iy0, zp), Point3::new(ix1, iy1, zp + pane)),
    ])
}
