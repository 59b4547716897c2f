//! Whether a point on a posed object is seen by a camera: inside the image, the first
//! surface along its ray, met from the front, and (optionally) not lost by the scanner.

use pairs::math::{Point3, Real};

use super::camera::Camera;
use super::scene::PosedScene;

/// Whether `point` (object frame, on or near the surface of `scene`) is visible from
/// `camera`: its pixel lies in the image and is not marked in `lost`, and the ray from the
/// camera towards it first meets a front face within `tolerance` of it.
pub fn is_visible(
    scene: &PosedScene,
    camera: &Camera,
    point: &Point3,
    tolerance: Real,
    lost: Option<&[bool]>,
) -> bool {
    let Some((u, v, _)) = camera.project(point) else {
        return false;
    };
    let Some((px, py)) = camera.intrinsics.pixel(u, v) else {
        return false;
    };
    if lost.is_some_and(|lost| lost[(py * camera.intrinsics.width + px) as usize]) {
        return false;
    }
    let offset = point - camera.centre();
    let distance = offset.norm();
    if distance <= tolerance {
        return false;
    }
    match scene.cast(&camera.centre(), &(offset / distance), distance + tolerance) {
        Some(hit) => !hit.back && (hit.distance - distance).abs() <= tolerance,
        None => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use articulated::mesh::Mesh;
    use articulated::objects::{ArticulatedObject, Link};
    use pairs::math::Isometry3;
    use pairs::Intrinsics;

    #[test]
    fn front_faces_are_visible_and_hidden_ones_are_not() {
        let cube = Mesh::cuboid(Point3::new(-0.5, -0.5, -0.5), Point3::new(0.5, 0.5, 0.5));
        let object = ArticulatedObject::new("test", Link { name: "cube".into(), mesh: cube });
        let scene = PosedScene::new(&object, &[Isometry3::identity()]).expect("scene");
        let k = Intrinsics::with_fov(64, 64, 1.2);
        let camera = Camera::look_at(k, &Point3::new(0.0, 0.0, 3.0), &Point3::origin());
        let front = Point3::new(0.1, 0.2, 0.5);
        let back = Point3::new(0.1, 0.2, -0.5);
        assert!(is_visible(&scene, &camera, &front, 1e-3, None));
        assert!(!is_visible(&scene, &camera, &back, 1e-3, None));
        let mut lost = vec![false; 64 * 64];
        let (u, v, _) = camera.project(&front).expect("in front");
        let (px, py) = camera.intrinsics.pixel(u, v).expect("in the image");
        lost[(py * 64 + px) as usize] = true;
        assert!(!is_visible(&scene, &camera, &front, 1e-3, Some(&lost)));
        let off_image =
            Camera::look_at(k, &Point3::new(0.0, 0.0, 3.0), &Point3::new(9.0, 0.0, 0.0));
        assert!(!is_visible(&scene, &off_image, &front, 1e-3, None));
    }
}
