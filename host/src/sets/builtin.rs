//! The built-in sets: the committed SPIR-V of every module of the catalog in both languages,
//! embedded by `host/build.rs` from the catalog (no hand-kept table).

use twinray_shared::catalog::Language;

include!(concat!(env!("OUT_DIR"), "/embedded_spirv.rs"));

/// The embedded module `name` in `language`.
pub fn spirv(language: Language, name: &str) -> Option<&'static [u8]> {
    EMBEDDED.iter().find(|(l, n, _)| *l == language && *n == name).map(|(_, _, bytes)| *bytes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use twinray_shared::catalog::MODULES;

    #[test]
    fn every_module_is_embedded_in_both_languages() {
        for spec in MODULES {
            for language in Language::ALL {
                assert!(spirv(language, spec.name).is_some(), "{} {}", language.name(), spec.name);
            }
        }
        assert_eq!(EMBEDDED.len(), 2 * MODULES.len(), "only the catalog's modules are embedded");
    }

    /// A contract version changed without `cargo xtask shaders` leaves the built-in sets
    /// recording the old one.
    #[test]
    fn every_built_in_module_records_this_contract() {
        for (language, name, bytes) in EMBEDDED {
            let info = twinray_shared::spirv_info::parse(bytes).expect("a module");
            let want = twinray_shared::contract::CONTRACT_VERSION;
            assert_eq!(info.contract(), Some(want), "{} {name} records another contract", language.name());
        }
    }
}
