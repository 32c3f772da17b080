//! The validation layer is really on in tests: a deliberately invalid call is reported, and the
//! check that every render runs after its work fails on it.

use ash::vk;
use twinray_tests::validated_context;

#[test]
fn a_validation_error_fails_the_next_check() {
    let ctx = validated_context();
    assert!(ctx.check_validation().is_ok(), "a fresh context already has validation errors");
    let info = vk::BufferCreateInfo::default().size(0).usage(vk::BufferUsageFlags::STORAGE_BUFFER);
    // SAFETY: deliberately invalid (size 0) to provoke the layer; a buffer, if made, is destroyed.
    unsafe {
        if let Ok(buffer) = ctx.device.create_buffer(&info, None) {
            ctx.device.destroy_buffer(buffer, None);
        }
    }
    let error = ctx.check_validation().expect_err("the layer did not report a zero-sized buffer").to_string();
    assert!(error.contains("VUID-VkBufferCreateInfo-size"), "{error}");
    assert!(ctx.check_validation().is_ok(), "errors are reported once");
}

/// An object still alive when the device goes is a leak the layer reports at teardown:
/// `close` must fail on it (the scene and probe sweeps end with `close`).
#[test]
fn a_leaked_object_is_reported_when_the_context_closes() {
    let ctx = validated_context();
    let info = vk::BufferCreateInfo::default().size(256).usage(vk::BufferUsageFlags::STORAGE_BUFFER);
    // SAFETY: a valid buffer, deliberately never destroyed.
    let _leaked = unsafe { ctx.device.create_buffer(&info, None) }.expect("creating a buffer");
    let error = ctx.close().expect_err("the layer did not report a leaked buffer").to_string();
    assert!(error.contains("VkBuffer") || error.contains("05137"), "{error}");
}

#[test]
fn a_clean_context_closes_without_errors() {
    validated_context().close().expect("a context that made nothing closes cleanly");
}
