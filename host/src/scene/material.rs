//! Materials of a shader crate's own kind in a scene (`kind = "NAME"` where the crate lists a
//! material `NAME`): kept as written until the scene meets the sets that know the kind
//! ([`resolve_own`]); then the crate's material, its keys' values and what its callable reads.

use super::shape::keys;
use crate::sets::own::{CrateKinds, OwnMaterialRef};
use glam::Vec4;
use twinray_shared::custom::BUILTIN_MATERIALS;
use twinray_shared::shapes::spec::Values;

/// A material of a crate's own kind: its kind and keys as written, and once resolved the
/// crate's material, its values and its callable's parameters (`Material::color_a`, `color_b`).
#[derive(Clone)]
pub struct OwnMaterialDesc {
    pub kind: String,
    keys: toml::Table,
    pub resolved: Option<(OwnMaterialRef, Values, [Vec4; 2])>,
}

impl OwnMaterialDesc {
    /// A material of kind `kind` with the other `keys` of its table, as a scene writes it.
    pub fn written(kind: String, keys: toml::Table) -> OwnMaterialDesc {
        OwnMaterialDesc { kind, keys, resolved: None }
    }
}

/// Written out by value, as shapes of a crate's own are.
impl std::fmt::Debug for OwnMaterialDesc {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.resolved {
            Some((_, values, _)) => write!(f, "{} {:?}", self.kind, values.0),
            None => write!(f, "{} {:?}", self.kind, self.keys),
        }
    }
}

/// Gives every material of a crate's own kind in `materials` (by name) its crate's material,
/// values and parameters, from the kinds of `own` (the sets' crates'); an error names a kind
/// none of them knows, a key, or the crate's refusal of the values.
pub fn resolve_own<'a>(
    materials: impl IntoIterator<Item = (&'a String, &'a mut OwnMaterialDesc)>,
    own: &[&'static CrateKinds],
) -> Result<(), String> {
    for (name, desc) in materials {
        if desc.resolved.is_some() {
            continue;
        }
        let Some(found) = own.iter().find_map(|o| o.find_material(&desc.kind)) else {
            let mut kinds: Vec<&str> = BUILTIN_MATERIALS.to_vec();
            kinds.extend(own.iter().flat_map(|o| o.materials.iter().map(|m| m.name)));
            let hint = if own.is_empty() {
                "; a shader crate's own kinds come with the set built from it (--shaders DIR)"
            } else {
                ""
            };
            return Err(format!(
                "material {name:?}: unknown material kind {:?} (kinds: {}){hint}",
                desc.kind,
                kinds.join(", ")
            ));
        };
        let m = found.material();
        let values = keys(m.name, m.params, desc.keys.clone(), false).map_err(|e| format!("material {name:?}: {e}"))?;
        let parameters = found.parameters(&values).map_err(|e| format!("material {name:?}: {e}"))?;
        desc.resolved = Some((found, values, parameters));
    }
    Ok(())
}

/// The callable modules of the crate's materials `materials`, each once, by name: kind
/// `MATERIAL_KINDS + i` is the `i`th.
pub fn own_callables<'a>(materials: impl IntoIterator<Item = &'a OwnMaterialDesc>) -> Vec<&'static str> {
    let mut modules: Vec<&'static str> =
        materials.into_iter().filter_map(|m| m.resolved.as_ref().map(|(found, ..)| found.material().module)).collect();
    modules.sort_unstable();
    modules.dedup();
    modules
}

#[cfg(test)]
mod tests {
    use crate::scene::{Colour, MeshFiles, Scene};
    use crate::sets::own::tests::test_kinds;

    const SCENE: &str = r#"
[image]
width = 8
height = 8
[camera]
eye = [0.0, 0.0, 5.0]
target = [0.0, 0.0, 0.0]
up = [0.0, 1.0, 0.0]
fov_y_degrees = 40.0
[materials.plain]
kind = "diffuse"
color = [0.5, 0.5, 0.5]
[materials.tiles]
kind = "checker"
colors = [[1.0, 1.0, 1.0], [0.0, 0.0, 0.0]]
scale = 2.0
[materials.sea]
kind = "waves"
color = [0.1, 0.3, 0.9]
period = 0.5
[shapes.ball]
kind = "sphere"
radius = 1.0
[[objects]]
shape = "ball"
material = "plain"
[[objects]]
shape = "ball"
material = "sea"
translate = [2.0, 0.0, 0.0]
[[objects]]
shape = "ball"
material = "tiles"
translate = [-2.0, 0.0, 0.0]
"#;

    #[test]
    fn a_crates_material_takes_the_first_kind_after_twinrays_and_only_its_objects_call_it() {
        let scene = Scene::parse_with(SCENE, "t.toml", MeshFiles::Builtin, &[test_kinds()]).unwrap();
        let data = scene.build();
        let sea = data.materials[scene.file.materials.keys().position(|k| k == "sea").unwrap()];
        let kinds = twinray_shared::bindings::MATERIAL_KINDS;
        assert_eq!(sea.kind, kinds, "the first kind after twinray's");
        assert_eq!((sea.color_a.to_array(), sea.color_b.w), ([0.1, 0.3, 0.9, 1.0], 0.5), "from its `parameters`");
        assert_eq!(data.plan.own_callables, ["waves_material"]);
        assert_eq!(data.plan.callable_kinds, [kinds], "twinray's kinds stay inline");
        assert_eq!(data.plan.callables(), ["waves_material"]);
        let colour = |object: u32| data.hit_group_of(object).map(|g| g.colour);
        assert_eq!(
            (colour(0), colour(1), colour(2)),
            (Some(Colour::Inline), Some(Colour::Callable), Some(Colour::Inline))
        );
    }

    #[test]
    fn a_crates_material_is_refused_unknown_with_wrong_keys_or_by_the_crate() {
        let refused = |text: &str, own: bool| {
            let own = if own { vec![test_kinds()] } else { Vec::new() };
            Scene::parse_with(text, "t.toml", MeshFiles::Builtin, &own).err().map(|e| e.to_string()).unwrap_or_default()
        };
        let e = refused(SCENE, false);
        assert!(
            e.contains("material \"sea\": unknown material kind \"waves\" (kinds: diffuse, emissive, checker, cutout)")
        );
        assert!(e.ends_with("come with the set built from it (--shaders DIR)"), "{e}");
        let e = refused(&SCENE.replace("period = 0.5", "period = -0.5"), true);
        assert!(e.contains("material \"sea\": period must be > 0 (got -0.5)"), "{e}");
        let e = refused(&SCENE.replace("period = 0.5", "period = 0.5\nperiode = 0.5"), true);
        assert!(e.contains("material \"sea\": unknown key `periode` for a waves (keys: kind, color, period)"), "{e}");
        let e = refused(&SCENE.replace("period = 0.5", "periode = 0.5"), true);
        assert!(e.contains("material \"sea\": missing key `period` for a waves"), "{e}");
        let e = refused(&SCENE.replace("[image]", "renderer = \"compute\"\n[image]"), true);
        assert!(e.contains("\"waves\" needs renderer = \"pipeline\""), "{e}");
        let e = refused(&SCENE.replace("kind = \"diffuse\"", "kind = \"difuse\""), true);
        assert!(
            e.contains("unknown material kind \"difuse\" (kinds: diffuse, emissive, checker, cutout, waves)"),
            "{e}"
        );
    }
}
