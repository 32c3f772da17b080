//! The C functions through which twinray reads a crate's [`CustomShape`]s and
//! [`CustomMaterial`]s. twinray writes a small library around the crate's `shared` library
//! (`twinray_describe`, `twinray_primitives`, `twinray_distance`, `twinray_normal`,
//! `twinray_material`, each one line calling the function of the same name here), builds it for the CPU with the crate's toolchain and loads it: across that line only
//! C types pass, since the host and the crate may be built by different compilers.
//!
//! A panic in a crate's function is caught here: `primitives` reports it as an error, and
//! `distance` and `normal` return NaN, which the host reports as the definition's fault;
//! `material` reports it as an error.

use super::{check_list, check_materials, CustomMaterial, CustomShape, Parameters};
use crate::shapes::spec::{Param, ParamType, Rule, Value, Values};
use glam::{DVec3, DVec4};
use std::panic::{catch_unwind, AssertUnwindSafe};

/// The version of these functions; the host refuses a library of another.
pub const VERSION: u32 = 2;
/// f32s per primitive that `primitives` writes: `a`, `b`, `tint`, then its box's `min` and `max`.
pub const PRIMITIVE_FLOATS: usize = 18;
/// f64s of a primitive's parameters as `distance` and `normal` take them: `a`, then `b`.
pub const PARAMETER_FLOATS: usize = 8;
/// f32s that `material` writes: `Material::color_a`, then `color_b`.
pub const MATERIAL_FLOATS: usize = 8;

/// What a crate's CPU library describes: its shapes, its materials, and the recursion depth
/// of the pipelines its stages need (1 unless its hit stages trace; its `RECURSION_DEPTH`).
#[derive(Clone, Copy)]
pub struct Described<'a> {
    /// Its `SHAPES`.
    pub shapes: &'a [CustomShape],
    /// Its `MATERIALS`.
    pub materials: &'a [CustomMaterial],
    /// Its `RECURSION_DEPTH`.
    pub recursion_depth: u32,
}

/// The crate's shapes and materials as JSON: `{"abi", "contract", "error", "recursion_depth",
/// "shapes": [{"name", "about", "hit_kind", "params": [{"name", "type", "rule", "max",
/// "default"}]}], "materials": [{"name", "about", "params"}]}`. `error` is null, or why a list
/// or the depth cannot be used ([`check_list`], [`check_materials`]).
pub fn description(crate_: Described) -> String {
    let Described { shapes, materials, recursion_depth } = crate_;
    let max = crate::interface::MAX_DECLARED_DEPTH;
    let depth = if (1..=max).contains(&recursion_depth) {
        Ok(())
    } else {
        Err(format!("RECURSION_DEPTH is {recursion_depth}, not in 1..={max}"))
    };
    let error = match check_list(shapes).and_then(|()| check_materials(materials)).and(depth) {
        Ok(()) => "null".to_string(),
        Err(e) => json_string(&e),
    };
    let shapes: Vec<String> = shapes
        .iter()
        .map(|s| {
            let (name, about) = (json_string(s.name), json_string(s.about));
            format!("{{\"name\":{name},\"about\":{about},\"hit_kind\":{},\"params\":{}}}", s.hit_kind, keys(s.params))
        })
        .collect();
    let materials: Vec<String> = materials
        .iter()
        .map(|m| {
            let (name, about) = (json_string(m.name), json_string(m.about));
            format!("{{\"name\":{name},\"about\":{about},\"params\":{}}}", keys(m.params))
        })
        .collect();
    format!(
        "{{\"abi\":{VERSION},\"contract\":{},\"error\":{error},\"recursion_depth\":{recursion_depth},\
         \"shapes\":[{}],\"materials\":[{}]}}",
        json_string(crate::contract::CONTRACT_VERSION),
        shapes.join(","),
        materials.join(",")
    )
}

/// Scene keys as a JSON list.
fn keys(params: &[Param]) -> String {
    let params: Vec<String> = params
        .iter()
        .map(|p| {
            let ty = match p.ty {
                ParamType::Number => "number",
                ParamType::Pair => "pair",
                ParamType::Triple => "triple",
                ParamType::Count => "count",
                ParamType::Seed => "seed",
            };
            let (rule, max) = match p.rule {
                Rule::Finite => ("finite", "null".to_string()),
                Rule::Positive => ("positive", "null".to_string()),
                Rule::CountUpTo(max) => ("count_up_to", max.to_string()),
                Rule::Any => ("any", "null".to_string()),
            };
            let default = match p.default {
                Some(v) => format!("{:?}", flatten(&[v])),
                None => "null".to_string(),
            };
            format!(
                "{{\"name\":{},\"type\":\"{ty}\",\"rule\":\"{rule}\",\"max\":{max},\"default\":{default}}}",
                json_string(p.name)
            )
        })
        .collect();
    format!("[{}]", params.join(","))
}

/// `text` as a JSON string.
fn json_string(text: &str) -> String {
    let mut out = String::from("\"");
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 => out.push_str(&format!("\\u{:04x}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// Values as the C functions pass them: each number, pair or triple as its f64s, a count or
/// seed as one f64, in the order of the shape's keys.
pub fn flatten(values: &[Value]) -> Vec<f64> {
    let mut out = Vec::new();
    for v in values {
        match *v {
            Value::Number(x) => out.push(f64::from(x)),
            Value::Pair(x) => out.extend(x.map(f64::from)),
            Value::Triple(x) => out.extend(x.map(f64::from)),
            Value::Count(n) => out.push(f64::from(n)),
            Value::Seed(n) => out.push(n as f64),
        }
    }
    out
}

/// The values of the keys `params` of the shape or material `name` from `flat` ([`flatten`]'s
/// order), or why they do not fit its keys.
pub fn unflatten(name: &str, params: &[Param], flat: &[f64]) -> Result<Values, String> {
    let mut rest = flat;
    let mut values = Vec::new();
    for p in params {
        let n = match p.ty {
            ParamType::Pair => 2,
            ParamType::Triple => 3,
            _ => 1,
        };
        if rest.len() < n {
            return Err(format!("{name}: {} values given for its keys, fewer than they take", flat.len()));
        }
        let (v, tail) = rest.split_at(n);
        rest = tail;
        let value = match p.ty {
            ParamType::Number => Value::Number(v[0] as f32),
            ParamType::Pair => Value::Pair([v[0] as f32, v[1] as f32]),
            ParamType::Triple => Value::Triple([v[0] as f32, v[1] as f32, v[2] as f32]),
            ParamType::Count => Value::Count(v[0] as u32),
            ParamType::Seed => Value::Seed(v[0] as u64),
        };
        p.check(value)?;
        values.push((p.name, value));
    }
    if !rest.is_empty() {
        return Err(format!("{name}: {} values given for its keys, more than they take", flat.len()));
    }
    Ok(Values(values))
}

/// Writes [`description`] into `out` (at most `capacity` bytes) and returns its whole length,
/// so that a caller whose buffer was short calls again with a longer one.
///
/// # Safety
/// `out` must be valid for `capacity` bytes of writes (or `capacity` 0).
pub unsafe fn describe(crate_: Described, out: *mut u8, capacity: usize) -> usize {
    // SAFETY: passed on from the caller.
    unsafe { write_text(&description(crate_), out, capacity) }
}

/// The primitives of shape `index` with the keys `values` (`count` f64s, [`flatten`]'s order):
/// their number, with [`PRIMITIVE_FLOATS`] f32s each written to `out` when `capacity` (in
/// primitives) holds them all. Below zero when the keys are refused (by their rules or the
/// shape's `check`) or the shape's function panicked, with why written to `message` (at most
/// `message_capacity` bytes) and the negated length of the whole message returned.
///
/// # Safety
/// `values` must be valid for `count` reads, `out` for `capacity * PRIMITIVE_FLOATS` writes and
/// `message` for `message_capacity` writes (a capacity may be 0).
#[allow(clippy::too_many_arguments)]
pub unsafe fn primitives(
    shapes: &[CustomShape],
    index: u32,
    values: *const f64,
    count: usize,
    out: *mut f32,
    capacity: usize,
    message: *mut u8,
    message_capacity: usize,
) -> i64 {
    // SAFETY: the caller gives `count` readable f64s at `values`.
    let flat = if count == 0 { &[][..] } else { unsafe { core::slice::from_raw_parts(values, count) } };
    let made = shapes.get(index as usize).ok_or_else(|| format!("no shape {index}")).and_then(|shape| {
        let values = unflatten(shape.name, shape.params, flat)?;
        let shape = *shape;
        catch_unwind(AssertUnwindSafe(|| (shape.check)(&values).map(|()| (shape.primitives)(&values))))
            .unwrap_or_else(|_| Err(format!("{}: its `check` or `primitives` panicked", shape.name)))
    });
    match made {
        Ok(list) => {
            if list.len() <= capacity {
                for (i, (p, aabb)) in list.iter().enumerate() {
                    let floats: [f32; PRIMITIVE_FLOATS] = [
                        p.a.x, p.a.y, p.a.z, p.a.w, p.b.x, p.b.y, p.b.z, p.b.w, p.tint.x, p.tint.y, p.tint.z, p.tint.w,
                        aabb.min.x, aabb.min.y, aabb.min.z, aabb.max.x, aabb.max.y, aabb.max.z,
                    ];
                    // SAFETY: i < list.len() <= capacity, and the caller gives capacity * 18 f32s.
                    unsafe {
                        core::ptr::copy_nonoverlapping(floats.as_ptr(), out.add(i * PRIMITIVE_FLOATS), PRIMITIVE_FLOATS)
                    };
                }
            }
            list.len() as i64
        }
        Err(why) => {
            // SAFETY: the caller gives `message_capacity` writable bytes at `message`.
            let whole = unsafe { write_text(&why, message, message_capacity) };
            -(whole.max(1) as i64)
        }
    }
}

/// The parameters of material `index` with the keys `values` (`count` f64s, [`flatten`]'s
/// order): 0, with [`MATERIAL_FLOATS`] f32s written to `out`; or below zero when the keys are
/// refused or the material's function panicked, with why written to `message` (at most
/// `message_capacity` bytes) and the negated length of the whole message returned.
///
/// # Safety
/// `values` must be valid for `count` reads, `out` for [`MATERIAL_FLOATS`] writes and
/// `message` for `message_capacity` writes (a capacity may be 0).
pub unsafe fn material(
    materials: &[CustomMaterial],
    index: u32,
    (values, count): (*const f64, usize),
    out: *mut f32,
    (message, message_capacity): (*mut u8, usize),
) -> i64 {
    // SAFETY: the caller gives `count` readable f64s at `values`.
    let flat = if count == 0 { &[][..] } else { unsafe { core::slice::from_raw_parts(values, count) } };
    let made = materials.get(index as usize).ok_or_else(|| format!("no material {index}")).and_then(|m| {
        let values = unflatten(m.name, m.params, flat)?;
        let m = *m;
        catch_unwind(AssertUnwindSafe(|| (m.check)(&values).map(|()| (m.parameters)(&values))))
            .unwrap_or_else(|_| Err(format!("{}: its `check` or `parameters` panicked", m.name)))
    });
    match made {
        Ok([a, b]) => {
            let floats: [f32; MATERIAL_FLOATS] = [a.x, a.y, a.z, a.w, b.x, b.y, b.z, b.w];
            // SAFETY: the caller gives MATERIAL_FLOATS writable f32s at `out`.
            unsafe { core::ptr::copy_nonoverlapping(floats.as_ptr(), out, MATERIAL_FLOATS) };
            0
        }
        Err(why) => {
            // SAFETY: the caller gives `message_capacity` writable bytes at `message`.
            let whole = unsafe { write_text(&why, message, message_capacity) };
            -(whole.max(1) as i64)
        }
    }
}

/// Writes the first `capacity` bytes of `text` to `out` and returns its whole length.
///
/// # Safety
/// `out` must be valid for `capacity` bytes of writes (or `capacity` 0).
unsafe fn write_text(text: &str, out: *mut u8, capacity: usize) -> usize {
    let n = text.len().min(capacity);
    if n > 0 {
        // SAFETY: the caller gives `capacity` writable bytes at `out`, and n <= capacity.
        unsafe { core::ptr::copy_nonoverlapping(text.as_ptr(), out, n) };
    }
    text.len()
}

/// Reads a point and a primitive's parameters.
///
/// # Safety
/// `parameters` must be valid for [`PARAMETER_FLOATS`] reads and `p` for 3.
unsafe fn inputs(parameters: *const f64, p: *const f64) -> (DVec3, Parameters) {
    // SAFETY: the caller gives 8 readable f64s at `parameters` and 3 at `p`.
    let (q, p) =
        unsafe { (core::slice::from_raw_parts(parameters, PARAMETER_FLOATS), core::slice::from_raw_parts(p, 3)) };
    let parameters = Parameters { a: DVec4::new(q[0], q[1], q[2], q[3]), b: DVec4::new(q[4], q[5], q[6], q[7]) };
    (DVec3::new(p[0], p[1], p[2]), parameters)
}

/// The signed distance of shape `index` at `p` (3 f64s) for `parameters`
/// ([`PARAMETER_FLOATS`] f64s); NaN for an unknown shape or a panic.
///
/// # Safety
/// `parameters` must be valid for [`PARAMETER_FLOATS`] reads and `p` for 3.
pub unsafe fn distance(shapes: &[CustomShape], index: u32, parameters: *const f64, p: *const f64) -> f64 {
    let Some(shape) = shapes.get(index as usize) else { return f64::NAN };
    // SAFETY: passed on from the caller.
    let (p, parameters) = unsafe { inputs(parameters, p) };
    catch_unwind(|| (shape.distance)(p, &parameters)).unwrap_or(f64::NAN)
}

/// The outward normal of shape `index` at `p`, written to `out` (3 f64s); NaN for an unknown
/// shape or a panic.
///
/// # Safety
/// `parameters` must be valid for [`PARAMETER_FLOATS`] reads, `p` for 3 and `out` for 3
/// writes.
pub unsafe fn normal(shapes: &[CustomShape], index: u32, parameters: *const f64, p: *const f64, out: *mut f64) {
    let n = match shapes.get(index as usize) {
        Some(shape) => {
            // SAFETY: passed on from the caller.
            let (p, parameters) = unsafe { inputs(parameters, p) };
            catch_unwind(|| (shape.normal)(p, &parameters)).unwrap_or(DVec3::NAN)
        }
        None => DVec3::NAN,
    };
    // SAFETY: the caller gives 3 writable f64s at `out`.
    unsafe { core::ptr::copy_nonoverlapping(n.to_array().as_ptr(), out, 3) };
}
