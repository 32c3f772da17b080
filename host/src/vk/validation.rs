//! The validation layer: whether to enable it, and the messenger that routes its messages to
//! the log and counts its errors so a render can fail on them.

use ash::{ext::debug_utils, vk};
use std::ffi::{c_void, CStr};
use std::sync::Mutex;

/// The Khronos validation layer.
pub const LAYER_NAME: &CStr = c"VK_LAYER_KHRONOS_validation";

/// Whether to run with the Khronos validation layer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Validation {
    /// No validation layer.
    Off,
    /// Enable it; fail if it is not installed.
    Required,
    /// Enable it with GPU-assisted validation, which instruments the shaders to report
    /// out-of-bounds descriptor and buffer access by stage and binding.
    GpuAssisted,
}

/// Error messages collected by the messenger; owned by the context, read after each submit.
#[derive(Default)]
pub struct ValidationLog {
    errors: Mutex<Vec<String>>,
}

impl ValidationLog {
    /// Takes the errors collected so far.
    pub fn take_errors(&self) -> Vec<String> {
        match self.errors.lock() {
            Ok(mut errors) => std::mem::take(&mut *errors),
            Err(poisoned) => std::mem::take(&mut *poisoned.into_inner()),
        }
    }

    fn push_error(&self, message: String) {
        match self.errors.lock() {
            Ok(mut errors) => errors.push(message),
            Err(poisoned) => poisoned.into_inner().push(message),
        }
    }
}

/// Messenger create info whose user data is `log`, which must outlive the messenger.
pub fn messenger_info(log: &ValidationLog) -> vk::DebugUtilsMessengerCreateInfoEXT<'static> {
    vk::DebugUtilsMessengerCreateInfoEXT::default()
        .message_severity(
            vk::DebugUtilsMessageSeverityFlagsEXT::ERROR
                | vk::DebugUtilsMessageSeverityFlagsEXT::WARNING
                | vk::DebugUtilsMessageSeverityFlagsEXT::INFO,
        )
        .message_type(
            vk::DebugUtilsMessageTypeFlagsEXT::GENERAL
                | vk::DebugUtilsMessageTypeFlagsEXT::VALIDATION
                | vk::DebugUtilsMessageTypeFlagsEXT::PERFORMANCE,
        )
        .pfn_user_callback(Some(callback))
        .user_data(log as *const ValidationLog as *mut c_void)
}

/// The messenger together with the loader that destroys it.
pub struct Messenger {
    pub loader: debug_utils::Instance,
    pub raw: vk::DebugUtilsMessengerEXT,
}

unsafe extern "system" fn callback(
    severity: vk::DebugUtilsMessageSeverityFlagsEXT,
    _types: vk::DebugUtilsMessageTypeFlagsEXT,
    data: *const vk::DebugUtilsMessengerCallbackDataEXT<'_>,
    user_data: *mut c_void,
) -> vk::Bool32 {
    // SAFETY: the layer passes valid callback data for the duration of the call.
    let message = unsafe { data.as_ref() }
        .and_then(|d| unsafe { d.message_as_c_str() })
        .map(|m| m.to_string_lossy().into_owned())
        .unwrap_or_default();
    if severity.contains(vk::DebugUtilsMessageSeverityFlagsEXT::ERROR) {
        log::error!("validation: {message}");
        // SAFETY: user_data is the context's ValidationLog, which outlives the messenger.
        if let Some(log) = unsafe { (user_data as *const ValidationLog).as_ref() } {
            log.push_error(message);
        }
    } else if severity.contains(vk::DebugUtilsMessageSeverityFlagsEXT::WARNING) {
        log::warn!("validation: {message}");
    } else {
        log::debug!("validation: {message}");
    }
    vk::FALSE
}
