//! The stages that serve `twinray probe` and `twinray explain`, as a macro the crate root invokes
//! (an entry point's name is its path): rays read from a buffer, traced as the renderers trace
//! them, and what they met written back.

/// Defines the probe and explain entry points: `probe` and its witnesses `probe_witness` and
/// `probe_witness_driver`,
/// `explain`, and the inline-ray (ray query) forms `explain_query` and `probe_query`.
macro_rules! probe_stages {
    () => {
        /// The probe: one ray per launch index from the ray buffer, traced through the same pipeline
        /// as renders (so it measures the very intersection and hit stages images use); writes what
        /// the closest-hit stage described, or NO_HIT (and a zero normal and t), or `PROBE_NO_PAYLOAD`
        /// where the stage that took the ray left the poisoned payload as it was.
        #[spirv(ray_generation)]
        pub fn probe(
            #[spirv(launch_id)] launch_id: UVec3,
            #[spirv(descriptor_set = 0, binding = 0)] tlas: &AccelerationStructure,
            #[spirv(storage_buffer, descriptor_set = 0, binding = 10)] rays: &[ProbeRay],
            #[spirv(storage_buffer, descriptor_set = 0, binding = 11)] results: &mut [ProbeResult],
            #[spirv(ray_payload)] payload: &mut HitPayload,
        ) {
            let i = launch_id.x as usize;
            // Checked before the trace: a bounds check of the write after it would keep the buffer's
            // length alive across the call (twinray's guide, *Rust stages*, "Writing loops around traceRay in Rust").
            if i >= rays.len() || i >= results.len() {
                return;
            }
            // SAFETY: i < rays.len(), checked above.
            let ray = unsafe { *rays.get_unchecked(i) };
            payload.poison();
            // SAFETY: the TLAS is bound and built; the payload is this stage's ray_payload variable.
            unsafe {
                tlas.trace_ray(
                    crate::flags::PRIMARY_RAY_FLAGS,
                    0xff,
                    0,
                    0,
                    MISS_PRIMARY as i32,
                    ray.origin.xyz(),
                    ray.origin.w,
                    ray.direction.xyz(),
                    ray.direction.w,
                    payload,
                );
            }
            // A miss writes no normal or t: zeros, not the poison.
            let normal_t = if payload.ids.w == NO_HIT {
                Vec4::ZERO
            } else {
                payload.shading_normal.xyz().extend(payload.position.w)
            };
            let ids = if payload.unwritten(false) { UVec4::splat(PROBE_NO_PAYLOAD) } else { payload.ids };
            // SAFETY: i < results.len(), checked before the trace.
            unsafe { *results.get_unchecked_mut(i) = ProbeResult { normal_t, ids } };
        }

        /// The probe's witness: a closest-hit stage twinray puts in place of a hit group's own (same
        /// intersection and any-hit stages) for one extra pass of the probe. It packs the
        /// object-space ray the intersection stages use (`twinray_shared::transform::stage_ray`,
        /// chosen and brought near the primitive as they do it), how far along the world ray it
        /// starts, and the t they reported, into the payload fields the probe ray generation stage
        /// copies out (as `ProbeResult` documents), so a probe can judge the stages against the
        /// ray they used, apart from the transform's error.
        ///
        /// A triangle's hit the stages measure again where the scene has far instances
        /// (`twinray_shared::transform::triangle_t`): its witness is the ray brought near the
        /// triangle and the t measured on it, or, where the ray was not moved, the driver's ray.
        #[spirv(closest_hit)]
        #[allow(clippy::too_many_arguments)]
        pub fn probe_witness(
            #[spirv(instance_id)] object: u32,
            #[spirv(instance_custom_index)] primitive_base: u32,
            #[spirv(primitive_id)] primitive_id: u32,
            #[spirv(hit_kind)] hit_kind: u32,
            #[spirv(world_ray_origin)] world_origin: Vec3,
            #[spirv(world_ray_direction)] world_direction: Vec3,
            #[spirv(object_ray_origin)] object_origin: Vec3,
            #[spirv(object_ray_direction)] object_direction: Vec3,
            #[spirv(object_to_world)] object_to_world: Matrix4x3,
            #[spirv(world_to_object)] world_to_object: Matrix4x3,
            #[spirv(ray_tmax)] t: f32,
            #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] objects: &[ObjectData],
            #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
            #[spirv(storage_buffer, descriptor_set = 0, binding = 8)] vertices: &[Vertex],
            #[spirv(storage_buffer, descriptor_set = 0, binding = 9)] indices: &[u32],
            #[spirv(incoming_ray_payload)] payload: &mut HitPayload,
            #[spirv(spec_constant(id = 3, default = 31))] features: u32,
        ) {
            let world = (world_origin, world_direction);
            let placed = (object_to_world.w_axis, world_to_object.to_mat3());
            use twinray_shared::bindings::{HIT_KIND_TRIANGLE_BACK, HIT_KIND_TRIANGLE_FRONT};
            use twinray_shared::features::FAR_INSTANCES;
            if (hit_kind == HIT_KIND_TRIANGLE_FRONT) | (hit_kind == HIT_KIND_TRIANGLE_BACK) {
                let mut ray = twinray_shared::transform::StageRay {
                    origin: object_origin,
                    direction: object_direction,
                    shift: 0.0,
                };
                if Features::new(features).has::<FAR_INSTANCES>() & ((object as usize) < objects.len()) {
                    // SAFETY: the index checked above; the vertices and indices are the host's.
                    let data = unsafe { *objects.get_unchecked(object as usize) };
                    let v = crate::hit::triangle_vertices(&data, primitive_id, vertices, indices);
                    let p = [v[0].position.xyz(), v[1].position.xyz(), v[2].position.xyz()];
                    let near = twinray_shared::transform::triangle_ray(world, placed, p);
                    if near.shift > 0.0 {
                        ray = near;
                    }
                    let t = twinray_shared::transform::plane_t(&near, p, t);
                    witness(payload, (ray.origin, ray.direction), t, ray.shift);
                    return;
                }
                witness(payload, (ray.origin, ray.direction), t, 0.0);
                return;
            }
            // The bound the intersection stage used: its object's routine (zero for the naive ones).
            let mut bound = Vec4::ZERO;
            let primitive = (primitive_base + primitive_id) as usize;
            if (object as usize) < objects.len() && primitive < primitives.len() {
                // SAFETY: both indices checked above.
                let shape = unsafe { objects.get_unchecked(object as usize) }.shape;
                bound = twinray_shared::shapes::shape_bound(shape, unsafe { primitives.get_unchecked(primitive) });
            }
            let ray = twinray_shared::transform::stage_ray(
                Features::new(features),
                (object_origin, object_direction),
                world,
                placed,
                bound,
            );
            witness(payload, (ray.origin, ray.direction), t, ray.shift);
        }

        /// The second witness, of what the driver's transform would have cost: as
        /// `probe_witness`, with the object-space ray the driver hands a hit group
        /// (`ObjectRayOriginKHR`, `ObjectRayDirectionKHR`), which the intersection stages do not use.
        #[spirv(closest_hit)]
        pub fn probe_witness_driver(
            #[spirv(object_ray_origin)] object_origin: Vec3,
            #[spirv(object_ray_direction)] object_direction: Vec3,
            #[spirv(ray_tmax)] t: f32,
            #[spirv(incoming_ray_payload)] payload: &mut HitPayload,
        ) {
            witness(payload, (object_origin, object_direction), t, 0.0);
        }

        /// A witness's record: the object-space ray, where it starts along the world ray and t,
        /// in the fields `probe` copies out.
        fn witness(payload: &mut HitPayload, (origin, d): (Vec3, Vec3), t: f32, shift: f32) {
            payload.position.w = t;
            payload.shading_normal = origin.extend(payload.shading_normal.w);
            payload.ids = UVec4::new(d.x.to_bits(), d.y.to_bits(), d.z.to_bits(), shift.to_bits());
        }

        /// `twinray explain`'s stage: one ray per launch index, traced as the renderer traces rays of
        /// its kind (`trace::primary` or `trace::visible`, the functions `raygen` calls); writes the
        /// primary ray's payload, or whether the shadow ray was occluded.
        #[spirv(ray_generation)]
        pub fn explain(
            #[spirv(launch_id)] launch_id: UVec3,
            #[spirv(descriptor_set = 0, binding = 0)] tlas: &AccelerationStructure,
            #[spirv(uniform, descriptor_set = 0, binding = 2)] frame: &FrameUniform,
            #[spirv(storage_buffer, descriptor_set = 0, binding = 10)] rays: &[ExplainRay],
            #[spirv(storage_buffer, descriptor_set = 0, binding = 11)] results: &mut [ExplainResult],
            #[spirv(ray_payload)] payload: &mut HitPayload,
            #[spirv(ray_payload)] shadow: &mut ShadowPayload,
        ) {
            let i = launch_id.x as usize;
            if i >= rays.len() || i >= results.len() {
                return;
            }
            // SAFETY: i < rays.len(), checked above.
            let r = unsafe { *rays.get_unchecked(i) };
            let ray = camera::Ray { origin: r.origin.xyz(), direction: r.direction.xyz() };
            let result = if r.kind.x == EXPLAIN_SHADOW {
                let lit = trace::visible(tlas, ray.origin, ray.direction, r.direction.w, Features::all(), shadow);
                ExplainResult { hit: HitPayload::NONE, occluded: UVec4::new(if lit { 0 } else { 1 }, 0, 0, 0) }
            } else {
                payload.poison();
                trace::primary(tlas, ray, (frame.reach.z, frame.reach.x), Features::all(), payload);
                ExplainResult { hit: *payload, occluded: UVec4::ZERO }
            };
            // SAFETY: i < results.len(), checked above.
            unsafe { *results.get_unchecked_mut(i) = result };
        }

        /// `twinray explain`'s stage for rays traced inline (`renderer = "compute"`, and the shadow
        /// rays of `shadow_method = "query"`): as `explain`, with `query::primary_query` and
        /// `query::visible_query`, which the compute renderer and `raygen_query` call; in workgroups of
        /// `PROBE_GROUP_SIZE` (the literal is the attribute's).
        #[spirv(compute(threads(64)))]
        #[allow(clippy::too_many_arguments)]
        pub fn explain_query(
            #[spirv(global_invocation_id)] id: UVec3,
            #[spirv(descriptor_set = 0, binding = 0)] tlas: &AccelerationStructure,
            #[spirv(uniform, descriptor_set = 0, binding = 2)] frame: &FrameUniform,
            #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] objects: &[ObjectData],
            #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
            #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] materials: &[Material],
            #[spirv(storage_buffer, descriptor_set = 0, binding = 8)] vertices: &[Vertex],
            #[spirv(storage_buffer, descriptor_set = 0, binding = 9)] indices: &[u32],
            #[spirv(descriptor_set = 0, binding = 12)] textures: &RuntimeArray<Texture>,
            #[spirv(storage_buffer, descriptor_set = 0, binding = 10)] rays: &[ExplainRay],
            #[spirv(storage_buffer, descriptor_set = 0, binding = 11)] results: &mut [ExplainResult],
            #[spirv(spec_constant(id = 3, default = 31))] features: u32,
        ) {
            let features = Features::new(features);
            let i = id.x as usize;
            // Whole workgroups cover the rays; both buffers checked, as in `explain`.
            if i >= rays.len() || i >= results.len() {
                return;
            }
            let r = rays[i];
            let ray = camera::Ray { origin: r.origin.xyz(), direction: r.direction.xyz() };
            results[i] = if r.kind.x == EXPLAIN_SHADOW {
                let (hit_buffers, mesh) = ((objects, primitives, materials), (vertices, indices));
                let lit = query::visible_query(
                    tlas,
                    ray.origin,
                    ray.direction,
                    r.direction.w,
                    features,
                    hit_buffers,
                    mesh,
                    textures,
                );
                ExplainResult { hit: HitPayload::NONE, occluded: UVec4::new(if lit { 0 } else { 1 }, 0, 0, 0) }
            } else {
                let mut hit = HitPayload::NONE;
                let reach = (frame.reach.z, frame.reach.x);
                query::primary_query(
                    tlas, ray, reach, features, &mut hit, frame, objects, primitives, materials, vertices, indices,
                    textures,
                );
                ExplainResult { hit, occluded: UVec4::ZERO }
            };
        }

        /// The compute renderer's probe (a probe of a `renderer = "compute"` scene): one ray per
        /// invocation, traced inline by the code that traces the renderer's primary rays, in
        /// workgroups of `PROBE_GROUP_SIZE` (the literal is the attribute's); writes what it described,
        /// or NO_HIT.
        #[spirv(compute(threads(64)))]
        #[allow(clippy::too_many_arguments)]
        pub fn probe_query(
            #[spirv(global_invocation_id)] id: UVec3,
            #[spirv(descriptor_set = 0, binding = 0)] tlas: &AccelerationStructure,
            #[spirv(storage_buffer, descriptor_set = 0, binding = 3)] objects: &[ObjectData],
            #[spirv(storage_buffer, descriptor_set = 0, binding = 4)] primitives: &[Primitive],
            #[spirv(storage_buffer, descriptor_set = 0, binding = 5)] materials: &[Material],
            #[spirv(storage_buffer, descriptor_set = 0, binding = 8)] vertices: &[Vertex],
            #[spirv(storage_buffer, descriptor_set = 0, binding = 9)] indices: &[u32],
            #[spirv(descriptor_set = 0, binding = 12)] textures: &RuntimeArray<Texture>,
            #[spirv(storage_buffer, descriptor_set = 0, binding = 10)] rays: &[ProbeRay],
            #[spirv(storage_buffer, descriptor_set = 0, binding = 11)] results: &mut [ProbeResult],
            #[spirv(spec_constant(id = 3, default = 31))] features: u32,
        ) {
            let i = id.x as usize;
            // Whole workgroups cover the rays.
            if i >= rays.len() {
                return;
            }
            let probe = rays[i];
            let mut hit = HitPayload::NONE;
            let range = (probe.origin.w, probe.direction.w);
            let ray = twinray_shared::camera::Ray { origin: probe.origin.xyz(), direction: probe.direction.xyz() };
            let hit_buffers = (objects, primitives, materials);
            // No cone: probes judge geometry, and their rays come from no camera.
            let (mesh, features) = ((vertices, indices), Features::new(features));
            query::trace_query(tlas, ray, range, &mut hit, Vec4::ZERO, hit_buffers, mesh, textures, (0.0, features));
            results[i] = ProbeResult { normal_t: hit.shading_normal.xyz().extend(hit.position.w), ids: hit.ids };
        }
    };
}
