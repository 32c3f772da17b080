//! Idempotent set-up: installs only what is missing, and says exactly what it would run when it
//! cannot install (not root, or no apt).

use crate::process::{self, output};
use anyhow::{bail, Result};
use std::path::Path;
use std::process::Command;
use twinray_compile::ensure_toolchain;

/// Lavapipe exposes VK_KHR_ray_tracing_pipeline from Mesa 25 on (bookworm's own 22.3 does not).
const MIN_MESA_MAJOR: u32 = 25;
const BACKPORTS_LIST: &str = "/etc/apt/sources.list.d/twinray-bookworm-backports.sources";
const BACKPORTS_SOURCE: &str = "Types: deb\nURIs: http://deb.debian.org/debian\nSuites: bookworm-backports\nComponents: main\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n";

#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Scope {
    /// Vulkan loader and lavapipe: enough to render.
    Vulkan,
    /// Also the shader toolchain (nightly, glslang, SPIRV-Tools) and the validation layer.
    Full,
}

pub fn run(scope: Scope) -> Result<()> {
    ensure_mesa()?;
    // g++: the host's FLIP dependency (nv-flip) compiles C++.
    let mut packages = vec!["libvulkan1", "g++"];
    if scope == Scope::Full {
        packages.extend(["glslang-tools", "spirv-tools", "vulkan-validationlayers"]);
        // The browser tests of `twinray view` drive Debian's chromium through chromedriver.
        packages.extend(["chromium", "chromium-driver"]);
        // Models no one here made: the glTF tests load every one (docs/gltf.md).
        packages.push("assimp-testmodels");
        // The confinement test watches which files twinray opens (app/tests/gltf_cli.rs).
        packages.push("strace");
        // The condition numbers of probe reports are checked against mpmath's (tests/condition.rs).
        packages.push("python3-mpmath");
    }
    ensure_packages(&packages)?;
    if scope == Scope::Full {
        ensure_toolchain()?;
        ensure_stable_components()?;
    }
    Ok(())
}

/// Installs the Debian packages of `packages` that are missing.
pub fn ensure_packages(packages: &[&str]) -> Result<()> {
    let missing: Vec<&str> = packages.iter().copied().filter(|p| dpkg_version(p).is_none()).collect();
    if missing.is_empty() {
        return Ok(());
    }
    apt_install(&missing, None)
}

/// The installed version of a Debian package, if any.
fn dpkg_version(package: &str) -> Option<String> {
    let out = Command::new("dpkg-query").args(["-W", "-f=${Status}|${Version}", package]).output().ok()?;
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    let (status, version) = text.split_once('|')?;
    (out.status.success() && status.ends_with(" installed")).then(|| version.to_string())
}

/// Major version of a Debian version string such as `25.0.7-2~bpo12+1`.
fn major(version: &str) -> Option<u32> {
    let without_epoch = version.split_once(':').map_or(version, |(_, v)| v);
    without_epoch.split('.').next()?.parse().ok()
}

fn ensure_mesa() -> Result<()> {
    let current = dpkg_version("mesa-vulkan-drivers");
    if has_ray_tracing_mesa(current.as_deref()) {
        return Ok(());
    }
    let codename = os_codename();
    let release = if codename.as_deref() == Some("bookworm") { Some("bookworm-backports") } else { None };
    if release.is_some() && !Path::new(BACKPORTS_LIST).exists() {
        if !can_apt() {
            print_manual(&format!("printf '{}' > {BACKPORTS_LIST}", BACKPORTS_SOURCE.replace('\n', "\\n")));
            bail!("Mesa lavapipe {MIN_MESA_MAJOR}+ is needed (found {current:?}); run the commands above as root");
        }
        std::fs::write(BACKPORTS_LIST, BACKPORTS_SOURCE)?;
        println!("setup: added {BACKPORTS_LIST}");
    }
    apt_install(&["mesa-vulkan-drivers"], release)?;
    let installed = dpkg_version("mesa-vulkan-drivers");
    if !has_ray_tracing_mesa(installed.as_deref()) {
        bail!("mesa-vulkan-drivers {installed:?} installed, but ray tracing on lavapipe needs {MIN_MESA_MAJOR}+");
    }
    Ok(())
}

fn has_ray_tracing_mesa(version: Option<&str>) -> bool {
    version.and_then(major).is_some_and(|m| m >= MIN_MESA_MAJOR)
}

fn os_codename() -> Option<String> {
    let text = std::fs::read_to_string("/etc/os-release").ok()?;
    text.lines().find_map(|l| l.strip_prefix("VERSION_CODENAME=")).map(|v| v.trim_matches('"').to_string())
}

fn can_apt() -> bool {
    let root = output(Command::new("id").arg("-u")).is_ok_and(|uid| uid.trim() == "0");
    root && Path::new("/usr/bin/apt-get").exists()
}

fn print_manual(line: &str) {
    println!("setup: cannot install here (needs root and apt-get). Run:\n  {line}");
}

fn apt_install(packages: &[&str], release: Option<&str>) -> Result<()> {
    let mut args = vec!["install", "-y", "--no-install-recommends"];
    if let Some(r) = release {
        args.extend(["-t", r]);
    }
    args.extend(packages);
    if !can_apt() {
        print_manual(&format!("apt-get update && apt-get {}", args.join(" ")));
        bail!("missing Debian packages: {}", packages.join(", "));
    }
    println!("setup: installing {}", packages.join(" "));
    process::run(Command::new("apt-get").arg("update").arg("-q"))?;
    process::run(Command::new("apt-get").args(&args).env("DEBIAN_FRONTEND", "noninteractive"))
}

/// rustfmt and clippy for the toolchain that builds the workspace.
fn ensure_stable_components() -> Result<()> {
    let installed = output(Command::new("rustup").args(["component", "list", "--installed"])).unwrap_or_default();
    let missing: Vec<&str> =
        ["rustfmt", "clippy"].into_iter().filter(|c| !installed.lines().any(|l| l.starts_with(c))).collect();
    if missing.is_empty() {
        return Ok(());
    }
    let mut args = vec!["component", "add"];
    args.extend(&missing);
    process::run(Command::new("rustup").args(&args))
}

#[cfg(test)]
mod tests {
    #[test]
    fn reads_major_versions() {
        assert_eq!(super::major("25.0.7-2~bpo12+1"), Some(25));
        assert_eq!(super::major("1:22.3.6-1+deb12u1"), Some(22));
        assert_eq!(super::major("garbage"), None);
    }
}
