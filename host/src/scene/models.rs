//! glTF models placed by a scene file (`[shapes.NAME] kind = "gltf"`): every object of such a
//! shape becomes the model's objects, each placed first by its node's world matrix, then by
//! the object's own transform; the model's meshes and materials join the scene's, named
//! `NAME/...`. An object that names a material gives it to every part of the model. This runs
//! after grids are expanded, so a grid of a model is a grid of its parts.

use super::check;
use super::file::{ObjectDesc, SceneFile};
use super::gltf::{load, mesh_shape, notice};
use super::mesh::MeshData;
use super::placed_clip::{Model, Part, PlacedClip};
use super::shape::ShapeDesc;
use crate::util::input::confined;
use std::collections::BTreeMap;
use std::path::Path;

/// What placing the models made: their meshes by the names of their shapes in the scene, for
/// each object of the scene the index of the object it came from (`None`: no models, the
/// objects are as written), and the clips of the animated models, played together where they
/// are placed (`None` where no model is animated).
pub struct Placed {
    pub meshes: BTreeMap<String, MeshData>,
    pub owners: Option<Vec<usize>>,
    pub clip: Option<PlacedClip>,
}

/// Places every glTF shape's model in `file` (files relative to `folder`).
pub fn place(file: &mut SceneFile, folder: Option<&Path>) -> Result<Placed, String> {
    let models: Vec<_> = file
        .shapes
        .iter()
        .filter_map(|(name, shape)| match shape {
            ShapeDesc::Gltf(g) => Some((name.clone(), g.clone())),
            _ => None,
        })
        .collect();
    let mut meshes = BTreeMap::new();
    if models.is_empty() {
        return Ok(Placed { meshes, owners: None, clip: None });
    }
    let folder = folder.ok_or("a built-in scene places no glTF files")?;
    let mut owners: Vec<usize> = (0..file.objects.len()).collect();
    // Each object's part of an animated model, and where.
    let mut parts: Vec<Option<Part>> = vec![None; file.objects.len()];
    let (mut animated, mut placements): (Vec<Model>, usize) = (Vec::new(), 0);
    for (name, desc) in models {
        let path = confined(folder, &desc.file).map_err(|e| format!("shape {name:?}: cannot read {e}"))?;
        let model = load(&path, desc.scene).map_err(|e| format!("shape {name:?}: {}: {e}", desc.file))?;
        notice(&path.display().to_string(), &model.ignored);
        let clip = model.clip.clone().map(|clip| {
            animated.push(Model { clip, prefix: format!("{name}/"), objects: model.file.clone() });
            animated.len() - 1
        });
        file.shapes.remove(&name);
        // Its grids are objects by now, and name a shape that is gone.
        file.grids.retain(|g| g.shape != name);
        let part = |s: &str| format!("{name}/{s}");
        for (shape, data) in model.meshes {
            file.shapes.insert(part(&shape), mesh_shape(&part(&shape)));
            meshes.insert(part(&shape), data);
        }
        for (material, desc) in model.file.materials {
            file.materials.insert(part(&material), desc);
        }
        let objects = std::mem::take(&mut file.objects);
        let (mut parts_of, mut animated_of) = (Vec::with_capacity(objects.len()), Vec::new());
        let was = objects.into_iter().zip(std::mem::take(&mut owners)).zip(std::mem::take(&mut parts));
        for ((object, owner), was_part) in was {
            if object.shape != name {
                file.objects.push(object);
                parts_of.push(owner);
                animated_of.push(was_part);
                continue;
            }
            parts_of.extend(std::iter::repeat_n(owner, model.file.objects.len()));
            let own = object.matrix.map_or(glam::Mat4::IDENTITY, |m| glam::Mat4::from_cols_array(&m));
            let placing = |part| clip.map(|model| Part { model, placement: placements, part, placing: own });
            animated_of.extend((0..model.file.objects.len()).map(placing));
            placements += 1;
            file.objects.extend(model.file.objects.iter().map(|p| ObjectDesc {
                name: match (&object.name, &p.name) {
                    (Some(own), Some(node)) => Some(format!("{own}: {node}")),
                    (own, node) => own.clone().or_else(|| node.clone()),
                },
                shape: part(&p.shape),
                material: if object.material.is_empty() { part(&p.material) } else { object.material.clone() },
                matrix: Some((own * p.transform()).to_cols_array()),
                // A face of the model is single-sided as its material says, or as the placing
                // object asks.
                single_sided: p.single_sided || object.single_sided,
                ..object.clone()
            }));
        }
        (owners, parts) = (parts_of, animated_of);
    }
    check::check(file)?;
    let clip = (!animated.is_empty()).then(|| PlacedClip::new(animated, parts));
    Ok(Placed { meshes, owners: Some(owners), clip })
}
