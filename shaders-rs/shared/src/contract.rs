//! The contract version: which `twinray-shared` a set's modules were built against, recorded in
//! every module twinray builds and checked by the host before a module is used.
//!
//! Everything a stage and the host agree on lives in this crate: the buffer layouts
//! (`layout`), the binding numbers (`bindings`), the payloads, hit attributes and callable
//! data (`interface`), the module catalog (`catalog`) and the feature bits stages are
//! specialised on (`features`). The contract's version is this crate's version, read by semver:
//! a module built against another version is refused where the two could disagree.
//!
//! - **Patch** (0.1.0 to 0.1.1): no change a built module can see; math fixes that keep every
//!   layout, binding, payload, entry point and feature bit.
//! - **Minor** (0.1 to 0.2): before 1.0, anything in the contract may change, and modules
//!   built against another minor version are refused. From 1.0 on, a minor version may only
//!   add (a binding no existing stage uses, a module a set may leave out, a feature bit): a
//!   module built against 1.2 is taken by a host of 1.3, not the other way round.
//! - **Major** (from 1.0 on): anything may change; modules of another major version are refused.
//!
//! Each version's changes are listed in [`CHANGES`], which the host quotes when it refuses a
//! module: a user sees what to change, not only that something did.

/// This crate's version, which is the contract's.
pub const CONTRACT_VERSION: &str = env!("CARGO_PKG_VERSION");

/// The text a module records its contract version in (a SPIR-V `OpModuleProcessed`), followed
/// by the version: `twinray-shared 0.1.0`.
pub const RECORD_PREFIX: &str = "twinray-shared ";

/// What changed in the contract, by the version that changed it, oldest first. A version that
/// changed nothing a module can see is not listed.
pub const CHANGES: &[(&str, &str)] = &[
    ("0.1.0", "the first recorded contract: the layouts, bindings, payloads and catalog of twinray 0.1"),
    (
        "0.2.0",
        "orthographic cameras: FrameUniform.cone.y is 1 for one (camera::primary_ray then starts each ray on the camera's plane, where proj_inverse maps its pixel, and sends it down the camera's -z), 0 for a perspective camera",
    ),
    (
        "0.3.0",
        "a mesh hit's object is its instance id plus its geometry index (bindings::mesh_object): a BLAS may hold several meshes, each a geometry, the instance slots of the objects after its first inactive; a point light's range and cone (Light.position.w, u and v: lighting::falloff) dim it",
    ),
];

/// The record a module built against this contract carries.
#[cfg(not(target_arch = "spirv"))]
pub fn record() -> String {
    format!("{RECORD_PREFIX}{CONTRACT_VERSION}")
}

/// `(major, minor, patch)` of a version written `X.Y.Z` (a pre-release or build suffix after
/// the patch is ignored); `None` for anything else.
#[cfg(not(target_arch = "spirv"))]
pub fn parse_version(text: &str) -> Option<(u32, u32, u32)> {
    let mut parts = text.splitn(3, '.');
    let major = parts.next()?.parse().ok()?;
    let minor = parts.next()?.parse().ok()?;
    let patch = parts.next()?;
    let digits = patch.find(|c: char| !c.is_ascii_digit()).unwrap_or(patch.len());
    Some((major, minor, patch[..digits].parse().ok()?))
}

/// Whether a module built against contract `built` may be used by a host of contract `host`
/// (the rules of the module comment).
#[cfg(not(target_arch = "spirv"))]
pub fn compatible(built: (u32, u32, u32), host: (u32, u32, u32)) -> bool {
    match (built, host) {
        ((0, built_minor, _), (0, host_minor, _)) => built_minor == host_minor,
        ((built_major, built_minor, _), (host_major, host_minor, _)) => {
            built_major == host_major && built_minor <= host_minor
        }
    }
}

/// Why a module that records `built` cannot be used by this crate's host, or `None` when it
/// can: both versions, and what changed between them ([`CHANGES`]).
#[cfg(not(target_arch = "spirv"))]
pub fn refusal(built: &str) -> Option<String> {
    refusal_of(built, CONTRACT_VERSION, CHANGES)
}

/// [`refusal`] for a host of contract `host` whose history is `changes`.
#[cfg(not(target_arch = "spirv"))]
fn refusal_of(built: &str, host: &str, changes: &[(&str, &str)]) -> Option<String> {
    let speaks = format!("this twinray speaks twinray-shared {host}");
    let Some(version) = parse_version(built) else {
        return Some(format!("it records contract {built:?}, which is not a version ({speaks})"));
    };
    let ours = parse_version(host)?;
    if compatible(version, ours) {
        return None;
    }
    let (low, high) = if version < ours { (version, ours) } else { (ours, version) };
    let between: Vec<String> = changes
        .iter()
        .filter(|(v, _)| parse_version(v).is_some_and(|v| v > low && v <= high))
        .map(|(v, what)| format!("{v}: {what}"))
        .collect();
    let changed = match (between.is_empty(), version > ours) {
        (false, _) => between.join("; "),
        (true, true) => "a contract newer than this twinray knows: install a newer twinray".into(),
        (true, false) => "nothing this twinray lists".into(),
    };
    Some(format!("built against twinray-shared {built}, but {speaks}; what changed: {changed}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn versions_read_as_semver() {
        assert_eq!(parse_version("0.1.0"), Some((0, 1, 0)));
        assert_eq!(parse_version("1.12.3-rc.1"), Some((1, 12, 3)));
        assert_eq!(parse_version("1.2"), None);
        assert_eq!(parse_version("one.two.three"), None);
        assert!(parse_version(CONTRACT_VERSION).is_some());
    }

    #[test]
    fn before_one_a_minor_version_breaks_and_after_it_a_minor_only_adds() {
        assert!(compatible((0, 1, 0), (0, 1, 7)));
        assert!(!compatible((0, 1, 0), (0, 2, 0)));
        assert!(!compatible((0, 2, 0), (0, 1, 0)));
        assert!(compatible((1, 2, 0), (1, 3, 0)));
        assert!(!compatible((1, 3, 0), (1, 2, 0)));
        assert!(!compatible((1, 0, 0), (2, 0, 0)));
    }

    #[test]
    fn a_refusal_names_both_versions_and_what_changed_between_them() {
        assert_eq!(refusal(CONTRACT_VERSION), None);
        let text = refusal("9.0.0").expect("refused");
        assert!(text.contains("9.0.0") && text.contains(CONTRACT_VERSION) && text.contains("newer"), "{text}");
        assert!(refusal("garbage").is_some());
        let history = [("0.1.0", "first"), ("0.2.0", "payload grew"), ("0.3.0", "binding 9 moved")];
        let text = refusal_of("0.1.4", "0.3.0", &history).expect("refused");
        assert!(text.contains("0.2.0: payload grew; 0.3.0: binding 9 moved") && !text.contains("first"), "{text}");
        assert_eq!(refusal_of("0.3.0", "0.3.2", &history), None);
    }

    #[test]
    fn every_listed_change_is_a_version_up_to_this_one_in_order() {
        let versions: Vec<_> = CHANGES.iter().map(|(v, _)| parse_version(v).expect("a version")).collect();
        assert!(versions.windows(2).all(|w| w[0] < w[1]));
        assert!(versions.iter().all(|v| *v <= parse_version(CONTRACT_VERSION).unwrap()));
    }
}
