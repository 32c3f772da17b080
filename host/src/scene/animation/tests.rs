//! Posing and checking animations, on small scenes written here.

use crate::scene::file::LightDesc;
use crate::scene::{MeshFiles, Scene};

const STILL: &str = r#"
[image]
width = 64
height = 48
[camera]
eye = [0.0, 2.0, 10.0]
target = [0.0, 0.0, 0.0]
up = [0.0, 1.0, 0.0]
fov_y_degrees = 40.0
[materials.m]
kind = "diffuse"
color = [0.5, 0.5, 0.5]
[[lights]]
kind = "rect"
center = [2.0, 4.0, 0.0]
u = [1.0, 0.0, 0.0]
v = [0.0, 0.0, 1.0]
color = [1.0, 1.0, 1.0]
intensity = 5.0
[[lights]]
kind = "directional"
direction = [1.0, 1.0, 0.0]
color = [1.0, 1.0, 1.0]
intensity = 1.0
[shapes.ball]
kind = "sphere"
radius = 0.5
[[objects]]
shape = "ball"
material = "m"
translate = [1.0, 0.0, 0.0]
[[grids]]
shape = "ball"
materials = ["m"]
count = [4, 1, 1]
spacing = [2.0, 0.0, 0.0]
origin = [-3.0, 0.0, 5.0]
"#;

fn scene(animation: &str) -> Result<Scene, String> {
    Scene::parse(&format!("{STILL}\n{animation}"), "test.toml", MeshFiles::Builtin).map_err(|e| e.to_string())
}

fn posed(animation: &str, frame: u32) -> Scene {
    scene(animation).unwrap_or_else(|e| panic!("{e}")).at_frame(frame).unwrap()
}

fn close(a: [f32; 3], b: [f32; 3]) -> bool {
    a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-5)
}

const KEYS: &str = r#"
[animation]
frames = 5
fps = 1
[[animation.tracks]]
target = "object 0"
property = "translate"
keys = [{ time = 1.0, value = [0.0, 0.0, 0.0] }, { time = 3.0, value = [4.0, 2.0, 0.0] }]
"#;

#[test]
fn linear_keys_hold_outside_and_interpolate_between() {
    let at = |frame| posed(KEYS, frame).file.objects[0].translate;
    assert_eq!(at(0), [0.0, 0.0, 0.0], "held before the first key");
    assert_eq!(at(2), [2.0, 1.0, 0.0]);
    assert_eq!(at(3), [4.0, 2.0, 0.0]);
    assert_eq!(at(4), [4.0, 2.0, 0.0], "held after the last key");
}

#[test]
fn smooth_keys_ease_in_and_out() {
    let smooth = KEYS.replace("property = \"translate\"", "property = \"translate\"\ninterpolation = \"smooth\"");
    let text = smooth.replace("frames = 5\nfps = 1", "frames = 9\nfps = 2");
    // t = 1.5 s is a quarter of the way: smoothstep(0.25) = 0.15625.
    let x = posed(&text, 3).file.objects[0].translate[0];
    assert!((x - 4.0 * 0.15625).abs() < 1e-6, "{x}");
    assert_eq!(posed(&text, 4).file.objects[0].translate, [2.0, 1.0, 0.0], "half way is half way");
}

#[test]
fn frame_zero_is_what_the_scene_holds() {
    let s = scene(KEYS).unwrap();
    assert_eq!(
        s.file.objects[0].translate, [0.0; 3],
        "file is posed at frame 0 (key value, not the written [1, 0, 0])"
    );
    assert_eq!(s.frame_count(), 5);
    let still = s.at_frame(2).unwrap();
    assert!(still.animation.is_none() && still.file.animation.is_none());
}

#[test]
fn a_rect_light_orbits_rigidly_and_a_directional_one_turns() {
    let text = r#"
[animation]
frames = 5
fps = 4
[[animation.motions]]
kind = "orbit"
target = "light 0"
period = 4.0
[[animation.motions]]
kind = "orbit"
target = "light 1"
axis = [0.0, 0.0, 1.0]
period = 2.0
"#;
    // 1 s = a quarter turn about +y: x goes to -z.
    let s = posed(text, 4);
    let LightDesc::Rect { center, u, v, .. } = s.file.lights[0] else { panic!() };
    assert!(close(center, [0.0, 4.0, -2.0]), "{center:?}");
    assert!(close(u, [0.0, 0.0, -1.0]) && close(v, [1.0, 0.0, 0.0]), "{u:?} {v:?}");
    // Half a turn about +z.
    let LightDesc::Directional { direction, .. } = s.file.lights[1] else { panic!() };
    assert!(close(direction, [-1.0, -1.0, 0.0]), "{direction:?}");
}

#[test]
fn grids_move_with_phase_steps_and_drift_with_period_spread() {
    let text = r#"
[animation]
frames = 3
fps = 1
[[animation.motions]]
kind = "bounce"
target = "grid 0"
height = 2.0
period = 2.0
phase_step = 90.0
[[animation.motions]]
kind = "spin"
target = "object 0"
degrees_per_second = [0.0, 90.0, 0.0]
"#;
    let s = posed(text, 1);
    // Object 0 is the written one; the grid's four follow. At t = 1: sin(90 + 90 k) per object.
    let heights: Vec<f32> = s.file.objects[1..].iter().map(|o| o.translate[1]).collect();
    assert!(close([heights[0], heights[1], heights[2]], [2.0, 0.0, 2.0]), "{heights:?}");
    assert_eq!(s.file.objects[0].rotate, [0.0, 90.0, 0.0]);
    let drift = r#"
[animation]
frames = 3
fps = 1
[[animation.motions]]
kind = "orbit"
target = "grid 0"
center = [0.0, 0.0, 5.0]
period = 4.0
period_spread = 1.0
"#;
    let s = posed(drift, 1);
    // The first turns a quarter, the third (period 4 x 1.5 = 6) a sixth, in one second.
    let angle = |i: usize, x0: f32| {
        let t = s.file.objects[i].translate;
        (-(t[2] - 5.0)).atan2(t[0]).to_degrees() - if x0 < 0.0 { 180.0 } else { 0.0 }
    };
    assert!((angle(1, -3.0).rem_euclid(360.0) - 90.0).abs() < 1e-3, "{}", angle(1, -3.0));
    assert!((angle(3, 1.0) - 60.0).abs() < 1e-3, "{}", angle(3, 1.0));
}

/// Each bad `[animation]` and what its error must name.
const BAD: &[(&str, &str)] = &[
    ("[animation]\nframes = 0", "animation.frames"),
    ("[animation]\nframes = 2\nfps = 0", "animation.fps"),
    ("[animation]\nframes = 2\nfps = nan", "animation.fps"),
    ("[animation]\nframes = \"many\"", "line 40, column 10"),
    ("[animation]\nframes = 2\nspeed = 3", "unknown field `speed`"),
    (
        "[animation]\nframes = 2\n[[animation.tracks]]\ntarget = \"object 0\"\nproperty = \"translate\"\nkeys = [{ time = 1.0, value = [0.0, 0.0, 0.0] }, { time = 0.5, value = [1.0, 0.0, 0.0] }]",
        "animation.tracks[0].keys[1].time",
    ),
    (
        "[animation]\nframes = 2\n[[animation.tracks]]\ntarget = \"object 0\"\nproperty = \"translate\"\nkeys = [{ time = 0.0, value = [nan, 0.0, 0.0] }]",
        "animation.tracks[0].keys[0].value",
    ),
    (
        "[animation]\nframes = 2\n[[animation.tracks]]\ntarget = \"object 7\"\nproperty = \"translate\"\nkeys = [{ time = 0.0, value = 1.0 }]",
        "animation.tracks[0].target",
    ),
    (
        "[animation]\nframes = 2\n[[animation.tracks]]\ntarget = \"light 0\"\nproperty = \"position\"\nkeys = [{ time = 0.0, value = [0.0, 0.0, 0.0] }]",
        "animation.tracks[0].property",
    ),
    (
        "[animation]\nframes = 2\n[[animation.tracks]]\ntarget = \"camera\"\nproperty = \"fov_y_degrees\"\nkeys = [{ time = 0.0, value = [1.0, 2.0, 3.0] }]",
        "takes one number",
    ),
    (
        "[animation]\nframes = 2\n[[animation.tracks]]\ntarget = \"grid 0\"\nproperty = \"translate\"\nkeys = [{ time = 0.0, value = [0.0, 0.0, 0.0] }]",
        "grids move by motions only",
    ),
    ("[animation]\nframes = 2\n[[animation.tracks]]\ntarget = \"camera\"\nproperty = \"eye\"\nkeys = []", "keys"),
    ("[animation]\nframes = 2\n[[animation.motions]]\nkind = \"spin\"\ntarget = \"camera\"\ndegrees_per_second = [1.0, 0.0, 0.0]", "animation.motions[0] (spin)"),
    ("[animation]\nframes = 2\n[[animation.motions]]\nkind = \"bounce\"\ntarget = \"light 1\"\nheight = 1.0\nperiod = 1.0", "cannot bounce"),
    ("[animation]\nframes = 2\n[[animation.motions]]\nkind = \"orbit\"\ntarget = \"object 0\"\nperiod = -1.0", ".period"),
    ("[animation]\nframes = 2\n[[animation.motions]]\nkind = \"orbit\"\ntarget = \"object 0\"\nperiod = 1.0\naxis = [0.0, 0.0, 0.0]", ".axis"),
    ("[animation]\nframes = 2\n[[animation.motions]]\nkind = \"wobble\"\ntarget = \"object 0\"", "wobble"),
    // Valid at both keys, zero half way: caught by posing every frame.
    (
        "[animation]\nframes = 3\nfps = 1\n[[animation.tracks]]\ntarget = \"light 1\"\nproperty = \"direction\"\nkeys = [{ time = 0.0, value = [1.0, 0.0, 0.0] }, { time = 2.0, value = [-1.0, 0.0, 0.0] }]",
        "frame 1 (t = 1 s): lights[1]: direction must not be zero",
    ),
    (
        "[animation]\nframes = 3\nfps = 1\n[[animation.tracks]]\ntarget = \"object 0\"\nproperty = \"scale\"\nkeys = [{ time = 0.0, value = 1.0 }, { time = 2.0, value = -1.0 }]",
        "frame 1 (t = 1 s): objects[0]: scale must not be zero",
    ),
];

#[test]
fn bad_animations_are_refused_naming_the_field() {
    for (text, expected) in BAD {
        match scene(text) {
            Ok(_) => panic!("accepted:\n{text}"),
            Err(e) => assert!(e.contains(expected), "error for\n{text}\nis {e:?}, expected it to name {expected:?}"),
        }
    }
}

#[test]
fn every_builtin_moving_scene_poses_every_frame() {
    for (name, _) in crate::scene::BUILTIN {
        let s = Scene::load(Some(name)).unwrap();
        if let Some(a) = &s.animation {
            assert!(a.frames > 1, "{name}");
            let (first, last) = (s.at_frame(0).unwrap(), s.at_frame(a.frames - 1).unwrap());
            let moved = first.file.objects.iter().zip(&last.file.objects).any(|(a, b)| a.translate != b.translate);
            assert!(moved, "{name}: nothing moved between the first and the last frame");
        }
    }
}

/// A clip that cannot pose its meshes after 1 s (as a skin whose posed vertices overflow f32).
#[derive(Debug)]
struct FailsLate;

impl super::Clip for FailsLate {
    fn start(&self) -> f32 {
        0.5
    }
    fn fps(&self) -> f32 {
        2.0
    }
    fn frames(&self) -> u32 {
        4
    }
    fn moves(&self) -> super::Moves {
        super::Moves { meshes: true, ..Default::default() }
    }
    fn pose(&self, _: f32, _: &mut crate::scene::file::SceneFile) {}
    fn meshes(&self, time: f32) -> Result<Vec<(String, crate::scene::mesh::MeshData)>, String> {
        if time > 1.0 {
            return Err("mesh 0 posed by node 0: a posed vertex is not finite".into());
        }
        Ok(Vec::new())
    }
    fn bodies(&self) -> Vec<usize> {
        Vec::new()
    }
}

/// A frame whose meshes cannot be posed is an error naming the frame, its time and the mesh,
/// not a still of stale meshes; the frames before it pose.
#[test]
fn a_frame_whose_meshes_cannot_be_posed_is_refused_with_its_time() {
    let mut s = scene("").unwrap();
    s.animation = Some(super::Animation::playing(std::sync::Arc::new(FailsLate), &s.file));
    assert!(s.at_frame(1).is_ok());
    let e = s.at_frame(2).expect_err("frame 2 posed").to_string();
    assert!(e.contains("frame 2 (t = 1.5 s): mesh 0 posed by node 0: a posed vertex is not finite"), "{e}");
}
