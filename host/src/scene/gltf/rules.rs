//! The glTF validator's rules on what a file states beyond its node graph (`graph`): morph
//! targets and weights, skins, animations, cameras, accessors and the texture coordinates a
//! material reads. A file that breaks one is not a glTF 2.0 file and viewers differ on what it
//! shows (which weight goes with a target the lists do not pair? where does a vertex bound to
//! a joint that is not there go?), so it is refused in one line naming the object, before
//! anything is placed, whether or not twinray models the part that breaks the rule.

use super::accessors::check as check_accessor;
use gltf::accessor::{DataType, Dimensions};
use gltf::animation::{Interpolation, Property};
use gltf::camera::Projection;
use std::collections::BTreeSet;

/// The first rule `doc` breaks that its JSON shows, said with the object named.
pub fn check(doc: &gltf::Document) -> Result<(), String> {
    channel_targets(doc.as_json())?;
    accessors(doc)?;
    cameras(doc)?;
    lights(doc)?;
    meshes(doc)?;
    nodes(doc)?;
    skins(doc)?;
    animations(doc)
}

/// The rules only the buffers show: animation key times rise strictly from 0 or later, and a
/// skinned mesh's joint indices name joints of its skin. Each accessor is bounds-checked
/// before it is read, and every animation output too, which `keyframes` reads.
pub fn check_data(doc: &gltf::Document, buffers: &[Vec<u8>]) -> Result<(), String> {
    let get = |b: gltf::Buffer| buffers.get(b.index()).map(Vec::as_slice);
    for animation in doc.animations() {
        for channel in animation.channels() {
            let sampler = channel.sampler();
            let what = format!("animation {} sampler {}", animation.index(), sampler.index());
            check_accessor(&sampler.input(), buffers, &what, "input", &[Dimensions::Scalar], &[DataType::F32])?;
            // Its type is `animations`' to judge; here, that it lies within its view.
            let output = sampler.output();
            check_accessor(&output, buffers, &what, "output", &[output.dimensions()], &[output.data_type()])?;
            let times = channel.reader(get).read_inputs().into_iter().flatten();
            rising(times, &what, sampler.input().index())?;
        }
    }
    let mut checked = BTreeSet::new();
    for node in doc.nodes() {
        let (Some(skin), Some(mesh)) = (node.skin(), node.mesh()) else { continue };
        if !checked.insert((skin.index(), mesh.index())) {
            continue;
        }
        let joints = skin.joints().len();
        for primitive in mesh.primitives() {
            let what = format!("mesh {} primitive {}", mesh.index(), primitive.index());
            let reader = primitive.reader(get);
            for (set, accessor) in (0..).map_while(|s| primitive.get(&gltf::Semantic::Joints(s)).map(|a| (s, a))) {
                let semantic = format!("JOINTS_{set}");
                check_accessor(
                    &accessor,
                    buffers,
                    &what,
                    &semantic,
                    &[Dimensions::Vec4],
                    &[DataType::U8, DataType::U16],
                )?;
                let named = reader.read_joints(set).map(|j| j.into_u16().flatten().max()).unwrap_or_default();
                if let Some(j) = named.filter(|&j| usize::from(j) >= joints) {
                    return Err(format!(
                        "{what}: {semantic} (accessor {}) names joint {j}, past the {joints} joints of skin {} of node {}",
                        accessor.index(),
                        skin.index(),
                        node.index()
                    ));
                }
            }
        }
    }
    Ok(())
}

/// Each animation channel's target is a node of the file and a path glTF defines: the `gltf`
/// crate's validation leaves both unchecked, and its reader unwraps them.
fn channel_targets(json: &gltf::json::Root) -> Result<(), String> {
    for (a, animation) in json.animations.iter().enumerate() {
        for (c, channel) in animation.channels.iter().enumerate() {
            let node = channel.target.node.value();
            if node >= json.nodes.len() {
                return Err(format!(
                    "animation {a} channel {c} targets node {node}, past its {} nodes",
                    json.nodes.len()
                ));
            }
            if !matches!(channel.target.path, gltf::json::validation::Checked::Valid(_)) {
                return Err(format!("animation {a} channel {c} targets a path glTF does not define"));
            }
        }
    }
    Ok(())
}

/// That key `times` rise strictly from 0 or later, as glTF asks of an animation's input.
fn rising(times: impl Iterator<Item = f32>, what: &str, accessor: usize) -> Result<(), String> {
    let mut last: Option<f32> = None;
    for (k, t) in times.enumerate() {
        if !t.is_finite() || t < 0.0 {
            return Err(format!("{what}: input (accessor {accessor}) key {k} is at {t} s (key times are 0 or later)"));
        }
        if let Some(l) = last.filter(|&l| t <= l) {
            return Err(format!(
                "{what}: input (accessor {accessor}) key {k} is at {t} s, not after key {}'s {l} s (key times rise strictly)",
                k - 1
            ));
        }
        last = Some(t);
    }
    Ok(())
}

/// `normalized` only on 8- and 16-bit integers, where it maps them to [0, 1] or [-1, 1].
fn accessors(doc: &gltf::Document) -> Result<(), String> {
    for a in doc.accessors() {
        if a.normalized() && matches!(a.data_type(), DataType::F32 | DataType::U32) {
            return Err(format!(
                "accessor {} is normalized but of {:?} (glTF normalizes only 8- and 16-bit integers)",
                a.index(),
                a.data_type()
            ));
        }
    }
    Ok(())
}

/// A camera's volume is not empty: an orthographic one's magnifications are not 0, a
/// perspective one's field of view and aspect are above 0, znear is not below 0 (above 0 in
/// perspective) and zfar lies beyond it.
fn cameras(doc: &gltf::Document) -> Result<(), String> {
    for camera in doc.cameras() {
        let name = format!("camera {}", camera.index());
        let wrong = match camera.projection() {
            Projection::Orthographic(o) => {
                let (x, y, near, far) = (o.xmag(), o.ymag(), o.znear(), o.zfar());
                if x == 0.0 || y == 0.0 || !x.is_finite() || !y.is_finite() {
                    Some(format!("is orthographic with an xmag of {x} and a ymag of {y} (neither may be 0)"))
                } else {
                    depth_range(near, Some(far))
                }
            }
            Projection::Perspective(p) => {
                let fov = p.yfov();
                if fov <= 0.0 || !fov.is_finite() {
                    Some(format!("has a yfov of {fov} (above 0)"))
                } else if let Some(a) = p.aspect_ratio().filter(|a| *a <= 0.0 || !a.is_finite()) {
                    Some(format!("has an aspectRatio of {a} (above 0)"))
                } else if p.znear() <= 0.0 {
                    Some(format!("has a znear of {} (perspective asks for one above 0)", p.znear()))
                } else {
                    depth_range(p.znear(), p.zfar())
                }
            }
        };
        if let Some(wrong) = wrong {
            return Err(format!("{name} {wrong}"));
        }
    }
    Ok(())
}

/// A KHR_lights_punctual light's range is above 0, and a spot light's cone opens from an
/// innerConeAngle of 0 or more to an outerConeAngle beyond it, at most a quarter turn.
fn lights(doc: &gltf::Document) -> Result<(), String> {
    use gltf::khr_lights_punctual::Kind;
    for light in doc.lights().into_iter().flatten() {
        let name = format!("KHR_lights_punctual light {}", light.index());
        if let Some(range) = light.range().filter(|r| !(*r > 0.0 && r.is_finite())) {
            return Err(format!("{name} has a range of {range} (above 0)"));
        }
        if let Kind::Spot { inner_cone_angle: inner, outer_cone_angle: outer } = light.kind() {
            if !(inner >= 0.0 && inner < outer && outer <= std::f32::consts::FRAC_PI_2) {
                return Err(format!(
                    "{name} is a spot light of innerConeAngle {inner} and outerConeAngle {outer} (0 <= inner < outer <= pi / 2)"
                ));
            }
        }
    }
    Ok(())
}

fn depth_range(near: f32, far: Option<f32>) -> Option<String> {
    if near < 0.0 || !near.is_finite() {
        return Some(format!("has a znear of {near} (0 or more)"));
    }
    far.filter(|&f| f <= near || f.is_nan()).map(|f| format!("has a zfar of {f}, not beyond its znear of {near}"))
}

/// A mesh's primitives have as many morph targets, each target's attributes one element per
/// vertex, the mesh's default weights one per target, and every texture a primitive's
/// material reads has its TEXCOORD set.
fn meshes(doc: &gltf::Document) -> Result<(), String> {
    for mesh in doc.meshes() {
        let targets = mesh.primitives().next().map_or(0, |p| p.morph_targets().len());
        for p in mesh.primitives() {
            let what = format!("mesh {} primitive {}", mesh.index(), p.index());
            if p.morph_targets().len() != targets {
                return Err(format!(
                    "{what} has {} morph targets, its primitive 0 {targets} (a mesh's primitives have as many)",
                    p.morph_targets().len()
                ));
            }
            let vertices = p.get(&gltf::Semantic::Positions).map_or(0, |a| a.count());
            for (t, target) in p.morph_targets().enumerate() {
                let attributes =
                    [("POSITION", target.positions()), ("NORMAL", target.normals()), ("TANGENT", target.tangents())];
                for (semantic, accessor) in attributes {
                    if let Some(a) = accessor.filter(|a| a.count() != vertices) {
                        return Err(format!(
                            "{what}: morph target {t}'s {semantic} (accessor {}) has {} elements, its POSITION {vertices}",
                            a.index(),
                            a.count()
                        ));
                    }
                }
            }
            texture_coordinates(&p, &what)?;
        }
        if let Some(w) = mesh.weights().filter(|w| w.len() != targets) {
            return Err(format!(
                "mesh {} has {} weights for its {targets} morph targets (one each)",
                mesh.index(),
                w.len()
            ));
        }
    }
    Ok(())
}

/// Every texture of `p`'s material reads a TEXCOORD set `p` has.
fn texture_coordinates(p: &gltf::Primitive, what: &str) -> Result<(), String> {
    let m = p.material();
    let Some(index) = m.index() else { return Ok(()) };
    let pbr = m.pbr_metallic_roughness();
    let effective = |i: gltf::texture::Info| i.texture_transform().and_then(|t| t.tex_coord()).unwrap_or(i.tex_coord());
    let sets = [
        ("baseColorTexture", pbr.base_color_texture().map(effective)),
        ("metallicRoughnessTexture", pbr.metallic_roughness_texture().map(effective)),
        ("normalTexture", m.normal_texture().map(|t| t.tex_coord())),
        ("occlusionTexture", m.occlusion_texture().map(|t| t.tex_coord())),
        ("emissiveTexture", m.emissive_texture().map(effective)),
    ];
    for (texture, set) in sets {
        if let Some(set) = set.filter(|&s| p.get(&gltf::Semantic::TexCoords(s)).is_none()) {
            return Err(format!("{what} has no TEXCOORD_{set}, which its material {index}'s {texture} reads"));
        }
    }
    Ok(())
}

/// A node's weights are one per morph target of its mesh; a skinned node has a mesh.
fn nodes(doc: &gltf::Document) -> Result<(), String> {
    for node in doc.nodes() {
        let targets = node.mesh().and_then(|m| m.primitives().next()).map_or(0, |p| p.morph_targets().len());
        if let Some(w) = node.weights().filter(|w| w.len() != targets || targets == 0) {
            return Err(format!(
                "node {} has {} weights for its mesh's {targets} morph targets (one each, and only with targets)",
                node.index(),
                w.len()
            ));
        }
        if node.skin().is_some() && node.mesh().is_none() {
            return Err(format!("node {} has a skin but no mesh to bind it to", node.index()));
        }
    }
    Ok(())
}

/// A skin has joints, and an inverse bind matrix (4x4 floats) for each.
fn skins(doc: &gltf::Document) -> Result<(), String> {
    for skin in doc.skins() {
        let joints = skin.joints().len();
        if joints == 0 {
            return Err(format!("skin {} has no joints", skin.index()));
        }
        let Some(a) = skin.inverse_bind_matrices() else { continue };
        if a.dimensions() != Dimensions::Mat4 || a.data_type() != DataType::F32 {
            return Err(format!(
                "skin {}: its inverse bind matrices (accessor {}) are not MAT4 of floats",
                skin.index(),
                a.index()
            ));
        }
        if a.count() < joints {
            return Err(format!(
                "skin {} has {} inverse bind matrices (accessor {}) for its {joints} joints (one each)",
                skin.index(),
                a.count(),
                a.index()
            ));
        }
    }
    Ok(())
}

/// Each channel's sampler gives one output per key (three for a cubic spline: in-tangent,
/// value, out-tangent), of as many values as its property has (one per morph target for
/// weights), in a type glTF allows for that property; no two channels drive one property.
fn animations(doc: &gltf::Document) -> Result<(), String> {
    for animation in doc.animations() {
        let mut driven = BTreeSet::new();
        for channel in animation.channels() {
            let (node, property) = (channel.target().node(), channel.target().property());
            let what = format!("animation {} channel {}", animation.index(), channel.index());
            if !driven.insert((node.index(), property as u8)) {
                return Err(format!("{what} drives node {}'s {property:?} again (one channel each)", node.index()));
            }
            if matches!(node.transform(), gltf::scene::Transform::Matrix { .. }) {
                return Err(format!(
                    "{what} drives node {}, which has a matrix (an animated node gives TRS)",
                    node.index()
                ));
            }
            let per_key = match property {
                Property::MorphTargetWeights => {
                    let targets =
                        node.mesh().and_then(|m| m.primitives().next()).map_or(0, |p| p.morph_targets().len());
                    if targets == 0 {
                        return Err(format!(
                            "{what} drives the weights of node {}, which has no morph targets",
                            node.index()
                        ));
                    }
                    targets
                }
                _ => 1,
            };
            let sampler = channel.sampler();
            let (input, output) = (sampler.input(), sampler.output());
            let keys = if sampler.interpolation() == Interpolation::CubicSpline { 3 } else { 1 };
            let want = input.count() * keys * per_key;
            if output.count() != want {
                return Err(format!(
                    "{what}: its sampler {}'s output (accessor {}) has {} elements for {} keys of {property:?} (it needs {want})",
                    sampler.index(),
                    output.index(),
                    output.count(),
                    input.count()
                ));
            }
            output_type(&output, property)
                .map_err(|e| format!("{what}: its sampler {}'s output {e}", sampler.index()))?;
        }
    }
    Ok(())
}

/// The accessor types glTF allows for an output of `property`.
fn output_type(a: &gltf::Accessor, property: Property) -> Result<(), String> {
    let normalized = |t: DataType| t == DataType::F32 || (a.normalized() && t != DataType::U32);
    let ok = match property {
        Property::Translation | Property::Scale => a.dimensions() == Dimensions::Vec3 && a.data_type() == DataType::F32,
        Property::Rotation => a.dimensions() == Dimensions::Vec4 && normalized(a.data_type()),
        Property::MorphTargetWeights => a.dimensions() == Dimensions::Scalar && normalized(a.data_type()),
    };
    if ok {
        Ok(())
    } else {
        Err(format!(
            "(accessor {}) is {:?} of {:?}{}, which glTF does not allow for {property:?}",
            a.index(),
            a.dimensions(),
            a.data_type(),
            if a.normalized() { " normalized" } else { "" }
        ))
    }
}
