use super::*;
use twinray_shared::custom::{CustomMaterial, CustomShape};
use twinray_shared::shapes::spec::{single, Param, ParamType, Value};

/// A capsule about y of `radius`, its caps' centres `length` apart, as a crate would list it.
const CAPSULE: CustomShape = CustomShape {
    name: "capsule",
    about: "a capsule about y",
    hit_kind: 40,
    params: &[Param::positive("radius"), Param::positive("length")],
    check: |v| if v.number("radius") > v.number("length") { Err("radius must be below length".into()) } else { Ok(()) },
    primitives: |v| {
        let (r, l) = (v.number("radius"), v.number("length"));
        single(Vec4::new(r, l / 2.0, 0.0, 0.0), Vec3::new(r, l / 2.0 + r, r))
    },
    distance: |p, q| (p - DVec3::new(0.0, p.y.clamp(-q.a.y, q.a.y), 0.0)).length() - q.a.x,
    normal: |p, q| p - DVec3::new(0.0, p.y.clamp(-q.a.y, q.a.y), 0.0),
};

/// Two colours in waves along y, `period` apart.
const WAVES: CustomMaterial = CustomMaterial {
    name: "waves",
    about: "waves of a colour",
    params: &[Param::finite("color", ParamType::Triple), Param::positive("period")],
    check: |_| Ok(()),
    parameters: |v| [Vec3::from(v.triple("color")).extend(1.0), Vec4::new(0.0, 0.0, 0.0, v.number("period"))],
};

/// What the test's C functions read; `with_list` changes it, one test at a time.
static LIST: std::sync::RwLock<&'static [CustomShape]> = std::sync::RwLock::new(&[CAPSULE]);

fn list() -> &'static [CustomShape] {
    *LIST.read().unwrap_or_else(|e| e.into_inner())
}

unsafe extern "C" fn describe(out: *mut u8, capacity: usize) -> usize {
    unsafe { abi::describe(abi::Described { shapes: list(), materials: &[WAVES], recursion_depth: 1 }, out, capacity) }
}
unsafe extern "C" fn primitives(s: u32, v: *const f64, n: usize, o: *mut f32, c: usize, m: *mut u8, mc: usize) -> i64 {
    unsafe { abi::primitives(list(), s, v, n, o, c, m, mc) }
}
unsafe extern "C" fn distance(s: u32, q: *const f64, p: *const f64) -> f64 {
    unsafe { abi::distance(list(), s, q, p) }
}
unsafe extern "C" fn normal(s: u32, q: *const f64, p: *const f64, o: *mut f64) {
    unsafe { abi::normal(list(), s, q, p, o) }
}

unsafe extern "C" fn material(i: u32, v: *const f64, n: usize, o: *mut f32, m: *mut u8, mc: usize) -> i64 {
    unsafe { abi::material(&[WAVES], i, (v, n), o, (m, mc)) }
}

const FUNCTIONS: Functions = Functions { describe, primitives, distance, normal, material };

static LOCK: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// A crate of one shape (`capsule`) and one material (`waves`: keys `color` and `period`),
/// read through its C functions, for tests of other layers.
pub(crate) fn test_kinds() -> &'static CrateKinds {
    Box::leak(Box::new(with_list(&[CAPSULE]).unwrap()))
}

/// The crate shapes of `shapes`, read through the C functions.
fn with_list(shapes: &'static [CustomShape]) -> Result<CrateKinds, String> {
    let _one = LOCK.lock().unwrap_or_else(|e| e.into_inner());
    *LIST.write().unwrap_or_else(|e| e.into_inner()) = shapes;
    let read = CrateKinds::from_functions("test".into(), FUNCTIONS);
    *LIST.write().unwrap_or_else(|e| e.into_inner()) = &[CAPSULE];
    read
}

#[test]
fn a_crates_shape_is_read_with_its_keys_and_computes_through_its_functions() {
    let shapes = with_list(&[CAPSULE]).unwrap();
    let (index, capsule) = shapes.shape("capsule").unwrap();
    assert_eq!((index, capsule.module, capsule.hit_kind), (0, "capsule_intersection", 40));
    assert_eq!(capsule.params.iter().map(|p| p.name).collect::<Vec<_>>(), ["radius", "length"]);
    let values = Values(vec![("radius", Value::Number(0.5)), ("length", Value::Number(2.0))]);
    let made = shapes.primitives(0, &values).unwrap();
    assert_eq!(made.len(), 1);
    assert_eq!(made[0].0.a, Vec4::new(0.5, 1.0, 0.0, 0.0));
    assert_eq!((made[0].1.min, made[0].1.max), (Vec3::new(-0.5, -1.5, -0.5), Vec3::new(0.5, 1.5, 0.5)));
    let fat = Values(vec![("radius", Value::Number(3.0)), ("length", Value::Number(2.0))]);
    assert_eq!(shapes.primitives(0, &fat).unwrap_err(), "radius must be below length");
    let q = Parameters::of(&made[0].0);
    assert_eq!(shapes.distance(0, &q, DVec3::new(2.0, 0.0, 0.0)), 1.5);
    assert_eq!(shapes.normal(0, &q, DVec3::new(0.0, 3.0, 0.0)), DVec3::new(0.0, 2.0, 0.0));
}

#[test]
fn a_crates_material_is_read_with_its_keys_and_its_parameters_come_from_its_function() {
    let kinds: &'static CrateKinds = Box::leak(Box::new(with_list(&[CAPSULE]).unwrap()));
    let waves = kinds.find_material("waves").unwrap();
    assert_eq!((waves.index, waves.material().module), (0, "waves_material"));
    assert_eq!(waves.material().params.iter().map(|p| p.name).collect::<Vec<_>>(), ["color", "period"]);
    let values = Values(vec![("color", Value::Triple([0.5, 0.25, 1.0])), ("period", Value::Number(2.0))]);
    assert_eq!(waves.parameters(&values).unwrap(), [Vec4::new(0.5, 0.25, 1.0, 1.0), Vec4::new(0.0, 0.0, 0.0, 2.0)]);
    let negative = Values(vec![("color", Value::Triple([0.5, 0.25, 1.0])), ("period", Value::Number(-2.0))]);
    assert_eq!(waves.parameters(&negative).unwrap_err(), "period must be > 0 (got -2)");
    assert!(kinds.find_material("capsule").is_none() && kinds.find("waves").is_none());
}

#[test]
fn a_list_twinray_cannot_use_is_refused_by_name() {
    let mut sphere = CAPSULE;
    sphere.name = "sphere";
    let e = with_list(Box::leak(Box::new([sphere]))).unwrap_err();
    assert!(e.contains("twinray has a shape kind of that name"), "{e}");
    let e = with_list(Box::leak(Box::new([CAPSULE, CAPSULE]))).unwrap_err();
    assert!(e.contains("listed twice"), "{e}");
}

/// A crate loaded twice is one set: repeated in a list, its repeat becomes a salted copy.
#[test]
fn a_crate_loaded_twice_is_one_set_and_its_repeat_a_copy() {
    use crate::sets::{Language, ShaderSet};
    let set = || {
        let shapes = with_list(&[CAPSULE]).unwrap();
        let own = OwnKinds::new(Some(shapes), &[], |m| Ok(Origin::Missing(format!("{}.spv", m.name).into()))).unwrap();
        let mut set = ShaderSet::uniform(Language::Rust);
        set.set_own(own);
        set
    };
    let (a, b) = (set(), set());
    assert!(a == b, "two loads of one crate");
    assert!(a != ShaderSet::uniform(Language::Rust), "the crate's shapes make it another set");
    let distinct = ShaderSet::distinct(&[a.clone(), b]);
    assert!(distinct[0] == a && distinct[1] == a.copy(1), "the repeat is timed as a copy");
}
