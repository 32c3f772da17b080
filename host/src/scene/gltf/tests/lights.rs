//! KHR_lights_punctual's ranges and spot cones: a spot light is a point light with a cone about
//! its node's -z and the file's angles, a range is kept, and a range or cone glTF forbids is
//! refused in one line naming the light.

use super::{load_text, refused, square, ONE_NODE};
use crate::scene::file::{LightDesc, SpotDesc};

/// The square, and a light node (node 1) turned a quarter turn about x, 2 above it.
fn with_light(light: &str) -> String {
    let nodes = format!(
        r#"{ONE_NODE}, {{"translation": [0, 2, 0], "rotation": [-0.7071067811865476, 0, 0, 0.7071067811865476],
            "extensions": {{"KHR_lights_punctual": {{"light": 0}}}}}}"#
    );
    square(None, &nodes, "").replacen(
        r#""scenes": [{"nodes": [0]}]"#,
        &format!(
            r#""scenes": [{{"nodes": [0, 1]}}], "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {{"KHR_lights_punctual": {{"lights": [{light}]}}}}"#
        ),
        1,
    )
}

#[test]
fn a_spot_light_is_a_point_light_with_a_cone_down_its_nodes_minus_z() {
    let spot = r#"{"type": "spot", "intensity": 3, "range": 5,
        "spot": {"innerConeAngle": 0.3490658503988659, "outerConeAngle": 0.5235987755982988}}"#;
    let model = load_text(&with_light(spot)).unwrap();
    let [LightDesc::Point {
        position,
        intensity,
        range,
        spot: Some(SpotDesc { direction, inner_cone_degrees, outer_cone_degrees }),
        ..
    }] = model.file.lights[..]
    else {
        panic!("{:?}", model.file.lights)
    };
    assert!((glam::Vec3::from(position) - glam::Vec3::new(0.0, 2.0, 0.0)).length() < 1e-6, "{position:?}");
    assert!((glam::Vec3::from(direction) - glam::Vec3::NEG_Y).length() < 1e-6, "{direction:?}");
    assert!((inner_cone_degrees - 20.0).abs() < 1e-4 && (outer_cone_degrees - 30.0).abs() < 1e-4);
    assert_eq!((intensity, range), (3.0, Some(5.0)));
    assert!(model.ignored.is_empty(), "{:?}", model.ignored);
    // glTF's defaults: no range, an inner angle of 0 and an outer one of a quarter turn halved.
    let model = load_text(&with_light(r#"{"type": "spot", "spot": {}}"#)).unwrap();
    let [LightDesc::Point { range: None, spot: Some(s), .. }] = model.file.lights[..] else { panic!() };
    assert_eq!((s.inner_cone_degrees, s.outer_cone_degrees), (0.0, 45.0));
}

#[test]
fn ranges_and_cones_gltf_forbids_are_refused() {
    refused(&with_light(r#"{"type": "point", "range": 0}"#), "KHR_lights_punctual light 0 has a range of 0");
    for cone in
        [r#""innerConeAngle": 0.5, "outerConeAngle": 0.5"#, r#""outerConeAngle": 2.0"#, r#""innerConeAngle": -0.1"#]
    {
        let light = format!(r#"{{"type": "spot", "spot": {{{cone}}}}}"#);
        refused(&with_light(&light), "KHR_lights_punctual light 0 is a spot light of innerConeAngle");
    }
}
