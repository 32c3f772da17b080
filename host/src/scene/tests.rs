//! Built-in scenes load, grids expand into objects, and a scene is never built without its meshes.

use super::*;

#[test]
fn every_builtin_scene_loads_with_objects() {
    for (name, _) in BUILTIN {
        let scene = Scene::load(Some(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(!scene.file.objects.is_empty(), "{name} has no objects");
    }
}

#[test]
fn grids_expand_into_objects() {
    let scene = Scene::load(Some("instances")).unwrap();
    assert_eq!(scene.file.objects.len(), 10_000);
    let data = scene.build();
    assert_eq!(data.instances.len(), 10_000);
    assert_eq!(data.blases.len(), 2, "one BLAS per shape, shared by its instances");
    let groups: Vec<_> = data.plan.hit_groups.iter().map(|g| g.name()).collect();
    assert_eq!(groups, ["triangles", "sphere"]);
}

#[test]
#[should_panic(expected = "has no mesh to build: the scene's meshes were given up")]
fn a_scene_built_without_its_meshes_is_refused() {
    let mut scene = Scene::load(Some("meshes")).unwrap();
    scene.meshes.clear();
    scene.build();
}
