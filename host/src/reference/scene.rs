//! The f64 reference for a whole scene: every object's shape in its own space, reached
//! through the inverse of its transform in f64; the first hit over all objects. A ray is
//! ambiguous when any object's answer is, or when two objects' hits are within float noise
//! of each other (which one is first is then rounding).

use super::cutout::{Corners, Coverage, RefCutout};
use super::shapes::{from_primitive, intersect, RefRay, RefShape, Verdict};
use super::texel::RefTexture;
use crate::scene::{BlasDesc, HitGeometry, HitGroup, Scene, SceneData};
use glam::{DMat4, DVec2, DVec3, Vec4Swizzles};
use twinray_shared::custom::Parameters;
use twinray_shared::layout::Material;

/// One object: its shapes in object space and the transforms to and from it.
pub struct RefObject {
    pub shapes: Vec<RefShape>,
    pub world_to_object: DMat4,
    pub object_to_world: DMat4,
    /// Its material's holes, if it is a cutout: a shape's first hit in a hole is ignored (as
    /// the any-hit stage ignores it, and the intersection stage reports no further root).
    pub cutout: Option<RefCutout>,
    /// Its instance mask: shadow rays see only occluders (`MASK_OCCLUDER`).
    pub mask: u32,
    /// What each triangle's corners give the surface's own alpha, where its cutout reads
    /// them (`RefCutout::reads_corners`); empty elsewhere.
    pub corners: Vec<Corners>,
    /// Its triangles seen from behind are culled for primary rays (`ObjectDesc::single_sided`,
    /// as `bindings::PRIMARY_RAY_FLAGS` and the instance's facing flags do on the GPU).
    pub single_sided: bool,
}

/// Which faces a ray sees: a primary ray (and a probe's) skips the back faces of single-sided
/// objects; a shadow ray sees every face, as a surface blocks light whichever way it faces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Faces {
    Front,
    Both,
}

/// The first hit over all objects, in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SceneVerdict {
    /// No object is hit.
    Miss,
    /// `normal`: world-space unit normal facing the ray's origin.
    Hit { object: usize, t: f64, normal: DVec3 },
    /// Within float noise of a boundary, or of a tie between objects: either answer is right.
    Ambiguous,
}

impl RefObject {
    /// Object-space magnitude at which the f32 world-to-object transform of a ray from
    /// `origin` rounds: the largest world coordinate involved (origin or translation) times
    /// the transform's largest stretch.
    fn noise_floor(&self, origin: DVec3) -> f64 {
        let m = &self.world_to_object;
        let stretch = m.x_axis.truncate().length().max(m.y_axis.truncate().length()).max(m.z_axis.truncate().length());
        let world = origin.abs().max_element().max(self.object_to_world.w_axis.truncate().abs().max_element());
        stretch * world
    }
}

impl RefObject {
    /// A world-space ray in this object's own space.
    fn ray(&self, origin: DVec3, direction: DVec3, (t_min, t_max): (f64, f64)) -> RefRay {
        RefRay {
            origin: self.world_to_object.transform_point3(origin),
            direction: self.world_to_object.transform_vector3(direction),
            t_min,
            t_max,
            noise_floor: self.noise_floor(origin),
        }
    }

    /// The true answer for a ray in this object's own space: its first hit over the object's
    /// shapes (the holes of a cutout skipped), with the object-space normal; ambiguous when
    /// any shape's answer is, or the hit is on the edge of a hole.
    pub fn first_hit(&self, ray: &RefRay, faces: Faces) -> Verdict {
        match self.first_shape(ray, faces) {
            None => Verdict::Ambiguous,
            Some(None) => Verdict::Miss,
            Some(Some((_, t, normal))) => Verdict::Hit { t, normal },
        }
    }

    /// Which of the object's shapes (a mesh's triangle, by index) `ray` meets first, at what t
    /// and object-space normal: `Some(None)` for none, `None` where the answer is ambiguous.
    /// Triangles ambiguous alone (the ray passes within noise of their edges) are decided
    /// together where the mesh is closed (`watertight::across`).
    pub fn first_shape(&self, ray: &RefRay, faces: Faces) -> Option<Option<(usize, f64, DVec3)>> {
        let mut first: Option<(usize, f64, DVec3)> = None;
        let mut unsure = Vec::new();
        for (k, shape) in self.shapes.iter().enumerate() {
            if faces == Faces::Front && self.seen_from_behind(shape, ray) {
                continue;
            }
            match intersect(shape, ray) {
                Verdict::Ambiguous if self.cutout.is_none() && matches!(shape, RefShape::Triangle { .. }) => {
                    unsure.push(k)
                }
                Verdict::Ambiguous => return None,
                Verdict::Miss => {}
                Verdict::Hit { t, normal } => {
                    match self.coverage(k, ray, t, normal) {
                        Coverage::Hole => continue,
                        Coverage::Edge | Coverage::Unmodelled => return None,
                        Coverage::Solid => {}
                    }
                    if first.is_none_or(|(_, nearest, _)| t < nearest) {
                        first = Some((k, t, normal));
                    }
                }
            }
        }
        if unsure.is_empty() {
            return Some(first);
        }
        // A culled ray within noise of a single-sided mesh's shared edge or vertex is left
        // ambiguous: lavapipe, tracing with back faces culled, lets such rays through where
        // the watertight decision below says they hit, even where only front faces meet
        // (decided that way, 10 false misses in 96,000 rays of probes/mesh-edges.toml over 12
        // runs, at vertices four front triangles share). Either answer is right there.
        if faces == Faces::Front && self.single_sided && first.is_none_or(|hit| !self.behind(&unsure, ray, hit.1)) {
            return None;
        }
        match (first, super::watertight::across(&self.shapes, &unsure, ray)) {
            // Ambiguous where the triangles meet, but behind a hit: the hit is first.
            (Some(hit), None) if self.behind(&unsure, ray, hit.1) => Some(Some(hit)),
            (_, None) => None,
            (first, Some(None)) => Some(first),
            (Some(hit), Some(Some(crossing))) => Some(Some(if hit.1 < crossing.1 { hit } else { crossing })),
            (None, Some(crossing)) => Some(crossing),
        }
    }

    /// What the cutout (if any) makes of `ray`'s hit on shape `k` at `t`.
    fn coverage(&self, k: usize, ray: &RefRay, t: f64, normal: DVec3) -> Coverage {
        let Some(cutout) = &self.cutout else { return Coverage::Solid };
        let triangle = match (&self.shapes[k], self.corners.get(k)) {
            (RefShape::Triangle { p }, Some(corners)) => Some((p, corners)),
            _ => None,
        };
        cutout.coverage(ray.at(t), ray.edge_band(t, normal), triangle)
    }

    /// Where a world-space ray within `reach` first crosses shape `k` of this object, holes and
    /// all, and what the cutout makes of that crossing; `None` where it does not cross it or
    /// the crossing is ambiguous.
    pub fn crossing(&self, k: usize, origin: DVec3, direction: DVec3, reach: (f64, f64)) -> Option<(f64, Coverage)> {
        let ray = self.ray(origin, direction, reach);
        match intersect(self.shapes.get(k)?, &ray) {
            Verdict::Hit { t, normal } => Some((t, self.coverage(k, &ray, t, normal))),
            _ => None,
        }
    }

    /// Whether `ray` (in object space) meets triangle `shape` of this object from behind where
    /// the object is single-sided. glTF's front is where the corners run counterclockwise in
    /// object space: in world space, under a node whose determinant is negative, they run
    /// clockwise, which is how glTF words it. So the ray sees the back where n . d > 0.
    fn seen_from_behind(&self, shape: &RefShape, ray: &RefRay) -> bool {
        let RefShape::Triangle { p } = shape else { return false };
        let winding = (p[1] - p[0]).cross(p[2] - p[0]);
        self.single_sided && winding.dot(ray.direction) > 0.0
    }

    /// Whether every triangle of `unsure` lies beyond `t` along `ray` by more than noise.
    fn behind(&self, unsure: &[usize], ray: &RefRay, t: f64) -> bool {
        let tol = ray.tolerance(t) / ray.direction.length();
        unsure.iter().all(|&k| match self.shapes[k] {
            RefShape::Triangle { p } => {
                p.iter().all(|c| (*c - ray.origin).dot(ray.direction) / ray.direction.length_squared() > t + 4.0 * tol)
            }
            _ => false,
        })
    }
}

/// The f64 reference of every object of a scene.
pub struct SceneReference {
    pub objects: Vec<RefObject>,
}

impl SceneReference {
    /// The reference of every object of `scene`; an error when a shape has no f64 reference.
    pub fn new(scene: &Scene) -> Result<SceneReference, String> {
        let data = scene.build();
        let objects = data
            .instances
            .iter()
            .map(|instance| {
                let object_to_world = instance.object_to_world.as_dmat4();
                let group = data.plan.hit_groups[instance.hit_group as usize];
                let material = &data.materials[data.objects[instance.object as usize].material as usize];
                let texture = data.textures.get((material.texture.x as usize).wrapping_sub(1));
                let texture = texture.map(|(image, sampler)| RefTexture::of(image, sampler));
                let cutout = RefCutout::of(material).map(|c| c.with_texture(texture));
                let reads = cutout.as_ref().is_some_and(|c| c.reads_corners());
                Ok(RefObject {
                    shapes: shapes(&data, group, instance.blas, instance.custom_index)?,
                    corners: if reads { corners(&data, material, instance.blas) } else { Vec::new() },
                    world_to_object: object_to_world.inverse(),
                    object_to_world,
                    cutout,
                    mask: instance.mask,
                    single_sided: instance.single_sided,
                })
            })
            .collect::<Result<_, String>>()?;
        Ok(SceneReference { objects })
    }

    /// The true answer for a world-space primary ray (or a probe's): every object, the back
    /// faces of single-sided ones culled.
    pub fn trace(&self, origin: DVec3, direction: DVec3, t_min: f64, t_max: f64) -> SceneVerdict {
        self.trace_seeing(origin, direction, (t_min, t_max), (u32::MAX, Faces::Front))
    }

    /// The true answer for a world-space shadow ray, which sees only objects whose mask shares a
    /// bit with `mask` (as a ray traced with that cull mask), and every face of them.
    pub fn trace_masked(&self, origin: DVec3, direction: DVec3, reach: (f64, f64), mask: u32) -> SceneVerdict {
        self.trace_seeing(origin, direction, reach, (mask, Faces::Both))
    }

    fn trace_seeing(
        &self,
        origin: DVec3,
        direction: DVec3,
        (t_min, t_max): (f64, f64),
        (mask, faces): (u32, Faces),
    ) -> SceneVerdict {
        let mut hits: Vec<(usize, f64, DVec3)> = Vec::new();
        for (i, object) in self.objects.iter().enumerate().filter(|(_, o)| o.mask & mask != 0) {
            match object.first_hit(&object.ray(origin, direction, (t_min, t_max)), faces) {
                Verdict::Ambiguous => return SceneVerdict::Ambiguous,
                Verdict::Miss => {}
                Verdict::Hit { t, normal } => {
                    // Normals go to world space by the inverse transpose.
                    let world = object.world_to_object.transpose().transform_vector3(normal).normalize();
                    let facing = if world.dot(direction) > 0.0 { -world } else { world };
                    hits.push((i, t, facing));
                }
            }
        }
        hits.sort_by(|a, b| a.1.total_cmp(&b.1));
        first_of(&hits, origin, direction)
    }

    /// The shape of `object` (a mesh's triangle, by index) that a world-space ray meets first,
    /// and the object-space point where it does; `None` on a miss or an ambiguous answer.
    pub fn shape_hit(
        &self,
        object: usize,
        origin: DVec3,
        direction: DVec3,
        reach: (f64, f64),
    ) -> Option<(usize, DVec3)> {
        let o = self.objects.get(object)?;
        let ray = o.ray(origin, direction, reach);
        let (k, t, _) = o.first_shape(&ray, Faces::Front)??;
        Some((k, ray.at(t)))
    }

    /// The objects (seen by `mask`) whose shapes a world-space ray crosses, holes and all, and
    /// the t of the first crossing of each, nearest first: where a stage may have found a hit
    /// the reference does not (a cutout's any-hit stage that kept a hit in a hole).
    pub fn crossings(&self, origin: DVec3, direction: DVec3, range: (f64, f64), mask: u32) -> Vec<(usize, f64)> {
        let mut out: Vec<(usize, f64)> = Vec::new();
        for (i, object) in self.objects.iter().enumerate().filter(|(_, o)| o.mask & mask != 0) {
            let ray = object.ray(origin, direction, range);
            let ts = object.shapes.iter().filter_map(|shape| match intersect(shape, &ray) {
                Verdict::Hit { t, .. } => Some(t),
                _ => None,
            });
            if let Some(t) = ts.min_by(f64::total_cmp) {
                out.push((i, t));
            }
        }
        out.sort_by(|a, b| a.1.total_cmp(&b.1));
        out
    }
}

/// The first of `hits` (sorted by t) as the scene's verdict: ambiguous when another object's hit
/// is within float noise of it.
fn first_of(hits: &[(usize, f64, DVec3)], origin: DVec3, direction: DVec3) -> SceneVerdict {
    match hits {
        [] => SceneVerdict::Miss,
        [(object, t, normal), rest @ ..] => {
            let scale = origin.abs().max_element().max((origin + direction * *t).abs().max_element());
            let noise = super::shapes::AMBIGUOUS_ULPS * scale / 16_777_216.0 / direction.length();
            match rest.first() {
                Some((other, t2, _)) if other != object && t2 - t <= noise => SceneVerdict::Ambiguous,
                _ => SceneVerdict::Hit { object: *object, t: *t, normal: *normal },
            }
        }
    }
}

/// What the corners of each triangle of a mesh BLAS give `material`'s own alpha: their alphas
/// (COLOR_0's) and the texture coordinates of the set its base colour texture reads, through
/// its transform (`twinray_shared::texture::vertex_uv`); in its triangles' order, none for
/// procedural primitives.
fn corners(data: &SceneData, material: &Material, blas: usize) -> Vec<Corners> {
    let BlasDesc::Triangles { vertex_base, index_base, index_count, .. } = &data.blases[blas] else {
        return Vec::new();
    };
    let (row_u, row_v) = (material.uv_u.as_dvec4(), material.uv_v.as_dvec4());
    let corner = |i: u32| {
        let vertex = &data.vertices[(*vertex_base + i) as usize];
        let uv = vertex.uv.as_dvec4();
        let uv = if material.texture.y == 1 { uv.zw() } else { uv.xy() };
        let uv = DVec2::new(row_u.xy().dot(uv) + row_u.z, row_v.xy().dot(uv) + row_v.z);
        (f64::from(vertex.color.w), uv)
    };
    let indices = data.indices.range(*index_base as usize, *index_count as usize).unwrap_or_default();
    indices
        .chunks_exact(3)
        .map(|t| {
            let [a, b, c] = [corner(t[0]), corner(t[1]), corner(t[2])];
            Corners { alpha: [a.0, b.0, c.0], uv: [a.1, b.1, c.1] }
        })
        .collect()
}

/// The reference shapes of one instance: its BLAS's primitives, read as its hit group reads
/// them; an error names a shape the reference does not know.
fn shapes(data: &SceneData, group: HitGroup, blas: usize, primitive_base: u32) -> Result<Vec<RefShape>, String> {
    match &data.blases[blas] {
        BlasDesc::Triangles { vertex_base, index_base, index_count, .. } => {
            let vertex = |i: u32| data.vertices[(*vertex_base + i) as usize].position.xyz().as_dvec3();
            let indices = data.indices.range(*index_base as usize, *index_count as usize).unwrap_or_default();
            Ok(indices
                .chunks_exact(3)
                .map(|t| RefShape::Triangle { p: [vertex(t[0]), vertex(t[1]), vertex(t[2])] })
                .collect())
        }
        BlasDesc::Aabbs(boxes) => {
            if let HitGeometry::Own(shape) = group.geometry {
                let primitives = &data.primitives[primitive_base as usize..][..boxes.len()];
                return Ok(primitives
                    .iter()
                    .zip(boxes)
                    .map(|(p, b)| RefShape::Own {
                        shape,
                        parameters: Parameters::of(p),
                        bounds: (b.min.as_dvec3(), b.max.as_dvec3()),
                    })
                    .collect());
            }
            let name = group.shape().map_or("triangles", |s| s.name);
            (0..boxes.len())
                .map(|k| {
                    from_primitive(name, &data.primitives[primitive_base as usize + k]).ok_or_else(|| {
                        format!("the f64 reference has no {name} shape (add its distance to TRACED in host/src/reference/traced.rs to probe it)")
                    })
                })
                .collect()
        }
    }
}
