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
