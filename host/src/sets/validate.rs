//! SPIRV-Tools' validator on every module from disk, before any driver sees it. Drivers
//! trust what they are given: of 200 damaged modules, 182 failed `spirv-val`, and the driver
//! took those as an unnamed "unknown error", rendered them, crashed on them or hung. The
//! validator is Debian's `spirv-val` (package `spirv-tools`, which `cargo xtask setup`
//! installs), run on the exact bytes twinray will use, for the environment twinray targets.

use std::io::{Read, Write};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};
use twinray_shared::catalog::target_env;

/// The validator: `TWINRAY_SPIRV_VAL` if set, else a `spirv-val` beside twinray's own
/// executable (the NVIDIA bundle carries one), else `spirv-val` on the PATH.
fn program() -> std::ffi::OsString {
    if let Some(named) = std::env::var_os("TWINRAY_SPIRV_VAL") {
        return named;
    }
    let beside = std::env::current_exe().ok().and_then(|exe| Some(exe.parent()?.join("spirv-val")));
    beside.filter(|p| p.is_file()).map_or_else(|| "spirv-val".into(), |p| p.into_os_string())
}

/// How long the validator may take on one module: a damaged module must not hang twinray
/// in the validator either.
const LIMIT: Duration = Duration::from_secs(60);

/// Longest validator message quoted in an error.
const MAX_MESSAGE: usize = 600;

/// Runs the validator on `bytes`, for the Vulkan environment of their SPIR-V version; the
/// error is its message, on one line.
pub(crate) fn validate(bytes: &[u8]) -> Result<(), String> {
    let program = program();
    let env = target_env(bytes);
    let mut child = Command::new(&program)
        .args(["--target-env", env])
        .arg("-")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| {
            format!(
                "cannot run the SPIR-V validator {} ({e}); every module from disk is validated before a \
                 driver sees it: install Debian's spirv-tools (cargo xtask setup does) or set TWINRAY_SPIRV_VAL",
                program.to_string_lossy()
            )
        })?;
    let mut stdin = child.stdin.take().ok_or("the validator's input could not be opened")?;
    let input = bytes.to_vec();
    // A thread feeds it, so that a validator that stops reading cannot block twinray.
    let feeder = std::thread::spawn(move || stdin.write_all(&input));
    let start = Instant::now();
    let status = loop {
        match child.try_wait() {
            Ok(Some(status)) => break status,
            Ok(None) if start.elapsed() > LIMIT => {
                let _ = child.kill();
                let _ = child.wait();
                return Err(format!("the SPIR-V validator did not finish in {} s", LIMIT.as_secs()));
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(2)),
            Err(e) => return Err(format!("waiting for the SPIR-V validator: {e}")),
        }
    };
    let _ = feeder.join();
    if status.success() {
        return Ok(());
    }
    let mut text = String::new();
    if let Some(mut pipe) = child.stderr.take() {
        let _ = pipe.read_to_string(&mut text);
    }
    if let Some(mut pipe) = child.stdout.take() {
        let _ = pipe.read_to_string(&mut text);
    }
    let one_line = text.split_whitespace().collect::<Vec<_>>().join(" ");
    let short: String = one_line.chars().take(MAX_MESSAGE).collect();
    let more = if short.len() < one_line.len() { "..." } else { "" };
    Err(format!("spirv-val --target-env {env} rejects it: {short}{more}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refuses_a_damaged_module_and_takes_a_built_one() {
        let rust = crate::sets::builtin::spirv(twinray_shared::catalog::Language::Rust, "miss").unwrap();
        assert_eq!(validate(rust), Ok(()));
        let mut damaged = rust.to_vec();
        damaged[4 * 6..4 * 7].copy_from_slice(&0xdead_beefu32.to_le_bytes());
        let e = validate(&damaged).unwrap_err();
        assert!(e.starts_with("spirv-val --target-env vulkan1.1spv1.4 rejects it: "), "{e}");
        assert!(!e.contains('\n'));
    }
}
