//! Each shape kind's equivalent in Mitsuba 3, for `twinray crosscheck` (twinray's guide, *Shading model*):
//! one of Mitsuba's own shapes placed in the shape's object space, or, for shapes Mitsuba
//! lacks, a fine triangle mesh with the exact normals at its vertices.

use glam::{Mat4, Vec3};

/// One part of a shape as Mitsuba draws it.
#[derive(Clone, Debug, PartialEq)]
pub struct MitsubaPart {
    /// Which Mitsuba shape it is.
    pub kind: MitsubaKind,
    /// Maps the Mitsuba shape's own space into the twinray shape's object space.
    pub to_object: Mat4,
    /// Multiplies the material's albedo (a `sphere_field` sphere's colour; else white).
    pub tint: Vec3,
}

/// Mitsuba's shapes, in their own spaces.
#[derive(Clone, Debug, PartialEq)]
pub enum MitsubaKind {
    /// `sphere`: radius 1 about the origin. Mitsuba takes no non-uniform scale of it.
    Sphere,
    /// `rectangle`: [-1, 1]^2 in the xy plane, facing +z.
    Rectangle,
    /// `disk`: radius 1 in the xy plane, facing +z.
    Disk,
    /// `cube`: [-1, 1]^3.
    Cube,
    /// `cylinder`: radius 1 about z from z = 0 to 1, open. Mitsuba takes no scale that makes
    /// its cross-section an ellipse.
    Cylinder,
    /// A triangle mesh, written as a PLY file.
    Mesh(TriangleMesh),
}

/// Triangles with a normal at every vertex (interpolated across each triangle, as Mitsuba
/// shades a mesh with vertex normals).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriangleMesh {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Unit normals, one per vertex.
    pub normals: Vec<Vec3>,
    /// Vertex indices of each triangle, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
}

impl MitsubaPart {
    /// A part of white tint.
    pub fn new(kind: MitsubaKind, to_object: Mat4) -> MitsubaPart {
        MitsubaPart { kind, to_object, tint: Vec3::ONE }
    }
}

/// Segments around the axis of a tessellated surface of revolution: the largest gap between
/// the mesh and the surface is 1 - cos(pi / 1024), 5e-6 of the radius.
pub const AROUND: u32 = 1024;
/// Segments along a curved profile (a sphere's meridian, a torus's tube).
pub const ALONG: u32 = 512;

/// One point of a profile in the (rho, y) half-plane, rho the distance from the y axis, with
/// the surface's unit normal there in the same plane.
#[derive(Clone, Copy, Debug)]
pub struct ProfilePoint {
    /// Distance from the y axis.
    pub rho: f32,
    /// Height.
    pub y: f32,
    /// The normal's component away from the y axis.
    pub normal_rho: f32,
    /// The normal's component along y.
    pub normal_y: f32,
}

/// The surface swept by turning `profile` (consecutive points joined) about the y axis in
/// `AROUND` steps. Ring pairs where one ring is on the axis become fans, so no triangle has
/// zero area.
pub fn lathe(profile: &[ProfilePoint]) -> TriangleMesh {
    let mut mesh = TriangleMesh::default();
    let ring = AROUND + 1;
    for p in profile {
        for k in 0..ring {
            let phi = std::f32::consts::TAU * k as f32 / AROUND as f32;
            let (s, c) = phi.sin_cos();
            mesh.positions.push(Vec3::new(p.rho * c, p.y, p.rho * s));
            mesh.normals.push(Vec3::new(p.normal_rho * c, p.normal_y, p.normal_rho * s).normalize());
        }
    }
    for (i, pair) in profile.windows(2).enumerate() {
        let (a, b) = (i as u32 * ring, (i as u32 + 1) * ring);
        for k in 0..AROUND {
            if pair[0].rho != 0.0 {
                mesh.triangles.push([a + k, b + k, a + k + 1]);
            }
            if pair[1].rho != 0.0 {
                mesh.triangles.push([a + k + 1, b + k, b + k + 1]);
            }
        }
    }
    mesh
}

/// A flat disk of `radius` at height `y`, its normal along `normal_y` (+1 or -1).
pub fn cap(radius: f32, y: f32, normal_y: f32) -> TriangleMesh {
    let point = |rho| ProfilePoint { rho, y, normal_rho: 0.0, normal_y };
    lathe(&[point(0.0), point(radius)])
}

/// The unit sphere.
pub fn unit_sphere() -> TriangleMesh {
    let profile: Vec<ProfilePoint> = (0..=ALONG)
        .map(|i| {
            let theta = std::f32::consts::PI * i as f32 / ALONG as f32;
            let (rho, y) = if i == 0 || i == ALONG { (0.0, theta.cos().round()) } else { theta.sin_cos() };
            ProfilePoint { rho, y, normal_rho: rho, normal_y: y }
        })
        .collect();
    lathe(&profile)
}

/// Mitsuba's cylinder (radius 1 about z from 0 to 1) as a mesh with its two caps: for a
/// cylinder under a scale Mitsuba's own cannot take.
pub fn unit_cylinder() -> TriangleMesh {
    let side = |y| ProfilePoint { rho: 1.0, y, normal_rho: 1.0, normal_y: 0.0 };
    let mut mesh = lathe(&[side(0.0), side(1.0)]);
    mesh.append(cap(1.0, 0.0, -1.0));
    mesh.append(cap(1.0, 1.0, 1.0));
    // Turned from about y (as `lathe` makes it) to about z, as Mitsuba's cylinder is: y -> z,
    // z -> -y keeps the orientation.
    let turn = |v: Vec3| Vec3::new(v.x, -v.z, v.y);
    mesh.positions.iter_mut().for_each(|p| *p = turn(*p));
    mesh.normals.iter_mut().for_each(|n| *n = turn(*n));
    mesh
}

impl TriangleMesh {
    /// Adds `other`'s triangles.
    pub fn append(&mut self, other: TriangleMesh) {
        let base = self.positions.len() as u32;
        self.positions.extend(other.positions);
        self.normals.extend(other.normals);
        self.triangles.extend(other.triangles.into_iter().map(|t| t.map(|i| i + base)));
    }

    /// The mesh moved by `m` (normals by its inverse transpose).
    pub fn transformed(&self, m: Mat4) -> TriangleMesh {
        let normal_matrix = glam::Mat3::from_mat4(m).inverse().transpose();
        TriangleMesh {
            positions: self.positions.iter().map(|p| m.transform_point3(*p)).collect(),
            normals: self.normals.iter().map(|n| (normal_matrix * *n).normalize()).collect(),
            triangles: self.triangles.clone(),
        }
    }
}

/// Maps Mitsuba's xy plane (facing +z) to the plane y = `y` of the object, scaled to half
/// extents `hx` along x and `hz` along z, facing +y (`up`) or -y.
pub fn flat(hx: f32, hz: f32, y: f32, up: bool) -> Mat4 {
    let sign = if up { 1.0 } else { -1.0 };
    // x -> x, y -> -z (or +z), z -> +y (or -y): a rotation, so the facing follows.
    Mat4::from_cols(
        glam::Vec4::new(hx, 0.0, 0.0, 0.0),
        glam::Vec4::new(0.0, 0.0, -sign * hz, 0.0),
        glam::Vec4::new(0.0, sign, 0.0, 0.0),
        glam::Vec4::new(0.0, y, 0.0, 1.0),
    )
}

/// A rectangle or disk in the object's xz plane, facing +y.
pub fn plane(kind: MitsubaKind, hx: f32, hz: f32) -> Vec<MitsubaPart> {
    vec![MitsubaPart::new(kind, flat(hx, hz, 0.0, true))]
}

/// A box of half extents `half` about the origin.
pub fn cube(half: Vec3) -> Vec<MitsubaPart> {
    vec![MitsubaPart::new(MitsubaKind::Cube, Mat4::from_scale(half))]
}

/// Spheres at the primitives' centres (`a.xyz`) with their radii (`a.w`) and tints.
pub fn spheres<'a>(primitives: impl IntoIterator<Item = &'a crate::layout::Primitive>) -> Vec<MitsubaPart> {
    use glam::Vec4Swizzles;
    primitives
        .into_iter()
        .map(|p| MitsubaPart {
            kind: MitsubaKind::Sphere,
            to_object: Mat4::from_translation(p.a.xyz()) * Mat4::from_scale(Vec3::splat(p.a.w)),
            tint: p.tint.xyz(),
        })
        .collect()
}

/// A cylinder of `radius` about y from -`half_height` to +`half_height`, capped: Mitsuba's
/// open cylinder and two disks.
pub fn capped_cylinder(radius: f32, half_height: f32) -> Vec<MitsubaPart> {
    let (r, h) = (radius, half_height);
    // z in [0, 1] -> y in [-h, h]; x -> x, y -> -z: a rotation and scales, so it faces out.
    let side = Mat4::from_cols(
        glam::Vec4::new(r, 0.0, 0.0, 0.0),
        glam::Vec4::new(0.0, 0.0, -r, 0.0),
        glam::Vec4::new(0.0, 2.0 * h, 0.0, 0.0),
        glam::Vec4::new(0.0, -h, 0.0, 1.0),
    );
    vec![
        MitsubaPart::new(MitsubaKind::Cylinder, side),
        MitsubaPart::new(MitsubaKind::Disk, flat(r, r, h, true)),
        MitsubaPart::new(MitsubaKind::Disk, flat(r, r, -h, false)),
    ]
}

/// A cone about y, base of `radius` at y = -`half_height` (capped), apex at +`half_height`,
/// as a mesh.
pub fn cone(radius: f32, half_height: f32) -> Vec<MitsubaPart> {
    let (r, h) = (radius, half_height);
    // The side's outward normal in the (rho, y) plane is along (2h, r).
    let n = glam::Vec2::new(2.0 * h, r).normalize();
    let side = |rho, y| ProfilePoint { rho, y, normal_rho: n.x, normal_y: n.y };
    let mut mesh = lathe(&[side(0.0, h), side(r, -h)]);
    mesh.append(cap(r, -h, -1.0));
    vec![MitsubaPart::new(MitsubaKind::Mesh(mesh), Mat4::IDENTITY)]
}

/// A torus about y: ring radius `major` in the xz plane, tube radius `minor`, as a mesh.
pub fn torus(major: f32, minor: f32) -> Vec<MitsubaPart> {
    let profile: Vec<ProfilePoint> = (0..=ALONG)
        .map(|i| {
            let theta = std::f32::consts::TAU * (i % ALONG) as f32 / ALONG as f32;
            let (s, c) = theta.sin_cos();
            ProfilePoint { rho: major + minor * c, y: minor * s, normal_rho: c, normal_y: s }
        })
        .collect();
    vec![MitsubaPart::new(MitsubaKind::Mesh(lathe(&profile)), Mat4::IDENTITY)]
}

/// No Mitsuba equivalent: `crosscheck` refuses scenes that use the kind. Generic over the
/// shape's values, so that this module needs nothing of `spec` (which names its parts).
pub fn none<V>(_: &V) -> Vec<MitsubaPart> {
    Vec::new()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every vertex of the tessellated sphere lies on it, with the radial normal, and no
    /// triangle has zero area (the poles are fans).
    #[test]
    fn the_unit_sphere_mesh_is_on_the_sphere_and_faces_out() {
        let mesh = unit_sphere();
        for (p, n) in mesh.positions.iter().zip(&mesh.normals) {
            assert!((p.length() - 1.0).abs() < 1e-6, "{p}");
            assert!(n.dot(*p) > 0.999_99, "{n} at {p}");
        }
        for t in &mesh.triangles {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            assert!((b - a).cross(c - a).length() > 0.0, "a triangle of zero area at {a}");
        }
    }

    /// The cylinder mesh spans Mitsuba's cylinder: radius 1 about z, z from 0 to 1.
    #[test]
    fn the_unit_cylinder_mesh_is_mitsubas_cylinder() {
        let mesh = unit_cylinder();
        for p in &mesh.positions {
            assert!((-1e-6..=1.0 + 1e-6).contains(&p.z), "{p}");
            assert!(p.truncate().length() <= 1.0 + 1e-6, "{p}");
        }
        let on_side = mesh.positions.iter().filter(|p| (p.truncate().length() - 1.0).abs() < 1e-6).count();
        assert!(on_side >= 2 * AROUND as usize);
    }
}
