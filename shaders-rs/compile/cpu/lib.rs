//! Written by twinray, rebuilt when the crate changes: the CPU side of a shader crate, which
//! twinray loads to read the crate's shapes and materials (twinray_shared::custom::abi says how).
#![allow(clippy::missing_safety_doc)]

use twinray_shared::custom::abi;

#[no_mangle]
pub extern "C" fn twinray_abi() -> u32 {
    abi::VERSION
}

#[no_mangle]
pub unsafe extern "C" fn twinray_describe(out: *mut u8, capacity: usize) -> usize {
    let described = abi::Described {
        shapes: own::SHAPES,
        materials: own::MATERIALS,
        recursion_depth: own::RECURSION_DEPTH,
    };
    unsafe { abi::describe(described, out, capacity) }
}

#[no_mangle]
pub unsafe extern "C" fn twinray_primitives(
    shape: u32,
    values: *const f64,
    count: usize,
    out: *mut f32,
    capacity: usize,
    message: *mut u8,
    message_capacity: usize,
) -> i64 {
    unsafe { abi::primitives(own::SHAPES, shape, values, count, out, capacity, message, message_capacity) }
}

#[no_mangle]
pub unsafe extern "C" fn twinray_distance(shape: u32, parameters: *const f64, p: *const f64) -> f64 {
    unsafe { abi::distance(own::SHAPES, shape, parameters, p) }
}

#[no_mangle]
pub unsafe extern "C" fn twinray_normal(shape: u32, parameters: *const f64, p: *const f64, out: *mut f64) {
    unsafe { abi::normal(own::SHAPES, shape, parameters, p, out) }
}

#[no_mangle]
pub unsafe extern "C" fn twinray_material(
    material: u32,
    values: *const f64,
    count: usize,
    out: *mut f32,
    message: *mut u8,
    message_capacity: usize,
) -> i64 {
    unsafe { abi::material(own::MATERIALS, material, (values, count), out, (message, message_capacity)) }
}
