//! Descriptor bindings, kind codes, specialisation constants and ray constants shared by both
//! shader sets.
//!
//! The Rust shaders must spell bindings as literals in `#[spirv(...)]` attributes; a test reads
//! the decorations back from every compiled module and checks them against these constants.

/// The only descriptor set.
pub const DESCRIPTOR_SET: u32 = 0;
/// Top-level acceleration structure.
pub const BINDING_TLAS: u32 = 0;
/// Output colour, a storage image of format rgba32f: each pixel's mean radiance.
pub const BINDING_IMAGE: u32 = 1;
/// [`crate::layout::FrameUniform`], a uniform buffer.
pub const BINDING_FRAME: u32 = 2;
/// `[ObjectData]`, indexed by the instance index (TLAS instances are in object order). The
/// instance custom index holds the object's `primitive_base`.
pub const BINDING_OBJECTS: u32 = 3;
/// `[Primitive]`: parameters of procedural primitives, from each object's `primitive_base`.
pub const BINDING_PRIMITIVES: u32 = 4;
/// `[Material]`.
pub const BINDING_MATERIALS: u32 = 5;
/// `[Light; MAX_LIGHTS]`, of which the first `FrameUniform::light_count` are the scene's.
pub const BINDING_LIGHTS: u32 = 6;
/// Most lights in a scene, and the lights buffer's fixed length. A fixed length leaves the
/// stages no buffer length to read: rust-gpu reads a slice's at the entry point, and every
/// thread waits for it before its first trace.
pub const MAX_LIGHTS: u32 = 1024;
/// `[u32]`, [`HIT_IDS_PER_PIXEL`] per pixel: object and primitive hit by the first primary ray
/// (or [`NO_HIT`]), how many shadow rays the pixel traced (so that rays/s count the rays
/// actually traced), and its primary rays whose payload no hit or miss stage wrote (see
/// [`no_payload_word`]).
pub const BINDING_HIT_IDS: u32 = 7;
/// u32 words per pixel in the hit-id buffer: the object and primitive the first primary ray
/// hit, the shadow rays traced, and the primary rays no stage wrote a payload for.
pub const HIT_IDS_PER_PIXEL: u32 = 4;
/// The fourth hit-id word of a pixel holds `count | first << NO_PAYLOAD_FIRST_SHIFT`: how many
/// of its primary rays came back with the payload ray generation poisoned, and the sample
/// index of the first (0 when none did).
pub const NO_PAYLOAD_FIRST_SHIFT: u32 = 16;

/// The fourth hit-id word after one more primary ray, sample `sample`, came back with no payload.
pub const fn no_payload_word(word: u32, sample: u32) -> u32 {
    if word == 0 {
        1 | (sample << NO_PAYLOAD_FIRST_SHIFT)
    } else {
        word + 1
    }
}
/// `[Vertex]` of every mesh, from each object's `vertex_base`.
pub const BINDING_VERTICES: u32 = 8;
/// `[u32]`, three per triangle, from each object's `index_base`, relative to `vertex_base`.
pub const BINDING_INDICES: u32 = 9;

/// The scene's textures: a runtime array of combined image samplers, [`TEXTURE_SLOTS`] of
/// them, indexed per hit by `Material::texture.x` (so non-uniformly: `NonUniform` in SPIR-V,
/// `nonuniformEXT` in GLSL). Slot 0 is a white texel; slots past the scene's last texture
/// repeat it, so every slot is written.
pub const BINDING_TEXTURES: u32 = 12;
/// How many slots the texture array has: a scene with more textures is refused.
pub const TEXTURE_SLOTS: u32 = 1024;

/// `[ProbeRay]` read by the probe stage, one per launch index.
pub const BINDING_PROBE_RAYS: u32 = 10;
/// `[ProbeResult]` written by the probe stage.
pub const BINDING_PROBE_RESULTS: u32 = 11;

/// `ExplainRay::kind` of a primary ray and of a shadow ray.
pub const EXPLAIN_PRIMARY: u32 = 0;
/// `ExplainRay::kind` of a shadow ray.
pub const EXPLAIN_SHADOW: u32 = 1;

/// The compute renderer (`renderer = "compute"`) runs workgroups of N x N pixels.
pub const RENDER_GROUP_SIZE: u32 = 8;
/// Its probe (`probe_query`) runs workgroups of N rays.
pub const PROBE_GROUP_SIZE: u32 = 64;
/// Hit kinds of triangles, as the pipeline reports them (`HitKindFrontFacingTriangleKHR` and
/// `HitKindBackFacingTriangleKHR`); the compute renderer derives them from its ray query.
pub const HIT_KIND_TRIANGLE_FRONT: u32 = 0xfe;
/// The hit kind of a triangle's back face (`HitKindBackFacingTriangleKHR`).
pub const HIT_KIND_TRIANGLE_BACK: u32 = 0xff;

/// Miss shader indices in the shader binding table.
pub const MISS_PRIMARY: u32 = 0;
/// The shadow rays' miss shader: it marks the light as seen.
pub const MISS_SHADOW: u32 = 1;

/// The ray flags of primary rays (and a probe's, which stand for them): back faces of
/// single-sided meshes culled (`CullBackFacingTrianglesKHR`, 0x10); the instances of the rest
/// disable culling (`TRIANGLE_FACING_CULL_DISABLE`). Shadow rays keep every face: a surface
/// blocks light whichever way it faces.
pub const PRIMARY_RAY_FLAGS: u32 = 0x10;

/// Instance masks: shadow rays see only occluders; emissive objects show but cast no shadow.
pub const MASK_OCCLUDER: u32 = 0x01;
/// The instance mask of emissive objects: primary rays see them, shadow rays pass them.
pub const MASK_EMITTER: u32 = 0x02;

/// Specialisation constants: whether any light casts shadows (0/1), and M for M x M primary
/// samples per pixel.
pub const SPEC_SHADOWS: u32 = 0;
/// Specialisation constant id: the square root of the primary samples per pixel.
pub const SPEC_SAMPLES_PER_SIDE: u32 = 1;
/// Specialisation constant: how rect lights' N x N shadow samples are placed.
pub const SPEC_SHADOW_SAMPLER: u32 = 2;
/// Specialisation constant of every stage: the features the scene uses (`crate::features`),
/// whose code a stage skips where their bit is clear.
pub const SPEC_FEATURES: u32 = 3;
/// Specialisation constant of ray generation: 1 where a closest hit may shade the surface
/// itself ([`MATERIAL_SHADED`]; the host sets it for any set with a stage from disk), 0 for
/// twinray's own sets, whose closest hits never do, so that the check costs them nothing.
pub const SPEC_SHADED_HITS: u32 = 4;
/// One jittered sample in each cell of an N x N grid over the light (the default).
pub const SHADOW_SAMPLER_STRATIFIED: u32 = 0;
/// N x N independent samples, each anywhere on the light.
pub const SHADOW_SAMPLER_RANDOM: u32 = 1;

/// Material kinds (`Material::kind`).
pub const MATERIAL_DIFFUSE: u32 = 0;
/// `Material::kind` of an emissive material.
pub const MATERIAL_EMISSIVE: u32 = 1;
/// `Material::kind` of a checker material.
pub const MATERIAL_CHECKER: u32 = 2;
/// Diffuse with holes: hits where its alpha pattern is transparent are ignored by the any-hit
/// stage, for primary and shadow rays alike.
pub const MATERIAL_CUTOUT: u32 = 3;
/// What a closest-hit stage that shades the surface itself writes as the hit's material kind
/// (`HitPayload::ids.z`): its `color` is then the radiance ray generation shows, not an albedo
/// it lights again. No material kind a scene reaches.
pub const MATERIAL_SHADED: u32 = 0xffff_fff0;
/// How many material kinds there are: the SBT's callable region has a record for each
/// (`material_shading = "callable"`), the kind being the record's index.
pub const MATERIAL_KINDS: u32 = 4;

/// Cutout alpha patterns (`Material::cutout_pattern`), over object-space x and z.
pub const CUTOUT_NONE: u32 = 0;
/// Alpha 1 in even cells, 0 in odd ones: square holes.
pub const CUTOUT_CHECKER: u32 = 1;
/// Alpha rising from 0 at each cell's centre to 1 at half a cell from it: round holes of
/// radius `threshold` half-cells.
pub const CUTOUT_DISCS: u32 = 2;
/// Alpha of the surface itself, on meshes: `color_a.w` times the vertex colour's alpha times
/// the base colour texture's (glTF's alpha mode MASK), at texture level 0.
pub const CUTOUT_TEXTURE: u32 = 3;

/// Light kinds (`Light::kind`).
pub const LIGHT_DIRECTIONAL: u32 = 0;
/// `Light::kind` of a point light.
pub const LIGHT_POINT: u32 = 1;
/// `Light::kind` of a rectangular area light.
pub const LIGHT_RECT: u32 = 2;

/// Written to the hit-id buffer (and `HitPayload::ids.w`) when a ray hits nothing.
pub const NO_HIT: u32 = 0xffff_ffff;
/// What the host fills every output word with before a set's stages write them (the image's
/// channels, the hit ids, the probe records), so that what is left of it counts as never
/// written. As an f32 it is a signalling NaN with a payload, which no arithmetic produces; as
/// a u32 it is no object, primitive or kind index and no shadow-ray count a scene reaches.
pub const UNWRITTEN: u32 = 0x7fa5_dead;
/// What the probe stage writes in every word of a record's `ids` when the ray's hit or miss
/// stage left the payload poisoned: the record was written (so it is not [`UNWRITTEN`]), the
/// payload was not. No object, primitive or hit kind a scene reaches.
pub const PROBE_NO_PAYLOAD: u32 = 0x7fa5_0bad;

/// The object (the index into the objects buffer, `layout::ObjectData`) that a hit on a mesh
/// belongs to: its instance id plus its geometry index. The host places consecutive objects
/// that share a transform, a hit group and a mask (a glTF mesh's primitives) as one TLAS
/// instance of one BLAS, object `k` of them its geometry `k`, and leaves the instance slots
/// of the others inactive; every other instance has one geometry, so this is its instance id.
/// A procedural BLAS has one geometry: its stages read the instance id alone.
#[inline(always)]
pub fn mesh_object(instance: u32, geometry: u32) -> u32 {
    instance + geometry
}
