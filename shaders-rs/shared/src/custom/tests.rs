use super::abi::{self, PARAMETER_FLOATS, PRIMITIVE_FLOATS};
use super::*;
use crate::shapes::spec::{no_check, single, ParamType, Rule, Value};
use glam::{Vec3, Vec4};

/// A capsule about y: `radius`, and `length` between its two caps' centres.
const CAPSULE: CustomShape = CustomShape {
    name: "capsule",
    about: "a capsule \"about\" y",
    hit_kind: 40,
    params: &[Param::positive("radius"), Param::positive("length")],
    check: |v| if v.number("length") > 1e6 { Err("length is too long".into()) } else { Ok(()) },
    primitives: |v| {
        let (r, l) = (v.number("radius"), v.number("length"));
        single(Vec4::new(r, l / 2.0, 0.0, 0.0), Vec3::new(r, l / 2.0 + r, r))
    },
    distance: |p, q| {
        let y = p.y.clamp(-q.a.y, q.a.y);
        (p - DVec3::new(0.0, y, 0.0)).length() - q.a.x
    },
    normal: |p, q| p - DVec3::new(0.0, p.y.clamp(-q.a.y, q.a.y), 0.0),
};

const PANICS: CustomShape = CustomShape {
    name: "panics",
    about: "",
    hit_kind: 41,
    params: &[],
    check: no_check,
    primitives: |_| panic!("no primitives"),
    distance: |_, _| panic!("no distance"),
    normal: |_, _| panic!("no normal"),
};

/// Two colours in waves along y: `color` and black, `period` apart.
const WAVES: CustomMaterial = CustomMaterial {
    name: "waves",
    about: "two colours in waves",
    params: &[Param::finite("color", ParamType::Triple), Param::positive("period")],
    check: |v| if v.number("period") > 100.0 { Err("period is too long".into()) } else { Ok(()) },
    parameters: |v| [Vec3::from(v.triple("color")).extend(1.0), Vec4::new(0.0, 0.0, 0.0, v.number("period"))],
};

#[test]
fn a_material_list_is_checked_by_name_and_keys() {
    assert_eq!(check_materials(&[WAVES]), Ok(()));
    assert!(check_materials(&[WAVES, WAVES]).unwrap_err().contains("material \"waves\" is listed twice"));
    let mut bad = WAVES;
    bad.name = "checker";
    assert!(check_materials(&[bad]).unwrap_err().contains("twinray has a material kind of that name"));
    bad.name = "Waves";
    assert!(check_materials(&[bad]).unwrap_err().contains("lower-case"));
    const KIND: &[Param] = &[Param::positive("kind")];
    bad = WAVES;
    bad.params = KIND;
    assert!(check_materials(&[bad]).unwrap_err().contains("material \"waves\": key \"kind\" is taken"));
}

/// `material` through the C function.
fn material(materials: &[CustomMaterial], index: u32, flat: &[f64]) -> Result<Vec<f32>, String> {
    let mut out = vec![f32::NAN; abi::MATERIAL_FLOATS];
    let mut message = [0u8; 200];
    // SAFETY: the buffers are as long as the counts given.
    let n = unsafe {
        abi::material(materials, index, (flat.as_ptr(), flat.len()), out.as_mut_ptr(), (message.as_mut_ptr(), 200))
    };
    if n < 0 {
        let len = (-n as usize).min(200);
        return Err(String::from_utf8_lossy(&message[..len]).into_owned());
    }
    Ok(out)
}

#[test]
fn a_material_s_parameters_come_from_its_keys_and_its_refusals_as_errors() {
    assert_eq!(material(&[WAVES], 0, &[0.5, 0.25, 1.0, 2.0]).unwrap(), [0.5, 0.25, 1.0, 1.0, 0.0, 0.0, 0.0, 2.0]);
    assert!(material(&[WAVES], 0, &[0.5, 0.25, 1.0, -2.0]).unwrap_err().contains("period must be > 0"));
    assert!(material(&[WAVES], 0, &[0.5, 0.25, 1.0, 200.0]).unwrap_err().contains("period is too long"));
    assert!(material(&[WAVES], 0, &[0.5]).unwrap_err().contains("waves: 1 values given for its keys, fewer"));
    assert!(material(&[WAVES], 1, &[]).unwrap_err().contains("no material 1"));
    let mut panics = WAVES;
    panics.parameters = |_| panic!("no parameters");
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let e = material(&[panics], 0, &[0.5, 0.25, 1.0, 2.0]);
    std::panic::set_hook(hook);
    assert!(e.unwrap_err().contains("waves: its `check` or `parameters` panicked"));
}

#[test]
fn a_list_is_checked_by_name_hit_kind_and_keys() {
    assert_eq!(check_list(&[CAPSULE, PANICS]), Ok(()));
    let mut bad = CAPSULE;
    bad.name = "Capsule";
    assert!(check_list(&[bad]).unwrap_err().contains("lower-case"));
    assert!(check_list(&[CAPSULE, CAPSULE]).unwrap_err().contains("listed twice"));
    let mut low = PANICS;
    low.hit_kind = 6;
    assert!(check_list(&[low]).unwrap_err().contains("hit kind 6 is not in 32..=127"));
    let mut same = PANICS;
    same.hit_kind = 40;
    assert!(check_list(&[CAPSULE, same]).unwrap_err().contains("both report hit kind 40"));
    let mut keys = CAPSULE;
    const KIND: &[Param] = &[Param::positive("kind")];
    keys.params = KIND;
    assert!(check_list(&[keys]).unwrap_err().contains("key \"kind\" is taken"));
    const SEED: &[Param] = &[Param { name: "seed", ty: ParamType::Seed, rule: Rule::Any, default: None }];
    keys.params = SEED;
    assert!(check_list(&[keys]).unwrap_err().contains("is a seed"));
    const NEGATIVE: &[Param] =
        &[Param { name: "r", ty: ParamType::Number, rule: Rule::Positive, default: Some(Value::Number(-1.0)) }];
    keys.params = NEGATIVE;
    assert!(check_list(&[keys]).unwrap_err().contains("the default of r must be > 0"));
}

fn described(shapes: &[CustomShape], materials: &[CustomMaterial]) -> String {
    abi::description(abi::Described { shapes, materials, recursion_depth: 1 })
}

#[test]
fn the_description_names_the_recursion_depth_and_refuses_one_no_driver_has() {
    let depth = |recursion_depth| abi::description(abi::Described { shapes: &[], materials: &[], recursion_depth });
    assert!(depth(2).contains("\"error\":null,\"recursion_depth\":2,"), "{}", depth(2));
    assert!(depth(0).contains("RECURSION_DEPTH is 0, not in 1..=31"), "{}", depth(0));
    assert!(depth(32).contains("RECURSION_DEPTH is 32, not in 1..=31"), "{}", depth(32));
}

#[test]
fn the_description_names_every_key_with_its_rule_and_default_and_escapes_text() {
    let mut with_default = CAPSULE;
    const PAIR: &[Param] =
        &[Param { name: "radius", ty: ParamType::Pair, rule: Rule::Positive, default: Some(Value::Pair([1.0, 2.5])) }];
    with_default.params = PAIR;
    let text = abi::description(abi::Described { shapes: &[with_default], materials: &[WAVES], recursion_depth: 1 });
    assert!(text.starts_with("{\"abi\":2,\"contract\":\""), "{text}");
    assert!(text.contains("\"error\":null"), "{text}");
    assert!(text.contains("\"about\":\"a capsule \\\"about\\\" y\""), "{text}");
    assert!(
        text.contains(
            "{\"name\":\"radius\",\"type\":\"pair\",\"rule\":\"positive\",\"max\":null,\"default\":[1.0, 2.5]}"
        ),
        "{text}"
    );
    assert!(text.ends_with(
        "\"materials\":[{\"name\":\"waves\",\"about\":\"two colours in waves\",\"params\":[{\"name\":\"color\",\
         \"type\":\"triple\",\"rule\":\"finite\",\"max\":null,\"default\":null},{\"name\":\"period\",\"type\":\"number\",\
         \"rule\":\"positive\",\"max\":null,\"default\":null}]}]}"
    ), "{text}");
    assert!(described(&[CAPSULE, CAPSULE], &[]).contains("\"error\":\"shape \\\"capsule\\\" is listed twice\""));
    let mut diffuse = WAVES;
    diffuse.name = "diffuse";
    assert!(described(&[], &[diffuse]).contains("twinray has a material kind of that name"));
}

#[test]
fn describe_reports_the_whole_length_and_writes_what_fits() {
    let crate_ = abi::Described { shapes: &[CAPSULE], materials: &[WAVES], recursion_depth: 1 };
    let whole = abi::description(crate_);
    let mut short = [0u8; 10];
    // SAFETY: 10 writable bytes.
    let n = unsafe { abi::describe(crate_, short.as_mut_ptr(), short.len()) };
    assert_eq!((n, &short[..]), (whole.len(), &whole.as_bytes()[..10]));
}

/// `primitives` through the C function, with room for `capacity` primitives.
fn primitives(shapes: &[CustomShape], index: u32, flat: &[f64], capacity: usize) -> Result<(i64, Vec<f32>), String> {
    let mut out = vec![f32::NAN; capacity * PRIMITIVE_FLOATS];
    let mut message = [0u8; 200];
    // SAFETY: the buffers are as long as the counts given.
    let n = unsafe {
        abi::primitives(shapes, index, flat.as_ptr(), flat.len(), out.as_mut_ptr(), capacity, message.as_mut_ptr(), 200)
    };
    if n < 0 {
        let len = (-n as usize).min(200);
        return Err(String::from_utf8_lossy(&message[..len]).into_owned());
    }
    Ok((n, out))
}

#[test]
fn primitives_pass_the_keys_checks_and_a_panic_as_errors() {
    let (n, out) = primitives(&[CAPSULE], 0, &[0.5, 3.0], 1).unwrap();
    assert_eq!(n, 1);
    assert_eq!(&out[..4], &[0.5, 1.5, 0.0, 0.0]);
    assert_eq!(&out[12..], &[-0.5, -2.0, -0.5, 0.5, 2.0, 0.5]);
    assert_eq!(primitives(&[CAPSULE], 0, &[0.5, 3.0], 0).unwrap().0, 1, "the count, with no room");
    assert!(primitives(&[CAPSULE], 0, &[-0.5, 3.0], 1).unwrap_err().contains("radius must be > 0"));
    assert!(primitives(&[CAPSULE], 0, &[0.5, 3e7], 1).unwrap_err().contains("length is too long"));
    assert!(primitives(&[CAPSULE], 0, &[0.5], 1).unwrap_err().contains("fewer than they take"));
    assert!(primitives(&[CAPSULE], 0, &[0.5, 1.0, 2.0], 1).unwrap_err().contains("more than they take"));
    assert!(primitives(&[CAPSULE], 3, &[], 1).unwrap_err().contains("no shape 3"));
    assert!(primitives(&[CAPSULE, PANICS], 1, &[], 1)
        .unwrap_err()
        .contains("panics: its `check` or `primitives` panicked"));
}

#[test]
fn distance_and_normal_read_the_parameters_and_turn_a_panic_into_nan() {
    let q = [0.5, 1.5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0f64];
    assert_eq!(q.len(), PARAMETER_FLOATS);
    let p = [0.0, 3.0, 0.0f64];
    let mut n = [0.0f64; 3];
    // SAFETY: 8 parameters, 3 coordinates, 3 outputs.
    unsafe {
        assert_eq!(abi::distance(&[CAPSULE], 0, q.as_ptr(), p.as_ptr()), 1.0);
        abi::normal(&[CAPSULE], 0, q.as_ptr(), p.as_ptr(), n.as_mut_ptr());
        assert_eq!(n, [0.0, 1.5, 0.0]);
        let hook = std::panic::take_hook();
        std::panic::set_hook(Box::new(|_| {}));
        let d = abi::distance(&[PANICS], 0, q.as_ptr(), p.as_ptr());
        abi::normal(&[PANICS], 0, q.as_ptr(), p.as_ptr(), n.as_mut_ptr());
        std::panic::set_hook(hook);
        assert!(d.is_nan() && n.iter().all(|x| x.is_nan()));
        assert!(abi::distance(&[CAPSULE], 9, q.as_ptr(), p.as_ptr()).is_nan());
    }
}
