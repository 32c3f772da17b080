//! A checked animation, and posing a scene at a frame: every moving target reset to its
//! value at rest, its keyframed tracks set, then its motions applied.

use super::format::Interpolation;
use crate::scene::file::{LightDesc, Scale, SceneFile};
use crate::scene::mesh::MeshData;
use glam::{EulerRot, Quat, Vec3};
use std::ops::Range;
use std::sync::Arc;

/// What a track or motion moves.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Target {
    Camera,
    /// Objects of the expanded scene: one written object, or every object of a grid.
    Objects(Range<usize>),
    Light(usize),
}

/// A keyframed property.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Property {
    Translate,
    Rotate,
    Scale,
    /// A point light's position.
    Position,
    /// A directional light's direction.
    Direction,
    /// A rect light's centre.
    Center,
    /// Euler angles (degrees) turning a rect light's `u` and `v` from the file's.
    Orientation,
    Color,
    Intensity,
    Eye,
    LookAt,
    Up,
    FieldOfView,
}

/// A keyframed property of one target.
#[derive(Clone, Debug)]
pub struct Track {
    pub target: Target,
    pub property: Property,
    pub interpolation: Interpolation,
    /// (time, value), times strictly increasing; scalars are stored in all three slots.
    pub keys: Vec<(f32, [f32; 3])>,
}

/// A shorthand motion, checked; angles in degrees, axes of unit length.
#[derive(Clone, Debug)]
pub enum MotionKind {
    Orbit { center: Vec3, axis: Vec3, cycle: Cycle },
    Bounce { height: f32, axis: Vec3, cycle: Cycle },
    Spin { degrees_per_second: Vec3 },
}

/// The timing of a periodic motion, per object of its target.
#[derive(Clone, Copy, Debug)]
pub struct Cycle {
    /// Seconds per cycle.
    pub period: f32,
    /// Degrees into the cycle at time 0.
    pub phase: f32,
    /// Degrees more for each further object of a grid.
    pub phase_step: f32,
    /// The k-th of K objects has period x (1 + period_spread x k / K).
    pub period_spread: f32,
}

impl Cycle {
    /// Degrees into the cycle of the `k`-th of `count` objects at `t`, one cycle being `full`
    /// degrees; reduced modulo 360 so that long times keep their precision in the sine.
    fn degrees(&self, full: f32, t: f32, k: usize, count: usize) -> f32 {
        let period = self.period * (1.0 + self.period_spread * k as f32 / count.max(1) as f32);
        (full * ((t / period) % 1.0) + self.phase + self.phase_step * k as f32) % 360.0
    }

    fn orbit(&self, axis: Vec3, t: f32, k: usize, count: usize) -> Quat {
        Quat::from_axis_angle(axis, self.degrees(360.0, t, k, count).to_radians())
    }

    fn bounce(&self, height: f32, axis: Vec3, t: f32, k: usize, count: usize) -> Vec3 {
        axis * height * self.degrees(180.0, t, k, count).to_radians().sin().abs()
    }
}

#[derive(Clone, Debug)]
pub struct Motion {
    pub target: Target,
    pub kind: MotionKind,
}

/// What an animation moves.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Moves {
    /// Objects: the TLAS changes.
    pub objects: bool,
    pub lights: bool,
    pub camera: bool,
    /// Meshes: their vertices change (skins, morph targets), and their BLASes with them.
    pub meshes: bool,
}

/// A checked `[animation]`.
#[derive(Clone, Debug)]
pub struct Animation {
    pub frames: u32,
    pub fps: f32,
    pub tracks: Vec<Track>,
    pub motions: Vec<Motion>,
    /// The scene as written, everything at rest: every frame is posed from it.
    pub rest: Box<SceneFile>,
    /// Where the posed scene's objects are parts of placed glTF models: each object's index
    /// in `rest` (whose objects are the models' objects as written), whose translation,
    /// rotation and scale it takes, so that a model's parts move as one. `None`: the
    /// objects are `rest`'s.
    pub owners: Option<Vec<usize>>,
    /// What poses the parts of models that move by their own animation (glTF clips): a
    /// model given alone, whose scene has no tracks or motions, or models placed by a scene
    /// file, whose `[animation]` (if any) then places their objects and the clip poses each
    /// part under its object.
    pub clip: Option<Arc<dyn Clip>>,
}

/// A model's own animation: it poses the scene at a time, as its file says.
pub trait Clip: std::fmt::Debug + Send + Sync {
    /// Seconds at frame 0.
    fn start(&self) -> f32;
    fn fps(&self) -> f32;
    fn frames(&self) -> u32;
    /// What it moves.
    fn moves(&self) -> Moves;
    /// Writes the values at `time` seconds of what it moves into `out`, a copy of the scene.
    fn pose(&self, time: f32, out: &mut SceneFile);
    /// The meshes it poses (skins, morph targets) at `time` seconds, by shape name; an error
    /// says what could not be posed then.
    fn meshes(&self, time: f32) -> Result<Vec<(String, MeshData)>, String>;
    /// For each object of the scene, the rigid body it belongs to: objects of one body are
    /// placed alike at every time (a node's primitives), so they may share a TLAS instance.
    fn bodies(&self) -> Vec<usize>;
}

impl Animation {
    /// Seconds at frame `frame`.
    pub fn time(&self, frame: u32) -> f32 {
        self.clip.as_ref().map_or(0.0, |c| c.start()) + frame as f32 / self.fps
    }

    /// What changes from frame to frame: only that is rewritten on the GPU.
    pub fn moves(&self) -> Moves {
        let clip = self.clip.as_ref().map(|c| c.moves()).unwrap_or_default();
        let any = |f: fn(&Target) -> bool| self.targets().any(f);
        Moves {
            objects: clip.objects || any(|t| matches!(t, Target::Objects(_))),
            lights: clip.lights || any(|t| matches!(t, Target::Light(_))),
            camera: clip.camera || any(|t| matches!(t, Target::Camera)),
            meshes: clip.meshes,
        }
    }

    pub(super) fn targets(&self) -> impl Iterator<Item = &Target> {
        self.tracks.iter().map(|t| &t.target).chain(self.motions.iter().map(|m| &m.target))
    }

    /// Writes frame `frame`'s values of everything that moves into `out`, a copy of the scene:
    /// each moving target is reset to its value at rest, its tracks set, then its motions
    /// applied in file order; with `owners`, on the objects as written, whose placement
    /// (translation, rotation, scale) each part then takes. A clip then poses the parts of
    /// its models (their `matrix`, under that placement) at its time.
    pub fn pose(&self, frame: u32, out: &mut SceneFile) {
        match &self.owners {
            Some(owners) => {
                let mut written = (*self.rest).clone();
                self.pose_written(frame, &mut written);
                (out.camera, out.lights) = (written.camera, written.lights);
                for (part, &owner) in out.objects.iter_mut().zip(owners) {
                    let o = &written.objects[owner];
                    (part.translate, part.rotate, part.scale) = (o.translate, o.rotate, o.scale);
                }
            }
            _ => self.pose_written(frame, out),
        }
        if let Some(clip) = &self.clip {
            clip.pose(self.time(frame), out);
        }
    }

    /// Which objects move as one, each object's body (`Clip::bodies`), where the animation
    /// knows: a clip does, `[animation]` does not (every object then moves on its own).
    pub fn bodies(&self) -> Option<Vec<usize>> {
        self.clip.as_ref().map(|c| c.bodies())
    }

    /// The meshes posed at frame `frame` (a clip's skins and morph targets), by shape name.
    pub fn meshes(&self, frame: u32) -> Result<Vec<(String, MeshData)>, String> {
        let Some(clip) = &self.clip else { return Ok(Vec::new()) };
        let time = self.time(frame);
        clip.meshes(time).map_err(|e| format!("frame {frame} (t = {time} s): {e}"))
    }

    /// An animation that plays `clip`, a model's own, over the scene `rest`.
    pub fn playing(clip: Arc<dyn Clip>, rest: &SceneFile) -> Animation {
        let (frames, fps) = (clip.frames(), clip.fps());
        let rest = Box::new(rest.clone());
        Animation { frames, fps, tracks: Vec::new(), motions: Vec::new(), rest, owners: None, clip: Some(clip) }
    }

    /// `pose` of a scene whose objects are `rest`'s, by the tracks and motions, whose times
    /// start at 0 (a clip's start, `--time`, is the clip's).
    fn pose_written(&self, frame: u32, out: &mut SceneFile) {
        let base = &self.rest;
        let t = frame as f32 / self.fps;
        for target in self.targets() {
            reset(base, out, target);
        }
        for track in &self.tracks {
            set(out, &track.target, track.property, track.value_at(t));
        }
        for motion in &self.motions {
            apply(out, motion, t);
        }
    }
}

impl Track {
    /// The value at `t` seconds: held before the first key and after the last.
    pub fn value_at(&self, t: f32) -> [f32; 3] {
        let next = self.keys.partition_point(|k| k.0 <= t);
        if next == self.keys.len() {
            return self.keys.last().map_or([0.0; 3], |k| k.1);
        }
        if next == 0 {
            return self.keys[0].1;
        }
        let ((t0, a), (t1, b)) = (self.keys[next - 1], self.keys[next]);
        let mut u = (t - t0) / (t1 - t0);
        if self.interpolation == Interpolation::Smooth {
            u = u * u * (3.0 - 2.0 * u);
        }
        std::array::from_fn(|i| a[i] + (b[i] - a[i]) * u)
    }
}

fn reset(base: &SceneFile, out: &mut SceneFile, target: &Target) {
    match target {
        Target::Camera => out.camera = base.camera,
        Target::Light(i) => out.lights[*i] = base.lights[*i].clone(),
        Target::Objects(range) => {
            for (o, b) in out.objects[range.clone()].iter_mut().zip(&base.objects[range.clone()]) {
                (o.translate, o.rotate, o.scale) = (b.translate, b.rotate, b.scale);
            }
        }
    }
}

/// Euler angles in degrees (x, then y, then z, as objects turn) as a rotation.
fn euler(degrees: [f32; 3]) -> Quat {
    let [x, y, z] = degrees.map(f32::to_radians);
    Quat::from_euler(EulerRot::ZYX, z, y, x)
}

fn turn(q: Quat, v: &mut [f32; 3]) {
    *v = (q * Vec3::from(*v)).into();
}

fn set(out: &mut SceneFile, target: &Target, property: Property, v: [f32; 3]) {
    match target {
        Target::Camera => match property {
            Property::Eye => out.camera.eye = v,
            Property::LookAt => out.camera.target = v,
            Property::Up => out.camera.up = v,
            _ => out.camera.fov_y_degrees = v[0],
        },
        Target::Objects(range) => {
            for o in &mut out.objects[range.clone()] {
                match property {
                    Property::Translate => o.translate = v,
                    Property::Rotate => o.rotate = v,
                    _ => o.scale = Scale::PerAxis(v),
                }
            }
        }
        Target::Light(i) => set_light(&mut out.lights[*i], property, v),
    }
}

fn set_light(light: &mut LightDesc, property: Property, v: [f32; 3]) {
    match (light, property) {
        (LightDesc::Rect { u, v: v_edge, .. }, Property::Orientation) => {
            let q = euler(v);
            turn(q, u);
            turn(q, v_edge);
        }
        (LightDesc::Point { position: p, .. }, Property::Position)
        | (LightDesc::Directional { direction: p, .. }, Property::Direction)
        | (LightDesc::Rect { center: p, .. }, Property::Center) => *p = v,
        (
            LightDesc::Point { color, .. } | LightDesc::Directional { color, .. } | LightDesc::Rect { color, .. },
            Property::Color,
        ) => *color = v,
        (
            LightDesc::Point { intensity, .. }
            | LightDesc::Directional { intensity, .. }
            | LightDesc::Rect { intensity, .. },
            Property::Intensity,
        ) => *intensity = v[0],
        // resolve() admits only the pairs above.
        _ => {}
    }
}

fn orbit_point(q: Quat, center: Vec3, p: &mut [f32; 3]) {
    *p = (center + q * (Vec3::from(*p) - center)).into();
}

fn apply(out: &mut SceneFile, motion: &Motion, t: f32) {
    match (&motion.target, &motion.kind) {
        (Target::Objects(range), kind) => {
            let count = range.len();
            for (k, o) in out.objects[range.clone()].iter_mut().enumerate() {
                match *kind {
                    MotionKind::Orbit { center, axis, cycle } => {
                        orbit_point(cycle.orbit(axis, t, k, count), center, &mut o.translate)
                    }
                    MotionKind::Bounce { height, axis, cycle } => {
                        o.translate = (Vec3::from(o.translate) + cycle.bounce(height, axis, t, k, count)).into();
                    }
                    MotionKind::Spin { degrees_per_second } => {
                        let turned = Vec3::from(o.rotate) + degrees_per_second * t;
                        o.rotate = turned.to_array().map(|d| d % 360.0);
                    }
                }
            }
        }
        (Target::Camera, MotionKind::Orbit { center, axis, cycle }) => {
            orbit_point(cycle.orbit(*axis, t, 0, 1), *center, &mut out.camera.eye)
        }
        (Target::Camera, MotionKind::Bounce { height, axis, cycle }) => {
            out.camera.eye = (Vec3::from(out.camera.eye) + cycle.bounce(*height, *axis, t, 0, 1)).into();
        }
        (Target::Light(i), kind) => move_light(&mut out.lights[*i], kind, t),
        // resolve() rejects a spinning camera.
        (Target::Camera, MotionKind::Spin { .. }) => {}
    }
}

fn move_light(light: &mut LightDesc, kind: &MotionKind, t: f32) {
    match (light, kind) {
        (LightDesc::Point { position: p, spot, .. }, &MotionKind::Orbit { center, axis, cycle }) => {
            // A spot light orbits rigidly, as a rect light does: its cone turns with it.
            let q = cycle.orbit(axis, t, 0, 1);
            orbit_point(q, center, p);
            if let Some(spot) = spot {
                turn(q, &mut spot.direction);
            }
        }
        (LightDesc::Rect { center: c, u, v, .. }, &MotionKind::Orbit { center, axis, cycle }) => {
            // A rect light orbits rigidly: it keeps facing the axis as it goes round.
            let q = cycle.orbit(axis, t, 0, 1);
            orbit_point(q, center, c);
            turn(q, u);
            turn(q, v);
        }
        (LightDesc::Directional { direction, .. }, &MotionKind::Orbit { axis, cycle, .. }) => {
            turn(cycle.orbit(axis, t, 0, 1), direction)
        }
        (
            LightDesc::Point { position: p, .. } | LightDesc::Rect { center: p, .. },
            &MotionKind::Bounce { height, axis, cycle },
        ) => *p = (Vec3::from(*p) + cycle.bounce(height, axis, t, 0, 1)).into(),
        (LightDesc::Rect { u, v, .. }, &MotionKind::Spin { degrees_per_second }) => {
            let q = euler((degrees_per_second * t).to_array().map(|d| d % 360.0));
            turn(q, u);
            turn(q, v);
        }
        // resolve() admits only the pairs above.
        _ => {}
    }
}
