//! The local origin: where the GPU's world coordinates are centred. The driver transforms each
//! ray into an instance's space in f32, and a triangle's hit is found in that space: for a ray
//! that starts 1e4 from the world origin and hits an object 10 units away, that transform
//! rounds at the magnitude of 1e4, and t comes back with a relative error of about 3e-4
//! (`probes/far-mesh.toml`, docs/numerics.md). Centred on the camera, the same ray starts near 0
//! and the object lies 10 units out: the driver's rounding is that of 10.
//!
//! Only the GPU's copy moves: objects' translations, the camera and the lights, each
//! `p - origin` computed in f64 and rounded once; rays handed to a probe or `explain` are moved
//! the same way, and hit points moved back. The f64 reference, the scene's checks and every
//! report work in the scene's own coordinates. Where the origin is a point of f32 near what
//! moves, the subtraction is exact (Sterbenz), so the GPU sees the very scene, translated.
//!
//! One origin helps only the rays that start near it: rays 1e4 from it are rounded at 1e4,
//! however near the world origin they start. A render's rays start at the eye, so it is
//! centred there; a probe's rays may start anywhere, so each is launched where it meets what it
//! can hit (`super::launches`), its start moved exactly.

use super::file::{LightDesc, SceneFile};
use glam::{DVec3, Vec3};

/// `p - origin`, in f64, rounded once.
pub fn to_local(p: Vec3, origin: Vec3) -> Vec3 {
    (p.as_dvec3() - origin.as_dvec3()).as_vec3()
}

/// `p + origin`, in f64, rounded once: a point the GPU reported, in the scene's coordinates.
pub fn to_world(p: Vec3, origin: Vec3) -> Vec3 {
    (p.as_dvec3() + origin.as_dvec3()).as_vec3()
}

/// The point of f32 nearest the mean of `points`; `None` for none.
pub fn mean(points: impl IntoIterator<Item = Vec3>) -> Option<Vec3> {
    let (sum, n) = points.into_iter().fold((DVec3::ZERO, 0u64), |(s, n), p| (s + p.as_dvec3(), n + 1));
    (n > 0).then(|| (sum / n as f64).as_vec3())
}

/// `file` as the GPU sees it with its world origin at `origin`: objects, camera and lights
/// moved by `-origin`. Shapes, materials and directions are unchanged.
pub fn rebase(file: &mut SceneFile, origin: Vec3) {
    let local = |p: &mut [f32; 3]| *p = to_local(Vec3::from(*p), origin).into();
    for object in &mut file.objects {
        local(&mut object.translate);
    }
    local(&mut file.camera.eye);
    local(&mut file.camera.target);
    for light in &mut file.lights {
        match light {
            LightDesc::Point { position, .. } => local(position),
            LightDesc::Rect { center, .. } => local(center),
            LightDesc::Directional { .. } => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn near_points_move_exactly_and_come_back() {
        let origin = Vec3::new(10000.0, -10000.0, 9990.0);
        let p = Vec3::new(10000.3, -10000.7, 10000.1);
        let local = to_local(p, origin);
        // Sterbenz: the difference of two f32 within a factor of 2 of each other is exact.
        assert_eq!(local.as_dvec3(), p.as_dvec3() - origin.as_dvec3());
        assert_eq!(to_world(local, origin), p);
    }

    #[test]
    fn the_mean_is_of_f32_and_none_of_nothing() {
        assert_eq!(mean([Vec3::X, Vec3::Y]), Some(Vec3::new(0.5, 0.5, 0.0)));
        assert_eq!(mean(std::iter::empty()), None);
    }
}
