//! What a hit is on, in the scene's own words: the object (a glTF model's node), its shape (a
//! glTF mesh's primitive, an OBJ file's group), its material, the triangle of a mesh and where
//! on it, and each texture the hit reads: the image, the coordinates it reads there and the
//! level of detail the ray's cone picks, found by the same shared code as the stages'
//! (`twinray_shared::texture`). The coordinates are in f64: on a mesh from the triangle's
//! barycentrics at the hit, on a procedural shape from the reference's own parametrisation
//! (`reference::uv`).

use crate::reference::shapes::from_primitive;
use crate::reference::uv::uv as reference_uv;
use crate::scene::{BlasDesc, Scene, SceneData};
use glam::{DVec2, DVec3, Mat3, Vec2, Vec4};
use serde::Serialize;
use twinray_shared::layout::{Material, Vertex};
use twinray_shared::shapes::{self, SHAPE_NAIVE};
use twinray_shared::texture::{self, TriangleHit};

/// What a hit is on.
#[derive(Clone, Debug, Serialize)]
pub struct Surface {
    /// The object's name (`name` in the scene file, a glTF node's), else `object #i`.
    pub object: String,
    pub shape: String,
    pub material: String,
    /// The triangle of a mesh, and the barycentrics of its second and third corner there
    /// (`None` for a procedural shape).
    pub triangle: Option<u32>,
    pub barycentrics: Option<[f64; 2]>,
    pub textures: Vec<Texel>,
}

/// One texture a hit reads.
#[derive(Clone, Debug, Serialize)]
pub struct Texel {
    /// "base colour" or "emission".
    pub role: &'static str,
    /// The image: its file, or its glTF model and index.
    pub file: String,
    pub uv_set: u32,
    /// The coordinates read, through the material's transform.
    pub uv: [f64; 2],
    /// The level of detail its taps sample (0: the image itself), clamped to the image's
    /// levels: as Vulkan picks it from the gradients the stage passes.
    pub level: f32,
    /// How many samples along the footprint's long axis the stage takes.
    pub taps: u32,
}

/// Where a ray met an object: the object, the triangle of a mesh the hit is on (as the set
/// reported it, or as the reference found it), the world-space point, and the ray's direction
/// and t (which give the cone's width there).
pub struct Hit {
    pub object: usize,
    pub triangle: Option<usize>,
    pub point: DVec3,
    pub direction: DVec3,
    pub t: f64,
}

/// What `hit` is on in `scene` (built as `data`), its primary ray's cone spreading by `spread`
/// radians (0: level 0).
pub fn surface(scene: &Scene, data: &SceneData, spread: f32, hit: &Hit) -> Option<Surface> {
    let desc = scene.file.objects.get(hit.object)?;
    let instance = data.instances.get(hit.object)?;
    let object = desc.name.clone().unwrap_or_else(|| format!("object #{}", hit.object));
    let (shape, material_name) = (desc.shape.clone(), desc.material.clone());
    let mut out =
        Surface { object, shape, material: material_name, triangle: None, barycentrics: None, textures: vec![] };
    let BlasDesc::Triangles { .. } = data.blases.get(instance.blas)? else {
        out.textures = shape_texels(data, spread, hit, instance.custom_index).unwrap_or_default();
        return Some(out);
    };
    let data_object = data.objects[hit.object];
    let k = hit.triangle?;
    let first = (data_object.index_base + 3 * k as u32) as usize;
    let corner =
        |j: usize| data.indices.get(first + j).and_then(|&i| data.vertices.get((data_object.vertex_base + i) as usize));
    let v: [Vertex; 3] = [*corner(0)?, *corner(1)?, *corner(2)?];
    let to_object = instance.object_to_world.as_dmat4().inverse();
    let b = barycentrics(&v, to_object.transform_point3(hit.point));
    (out.triangle, out.barycentrics) = (Some(k as u32), Some(b.to_array()));
    let material = data.materials[data_object.material as usize];
    let cone = TriangleHit {
        object_to_world: Mat3::from_mat4(instance.object_to_world),
        positions: v.map(|x| x.position.truncate()),
        barycentrics: b.as_vec2(),
        direction: hit.direction.as_vec3().normalize(),
        width: spread * hit.t as f32,
    };
    out.textures = texels(data, &material, |set| {
        let footprint = texture::footprint(&cone, texture::triangle_uv(&material, &v, set));
        (footprint, at_f64(&material, &v, set, b))
    });
    Some(out)
}

/// The textures `material` reads at a hit: for each (base colour, emission), its image, the
/// coordinates read (in f64) and the level its taps sample, from `read(set)`: the footprint of
/// the cone the stages compute for the texture's coordinate set, and the coordinates in f64.
fn texels(data: &SceneData, material: &Material, read: impl Fn(u32) -> ((Vec2, Vec2, Vec2), DVec2)) -> Vec<Texel> {
    let mut out = Vec::new();
    for (role, slot, set) in
        [("base colour", material.texture.x, material.texture.y), ("emission", material.texture.z, material.texture.w)]
    {
        if slot == 0 {
            continue;
        }
        let Some((image, sampler)) = data.textures.get(slot as usize - 1) else { continue };
        let ((at, dx, dy), uv) = read(set);
        let taps = texture::taps(at, dx, dy);
        let size = Vec2::new(image.width as f32, image.height as f32);
        let rho = (taps.dx * size).length().max((taps.dy * size).length());
        let levels = if sampler.mipmap.is_some() { image.width.max(image.height).ilog2() } else { 0 };
        let level = if rho > 0.0 { rho.log2().clamp(0.0, levels as f32) } else { 0.0 };
        out.push(Texel { role, file: image.name.clone(), uv_set: set, uv: uv.to_array(), level, taps: taps.count });
    }
    out
}

/// The textures a hit on a procedural shape reads: its coordinates from the f64 reference's
/// parametrisation at the point (`reference::uv`), the level from the stages' shared code with
/// the normal of the piece the reference puts the point on. `None` where the hit's primitive
/// or shape is unknown.
fn shape_texels(data: &SceneData, spread: f32, hit: &Hit, primitive_base: u32) -> Option<Vec<Texel>> {
    let object = data.objects.get(hit.object)?;
    let primitive = *data.primitives.get(primitive_base as usize + hit.triangle?)?;
    let kind = object.shape & !SHAPE_NAIVE;
    let name = twinray_shared::shapes::SHAPES.iter().find(|s| s.hit_kind == kind)?.name;
    let reference = from_primitive(name, &primitive)?;
    let instance = data.instances.get(hit.object)?;
    let world_to_object = instance.object_to_world.as_dmat4().inverse();
    let p = world_to_object.transform_point3(hit.point);
    let (uv, normal) = reference_uv(&reference, p)?;
    let material = data.materials[object.material as usize];
    let s = shapes::shape_uv(kind, &primitive, p.as_vec3(), normal.as_vec3());
    let to_object = (Mat3::from_mat4(instance.object_to_world).inverse(), hit.direction.as_vec3().normalize());
    let footprint =
        texture::shape_footprint(&material, &s, (normal.as_vec3(), to_object.0), to_object.1, spread * hit.t as f32);
    Some(texels(data, &material, |_| (footprint, transform_f64(&material, uv))))
}

/// The barycentrics of vertices 1 and 2 at `p`, a point in (or near) the triangle's plane.
fn barycentrics(v: &[Vertex; 3], p: DVec3) -> DVec2 {
    let [p0, p1, p2] = v.map(|x| x.position.truncate().as_dvec3());
    let (e1, e2, w) = (p1 - p0, p2 - p0, p - p0);
    let (d00, d01, d11, d20, d21) = (e1.dot(e1), e1.dot(e2), e2.dot(e2), w.dot(e1), w.dot(e2));
    let denominator = d00 * d11 - d01 * d01;
    if denominator == 0.0 {
        return DVec2::ZERO;
    }
    DVec2::new((d11 * d20 - d01 * d21) / denominator, (d00 * d21 - d01 * d20) / denominator)
}

/// The texture coordinates at barycentrics `b` in f64: each corner's set `set` through the
/// material's transform, interpolated.
fn at_f64(material: &Material, v: &[Vertex; 3], set: u32, b: DVec2) -> DVec2 {
    let corner = |x: &Vertex| {
        let uv = if set == 1 {
            DVec2::new(f64::from(x.uv.z), f64::from(x.uv.w))
        } else {
            x.uv.truncate().truncate().as_dvec2()
        };
        transform_f64(material, uv)
    };
    corner(&v[0]) * (1.0 - b.x - b.y) + corner(&v[1]) * b.x + corner(&v[2]) * b.y
}

/// `uv` through the material's texture coordinate transform, in f64.
fn transform_f64(material: &Material, uv: DVec2) -> DVec2 {
    let row = |r: Vec4| r.truncate().truncate().as_dvec2().dot(uv) + f64::from(r.z);
    DVec2::new(row(material.uv_u), row(material.uv_v))
}

/// The surface in words: "node 1 \"Cube\" (shape ..., material ...), triangle 5 at
/// barycentrics (0.25, 0.5); base colour texture F (uv set 0) at uv (0.1, 0.2), level 1.30 in
/// 2 taps".
pub fn words(s: &Surface) -> String {
    let mut out = format!("on {} (shape {:?}, material {:?})", s.object, s.shape, s.material);
    if let (Some(t), Some([u, v])) = (s.triangle, s.barycentrics) {
        out += &format!(", triangle {t} at barycentrics ({u:.6}, {v:.6})");
    }
    for t in &s.textures {
        out += &format!(
            "; {} texture {} (uv set {}) at uv ({:.6}, {:.6}), level {:.2} in {} tap(s)",
            t.role, t.file, t.uv_set, t.uv[0], t.uv[1], t.level, t.taps
        );
    }
    out
}
