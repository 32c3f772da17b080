use super::*;

fn starter(tag: &str, glsl: bool) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("twinray-scaffold-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    crate::starter::write(&dir, "my-stages", glsl).unwrap();
    dir
}

fn read(dir: &Path, file: &str) -> String {
    std::fs::read_to_string(dir.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"))
}

#[test]
fn a_starter_crate_has_a_shared_library_in_its_manifest_and_lock() {
    let dir = starter("shared", false);
    let manifest = read(&dir, "Cargo.toml");
    assert!(
        manifest.contains("twinray-shared = { path = \"twinray-shared\" }\nmy-stages-shared = { path = \"shared\" }")
    );
    assert!(manifest.contains("exclude = [\"shared\", \"twinray-shared\"]"), "{manifest}");
    let lock = read(&dir, "Cargo.lock");
    assert!(lock.contains(
        "name = \"my-stages\"\nversion = \"0.1.0\"\ndependencies = [\n \"my-stages-shared\",\n \"spirv-std\",\n"
    ));
    assert!(lock.contains("[[package]]\nname = \"my-stages-shared\"\nversion = \"0.1.0\""));
    assert_eq!(lock, sorted_lock(&lock), "packages in cargo's order");
    assert!(read(&dir, "shared/Cargo.toml").contains("name = \"my-stages-shared\""));
    assert!(read(&dir, "shared/src/lib.rs").contains("pub const SHAPES"));
    assert!(ensure_shared(&dir, "my-stages").unwrap().is_empty(), "a crate with one is left alone");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_shape_is_added_in_every_place_it_needs_with_its_own_hit_kind() {
    let dir = starter("shape", true);
    let (written, kind) = add_shape(&dir, "capsule").unwrap();
    assert_eq!(kind, 32);
    for file in [
        "shared/src/capsule.rs",
        "src/capsule.rs",
        "scenes/capsule.toml",
        "probes/capsule.toml",
        "glsl/capsule_intersection.rint",
    ] {
        assert!(written.contains(&PathBuf::from(file)), "{file} not written");
        assert!(!read(&dir, file).contains("{shape}") && !read(&dir, file).contains("{hit_kind}"), "{file}");
    }
    assert!(read(&dir, "shared/src/capsule.rs").contains("pub const HIT_KIND: u32 = 32;"));
    assert!(read(&dir, "src/capsule.rs").contains("use my_stages_shared::capsule::{intersect, HIT_KIND};"));
    let lib = read(&dir, "shared/src/lib.rs");
    assert!(lib.contains("pub mod capsule;\n") && lib.contains("    capsule::SHAPE,\n    // The shapes ("), "{lib}");
    assert!(read(&dir, "src/lib.rs").ends_with("pub mod capsule;\n"));
    let (_, next) = add_shape(&dir, "blob").unwrap();
    assert_eq!(next, 33, "the next free hit kind");
    assert!(read(&dir, "shared/src/lib.rs").contains("    capsule::SHAPE,\n    blob::SHAPE,\n"));
    // Added twice: refused, and nothing of the first is touched.
    let before = read(&dir, "shared/src/lib.rs");
    let e = add_shape(&dir, "capsule").unwrap_err().to_string();
    assert!(e.contains("has a shape \"capsule\" already (nothing was written)"), "{e}");
    assert_eq!(read(&dir, "shared/src/lib.rs"), before);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn names_twinray_or_rust_take_are_refused() {
    for (name, why) in [
        ("Capsule", "lower-case"),
        ("2d", "a letter first"),
        ("sphere", "is taken"),
        ("mesh", "is taken"),
        ("type", "is taken"),
        ("shared", "is taken"),
        ("checker", "is taken"),
    ] {
        let e = check_name("shape", name).unwrap_err().to_string();
        assert!(e.contains(why), "{name}: {e}");
    }
    let e = add_shape(Path::new("/nonexistent/crate"), "capsule").unwrap_err().to_string();
    assert!(e.contains("no shader crate here"), "{e}");
}

#[test]
fn a_material_is_added_in_every_place_it_needs() {
    let dir = starter("material", true);
    let written = add_material(&dir, "waves").unwrap();
    for file in ["shared/src/waves.rs", "src/waves.rs", "scenes/waves.toml", "glsl/waves_material.rcall"] {
        assert!(written.contains(&PathBuf::from(file)), "{file} not written");
        assert!(!read(&dir, file).contains("{material}") && !read(&dir, file).contains("{shared}"), "{file}");
    }
    assert!(read(&dir, "src/waves.rs").contains("pub fn waves_material("));
    let lib = read(&dir, "shared/src/lib.rs");
    assert!(lib.contains("pub mod waves;\n") && lib.contains("    waves::MATERIAL,\n    // The materials ("), "{lib}");
    assert!(
        read(&dir, "src/lib.rs").ends_with("/// The callable of the crate's own material `waves`.\npub mod waves;\n")
    );
    let e = add_material(&dir, "waves").unwrap_err().to_string();
    assert!(e.contains("has a material \"waves\" already (nothing was written)"), "{e}");
    let e = add_shape(&dir, "waves").unwrap_err().to_string();
    assert!(e.contains("shared/src/waves.rs exists"), "a shape cannot take a material's name: {e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_crate_made_before_materials_gains_their_list_with_its_first() {
    let dir = starter("old-lib", false);
    let lib = read(&dir, "shared/src/lib.rs");
    let at = lib.find("\n/// The materials scenes may name").unwrap();
    std::fs::write(dir.join("shared/src/lib.rs"), &lib[..at]).unwrap();
    add_material(&dir, "waves").unwrap();
    let lib = read(&dir, "shared/src/lib.rs");
    assert!(lib.contains("pub const MATERIALS: &[twinray_shared::custom::CustomMaterial] = &[\n    waves::MATERIAL,\n"));
    assert!(!dir.join("glsl").exists(), "no GLSL twin where the crate has none");
    std::fs::remove_dir_all(&dir).unwrap();
}
