//! glTF animations sampled at a time, the ones a viewer plays together (`playing`): each
//! channel's translation, rotation, scale or morph target weights of its node, by the
//! sampler's interpolation (`STEP`, `LINEAR` with rotations by spherical interpolation,
//! `CUBICSPLINE` by Hermite splines of its tangents), integers normalized as glTF says.
//! Each animation loops over its own length (its channels' last key), as glTF-Sample-Viewer
//! plays it; within that, before a channel's first key it holds the first key's value, after
//! its last the last's.
//! The file's rules (keys rising, output counts and types) are `rules`'; every accessor is
//! bounds-checked there before this reads it.

use glam::{Mat4, Quat, Vec3};
use gltf::animation::util::ReadOutputs;
use gltf::animation::Interpolation;
use std::collections::{BTreeMap, BTreeSet};

/// A node's translation, rotation and scale.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Trs {
    pub translation: Vec3,
    pub rotation: Quat,
    pub scale: Vec3,
}

impl Trs {
    /// `node`'s own, as its file gives it.
    pub fn rest(node: &gltf::Node) -> Trs {
        let (t, r, s) = node.transform().decomposed();
        Trs { translation: Vec3::from(t), rotation: Quat::from_array(r), scale: Vec3::from(s) }
    }

    pub fn matrix(&self) -> Mat4 {
        Mat4::from_scale_rotation_translation(self.scale, self.rotation, self.translation)
    }
}

/// What an animation sets at a time: the local matrix of every node it moves, and the morph
/// target weights of every node whose weights it drives.
#[derive(Default)]
pub struct Posed {
    pub matrices: BTreeMap<usize, Mat4>,
    pub weights: BTreeMap<usize, Vec<f32>>,
}

/// An animation played (`playing`): its index in the file, and the last key of its channels
/// that twinray leaves out (`KHR_animation_pointer`'s, `buffers::node_channels`), which still
/// count toward its length as glTF-Sample-Viewer counts them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Played {
    pub index: usize,
    pub left_out_end: f32,
}

/// The animations of `doc` played together, as glTF-Sample-Viewer starts them when it opens a
/// file: in the file's order, each that drives no property of a node (its translation,
/// rotation, scale or weights) that an animation already chosen drives. So a file with one
/// animation per object plays them all, and one whose animations are alternative cycles of one
/// rig (a walk, a run) plays its first. `left_out_ends` are each animation's ends of the
/// channels left out (`buffers::Loaded`).
pub fn playing(doc: &gltf::Document, left_out_ends: &[f32]) -> Vec<Played> {
    let mut driven = BTreeSet::new();
    let mut chosen = Vec::new();
    for animation in doc.animations() {
        let own: BTreeSet<(usize, u8)> =
            animation.channels().map(|c| (c.target().node().index(), c.target().property() as u8)).collect();
        if own.is_disjoint(&driven) {
            driven.extend(own);
            let left_out_end = left_out_ends.get(animation.index()).copied().unwrap_or(0.0);
            chosen.push(Played { index: animation.index(), left_out_end });
        }
    }
    chosen
}

/// `animations` of `doc`, in the file's order, each with what `playing` says of it.
fn played<'a>(
    doc: &'a gltf::Document,
    animations: &'a [Played],
) -> impl Iterator<Item = (gltf::Animation<'a>, &'a Played)> {
    doc.animations().filter_map(|a| Some((a.clone(), animations.iter().find(|p| p.index == a.index())?)))
}

/// The channels of `animations` of `doc`, in the file's order.
pub fn channels<'a>(
    doc: &'a gltf::Document,
    animations: &'a [Played],
) -> impl Iterator<Item = gltf::animation::Channel<'a>> {
    played(doc, animations).flat_map(|(a, _)| a.channels())
}

/// What `animations` of `doc` (driving no property twice, `playing`) set at `time` seconds,
/// each at its own time in its cycle (`within_cycle`; its length the last key of its channels,
/// those left out included): each node they move at its rest
/// transform with the channels' values in place of what they drive, and the weights they
/// drive.
pub fn pose(doc: &gltf::Document, buffers: &[Vec<u8>], animations: &[Played], time: f32) -> Posed {
    let mut moved: BTreeMap<usize, Trs> = BTreeMap::new();
    let mut weights = BTreeMap::new();
    let get = |b: gltf::Buffer| buffers.get(b.index()).map(Vec::as_slice);
    for (animation, played) in played(doc, animations) {
        let keyed: Vec<(gltf::animation::Channel, Vec<f32>)> = animation
            .channels()
            .filter_map(|c| Some((c.clone(), c.reader(get).read_inputs()?.collect())))
            .filter(|(_, times): &(_, Vec<f32>)| !times.is_empty())
            .collect();
        let length = keyed.iter().map(|(_, times)| times[times.len() - 1]).fold(played.left_out_end, f32::max);
        let time = within_cycle(time, length);
        for (channel, times) in keyed {
            let node = channel.target().node();
            let interpolation = channel.sampler().interpolation();
            let trs = moved.entry(node.index()).or_insert_with(|| Trs::rest(&node));
            match channel.reader(get).read_outputs() {
                Some(ReadOutputs::Translations(v)) => {
                    let values: Vec<Vec3> = v.map(Vec3::from).collect();
                    trs.translation = sample(&times, &values, interpolation, time, |a, b, s| a.lerp(b, s));
                }
                Some(ReadOutputs::Scales(v)) => {
                    let values: Vec<Vec3> = v.map(Vec3::from).collect();
                    trs.scale = sample(&times, &values, interpolation, time, |a, b, s| a.lerp(b, s));
                }
                Some(ReadOutputs::Rotations(v)) => {
                    let values: Vec<Quat> = v.into_f32().map(Quat::from_array).collect();
                    let q = sample(&times, &values, interpolation, time, |a, b, s| a.slerp(b, s));
                    trs.rotation = q.normalize();
                }
                Some(ReadOutputs::MorphTargetWeights(v)) => {
                    let values: Vec<f32> = v.into_f32().collect();
                    weights.insert(node.index(), sample_weights(&times, &values, interpolation, time));
                }
                None => {}
            }
        }
    }
    let matrices = moved.into_iter().map(|(node, trs)| (node, trs.matrix())).collect();
    Posed { matrices, weights }
}

/// `time` as an animation `length` seconds long shows it, looped as glTF-Sample-Viewer loops
/// it (its time modulo the animation's length): up to `length` the time itself, after it the
/// time into the current cycle. At a whole number of cycles this gives the cycle's end (its
/// last key), the value the viewer shows up to that instant, where its modulo gives the next
/// cycle's start: so the last frame of a clip, and `--time` at an animation's end, show the
/// last key.
fn within_cycle(time: f32, length: f32) -> f32 {
    if length <= 0.0 || time <= length {
        return time;
    }
    let into = time % length;
    if into == 0.0 {
        length
    } else {
        into
    }
}

/// The weights at `time` of a weights channel: its outputs hold, per key, one weight per
/// target (for a cubic spline, the in-tangents of every target, then the values, then the
/// out-tangents), so the targets are the outputs per key; each target's weight is sampled as
/// a value of its own.
fn sample_weights(times: &[f32], outputs: &[f32], interpolation: Interpolation, time: f32) -> Vec<f32> {
    let per_key = if interpolation == Interpolation::CubicSpline { 3 } else { 1 };
    let targets = outputs.len() / (times.len() * per_key);
    (0..targets)
        .map(|i| {
            // Target i's own keys, in the layout `sample` reads (in, value, out per key when cubic).
            let own: Vec<f32> = (0..times.len() * per_key)
                .map(|j| outputs[(j / per_key) * per_key * targets + (j % per_key) * targets + i])
                .collect();
            sample(times, &own, interpolation, time, |a, b, s| a + (b - a) * s)
        })
        .collect()
}

/// What a value type needs for a cubic spline: sums and scaling.
pub trait Spline: Copy + std::ops::Add<Output = Self> + std::ops::Mul<f32, Output = Self> {}
impl Spline for Vec3 {}
impl Spline for f32 {}
impl Spline for Quat {}

/// The value at `time` of keys at `times` (rising) with `values` (one per key, three per key
/// for a cubic spline: in-tangent, value, out-tangent), `linear` mixing two keys' values.
pub fn sample<T: Spline>(
    times: &[f32],
    values: &[T],
    interpolation: Interpolation,
    time: f32,
    linear: impl Fn(T, T, f32) -> T,
) -> T {
    let cubic = interpolation == Interpolation::CubicSpline;
    let value = |k: usize| if cubic { values[3 * k + 1] } else { values[k] };
    let last = times.len() - 1;
    // The key at or before `time` (the first key before it, the last after it).
    let k = times.partition_point(|&t| t <= time).saturating_sub(1);
    if time <= times[0] || k >= last {
        return value(if time <= times[0] { 0 } else { last });
    }
    let span = times[k + 1] - times[k];
    let s = (time - times[k]) / span;
    match interpolation {
        Interpolation::Step => value(k),
        Interpolation::Linear => linear(value(k), value(k + 1), s),
        Interpolation::CubicSpline => {
            let (s2, s3) = (s * s, s * s * s);
            let out_tangent = values[3 * k + 2] * span;
            let in_tangent = values[3 * (k + 1)] * span;
            value(k) * (2.0 * s3 - 3.0 * s2 + 1.0)
                + out_tangent * (s3 - 2.0 * s2 + s)
                + value(k + 1) * (-2.0 * s3 + 3.0 * s2)
                + in_tangent * (s3 - s2)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TIMES: [f32; 3] = [1.0, 2.0, 4.0];

    #[test]
    fn past_its_length_an_animation_is_at_its_time_into_the_cycle() {
        for (time, want) in [(0.0, 0.0), (1.0, 1.0), (4.0, 4.0), (5.0, 1.0), (8.0, 4.0), (9.5, 1.5), (12.0, 4.0)] {
            assert_eq!(within_cycle(time, 4.0), want, "{time} s");
        }
        // An animation of one instant (every key at 0 s) has no cycle: the time is left.
        assert_eq!(within_cycle(3.0, 0.0), 3.0);
    }

    #[test]
    fn each_interpolation_holds_before_the_first_key_and_after_the_last() {
        let values = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let lerp = |a: Vec3, b: Vec3, s: f32| a.lerp(b, s);
        for interpolation in [Interpolation::Step, Interpolation::Linear] {
            assert_eq!(sample(&TIMES, &values, interpolation, 0.0, lerp), Vec3::ZERO);
            assert_eq!(sample(&TIMES, &values, interpolation, 1.0, lerp), Vec3::ZERO);
            assert_eq!(sample(&TIMES, &values, interpolation, 2.0, lerp), Vec3::X);
            assert_eq!(sample(&TIMES, &values, interpolation, 9.0, lerp), Vec3::Y);
        }
        assert_eq!(sample(&TIMES, &values, Interpolation::Step, 1.5, lerp), Vec3::ZERO);
        assert_eq!(sample(&TIMES, &values, Interpolation::Linear, 1.5, lerp), Vec3::X * 0.5);
        assert_eq!(sample(&TIMES, &values, Interpolation::Linear, 3.0, lerp), Vec3::new(0.5, 0.5, 0.0));
    }

    /// A cubic spline passes through its keys, and with tangents of a straight line at unit
    /// speed between keys one second apart it is that line; its tangents are per second, so a
    /// span of two seconds doubles their reach.
    #[test]
    fn a_cubic_spline_is_hermite_with_tangents_per_second() {
        let lerp = |a: Vec3, b: Vec3, s: f32| a.lerp(b, s);
        let (t, v) = (Vec3::X, Vec3::ZERO);
        let keys = [t, v, t, t, Vec3::X, t, t, Vec3::X * 3.0, t];
        let at = |time: f32| sample(&TIMES, &keys, Interpolation::CubicSpline, time, lerp);
        assert_eq!(at(1.0), Vec3::ZERO);
        assert_eq!(at(2.0), Vec3::X);
        assert!((at(1.25) - Vec3::X * 0.25).length() < 1e-6, "{}", at(1.25));
        // From 1 at 2 s to 3 at 4 s with slopes 1: the Hermite curve's midpoint is 2.
        assert!((at(3.0) - Vec3::X * 2.0).length() < 1e-6, "{}", at(3.0));
        assert_eq!(at(5.0), Vec3::X * 3.0);
    }

    /// Two targets' weights, one key per time: each target follows its own keys, and a
    /// cubic spline's in-tangents, values and out-tangents are each a run of all targets.
    #[test]
    fn each_target_weight_is_sampled_from_its_own_keys() {
        let outputs = [0.0, 1.0, 1.0, 0.0, 0.5, 0.5];
        assert_eq!(sample_weights(&TIMES, &outputs, Interpolation::Linear, 1.5), [0.5, 0.5]);
        assert_eq!(sample_weights(&TIMES, &outputs, Interpolation::Step, 3.0), [1.0, 0.0]);
        assert_eq!(sample_weights(&TIMES, &outputs, Interpolation::Linear, 9.0), [0.5, 0.5]);
        // Keys at 1 s and 2 s; target 0 from 0 to 1, target 1 from 1 to 0, every tangent 0.
        let cubic = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0];
        let mid = sample_weights(&TIMES[..2], &cubic, Interpolation::CubicSpline, 1.5);
        assert!((mid[0] - 0.5).abs() < 1e-6 && (mid[1] - 0.5).abs() < 1e-6, "{mid:?}");
        let early = sample_weights(&TIMES[..2], &cubic, Interpolation::CubicSpline, 1.25);
        assert!(early[0] < 0.25 && early[1] > 0.75, "flat tangents ease out of the keys: {early:?}");
    }

    #[test]
    fn rotations_turn_the_short_way_at_a_steady_rate() {
        let (a, b) = (Quat::IDENTITY, Quat::from_rotation_y(std::f32::consts::FRAC_PI_2));
        // The same rotation as b, written with its sign turned: the short way is still 90 degrees.
        let keys = [a, -b];
        let q = sample(&TIMES[..2], &keys, Interpolation::Linear, 1.5, |a, b, s| a.slerp(b, s));
        let want = Quat::from_rotation_y(std::f32::consts::FRAC_PI_4);
        assert!(q.normalize().angle_between(want) < 1e-4, "{q}");
    }
}
