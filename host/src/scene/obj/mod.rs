//! An OBJ file with its material library (MTL) as a scene: one more way to fill the scene model,
//! as glTF is. Each group of faces of one material becomes a mesh shape and an object; each MTL
//! material a diffuse material of its `Kd`, times its `map_Kd` texture, with its `Ke` and
//! `map_Ke` as emission. The model is framed and lit as a glTF model without camera or lights
//! (`framing`). What it has that twinray does not model is named in one notice, and so is a
//! material library or texture that cannot be read (OBJ files often travel without them):
//! the faces are drawn without it.

use super::file::{EmissionDesc, MaterialDesc, ObjectDesc};
use super::framing::{self, ignore_found, Model, View};
use super::gltf::{mesh_shape, DEFAULT_MATERIAL};
use super::mesh;
use super::texture::{self, SamplerDesc, TextureDesc};
use crate::util::input::{confined, read_bounded, Unconfined};
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use std::sync::Arc;

mod mtl;

/// Whether `path` names an OBJ file, by its extension.
pub fn is_obj(path: &Path) -> bool {
    path.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("obj"))
}

/// Reads the OBJ file at `path` and the material libraries and textures it names (beside it),
/// all within the mesh file size limit together; the error says what is wrong.
pub fn load(path: &Path) -> Result<Model, String> {
    let mut budget = mesh::max_mesh_bytes()?;
    let folder = path.parent().unwrap_or(Path::new("."));
    let bytes = read_bounded(path, budget).map_err(|e| format!("cannot read: {e}"))?;
    budget -= bytes.len() as u64;
    let text = mesh::obj_text(&bytes, true);
    drop(bytes);
    // tobj hands the loader no mutable state: what it read and what it could not go through
    // cells.
    let (spent, unread) = (std::cell::Cell::new(0u64), std::cell::RefCell::new(BTreeSet::new()));
    let refused = std::cell::RefCell::new(None);
    let mut reader = std::io::BufReader::new(text.as_bytes());
    let (models, materials) = tobj::load_obj_buf(&mut reader, &mesh::OBJ_OPTIONS, |name| {
        let name = local(&name.to_string_lossy());
        let read = confined(folder, &name).and_then(|path| {
            read_bounded(&path, budget.saturating_sub(spent.get())).map_err(|e| Unconfined::Unreadable(e.to_string()))
        });
        match read {
            Ok(bytes) => {
                spent.set(spent.get() + bytes.len() as u64);
                Ok(mtl::parse(&String::from_utf8_lossy(&bytes)))
            }
            Err(Unconfined::Unreadable(e)) => {
                unread.borrow_mut().insert(format!("material library {name:?} ({e}: default material)"));
                Ok(Default::default())
            }
            Err(Unconfined::Outside(e)) => {
                refused.borrow_mut().get_or_insert(format!("material library: cannot read {e}"));
                Ok(Default::default())
            }
        }
    })
    .map_err(|e| format!("cannot read: {e}"))?;
    if let Some(refused) = refused.into_inner() {
        return Err(refused);
    }
    budget = budget.saturating_sub(spent.get());
    let mut ignored = unread.into_inner();
    let materials = materials.unwrap_or_default();
    let mut described = BTreeMap::new();
    let mut decoded = BTreeMap::new();
    let mut files = Files { folder, budget: &mut budget, decoded: &mut decoded, refused: None };
    let (mut meshes, mut objects) = (BTreeMap::new(), Vec::new());
    for (i, m) in models.iter().enumerate().filter(|(_, m)| !m.mesh.indices.is_empty()) {
        let shape = format!("group {i} {:?}", m.name);
        meshes.insert(shape.clone(), mesh::from_models(std::slice::from_ref(m), &shape, Default::default())?);
        let material = match m.mesh.material_id.and_then(|k| materials.get(k)) {
            Some(mtl) => material(mtl, &mut described, &mut files, &mut ignored)?,
            None => {
                described.entry(DEFAULT_MATERIAL.to_string()).or_insert_with(default_material);
                DEFAULT_MATERIAL.to_string()
            }
        };
        objects.push(ObjectDesc::placed(shape, material, None));
        if !m.mesh.normals.is_empty() {
            ignored.insert("vertex normals (vn: flat normals used)".into());
        }
    }
    if let Some(refused) = files.refused {
        return Err(refused);
    }
    if objects.is_empty() {
        return Err("it has no faces".into());
    }
    let view = View::framed(&objects, &meshes);
    let shapes = meshes.keys().map(|name| (name.clone(), mesh_shape(name))).collect();
    let file = framing::scene_file("an OBJ model", view, shapes, described, objects);
    Ok(Model { file, meshes, ignored, clip: None })
}

/// A path an MTL file gives (`.\wood.jpg` from Windows tools) as one relative to its folder.
fn local(path: &str) -> String {
    path.trim().replace('\\', "/")
}

fn default_material() -> MaterialDesc {
    MaterialDesc::Diffuse { color: [0.8; 3], texture: None, emission: None }
}

/// Where a model's textures are read from, how many more bytes may be read, and the images
/// decoded so far by file name.
struct Files<'a> {
    folder: &'a Path,
    budget: &'a mut u64,
    decoded: &'a mut BTreeMap<String, Arc<texture::TextureImage>>,
    /// A texture refused for lying outside the model's folder: the load fails with it.
    refused: Option<String>,
}

/// The name of `mtl`'s twinray material, added to `described` the first time.
fn material(
    mtl: &tobj::Material,
    described: &mut BTreeMap<String, MaterialDesc>,
    files: &mut Files,
    ignored: &mut BTreeSet<String>,
) -> Result<String, String> {
    let name = format!("material {:?}", mtl.name);
    if described.contains_key(&name) {
        return Ok(name);
    }
    let mut texture = |file: Option<&String>| {
        let read = read_texture(file?, files);
        read.map_err(|e| ignored.insert(format!("material {:?}: {e} (untextured)", mtl.name))).ok()
    };
    let own = texture(mtl.diffuse_texture.as_ref());
    let emission = match mtl.emissive {
        Some(color) if color != [0.0; 3] => {
            Some(Box::new(EmissionDesc { color, intensity: 1.0, texture: texture(mtl.unknown_param.get("map_Ke")) }))
        }
        _ => None,
    };
    let (texture, color) = (own, mtl.diffuse.unwrap_or([0.8; 3]));
    described.insert(name.clone(), MaterialDesc::Diffuse { color, texture, emission });
    let found = [
        (mtl.specular.is_some_and(|s| s != [0.0; 3]) || mtl.specular_texture.is_some(), "specular (shaded as diffuse)"),
        (mtl.dissolve.is_some_and(|d| d < 1.0) || mtl.dissolve_texture.is_some(), "dissolve (drawn opaque)"),
        (mtl.normal_texture.is_some() || mtl.unknown_param.contains_key("map_bump"), "bump and normal maps"),
        (mtl.ambient_texture.is_some() || mtl.shininess_texture.is_some(), "ambient and shininess maps"),
    ];
    ignore_found(ignored, &found);
    Ok(name)
}

/// The texture of image `file` (relative to the model's folder, sRGB), read bounded and
/// decoded once per model.
fn read_texture(file: &str, files: &mut Files) -> Result<Box<TextureDesc>, String> {
    let file = local(file);
    let image = match files.decoded.get(&file) {
        Some(image) => image.clone(),
        None => {
            let path = match confined(files.folder, &file) {
                Ok(path) => path,
                Err(Unconfined::Unreadable(e)) => return Err(format!("cannot read texture {e}")),
                Err(Unconfined::Outside(e)) => {
                    let refused = format!("texture: cannot read {e}");
                    files.refused.get_or_insert(refused.clone());
                    return Err(refused);
                }
            };
            let bytes = read_bounded(&path, *files.budget).map_err(|e| format!("cannot read texture {file:?}: {e}"))?;
            *files.budget = files.budget.saturating_sub(bytes.len() as u64);
            let image = Arc::new(texture::decode(&file, &bytes, true, files.budget).map_err(|e| e.to_string())?);
            files.decoded.insert(file.clone(), image.clone());
            image
        }
    };
    Ok(Box::new(TextureDesc {
        file,
        uv: 0,
        sampler: SamplerDesc::DEFAULT,
        transform: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        image: Some(image),
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Three groups: a red one, one textured through a Windows path, and one whose texture is
    /// missing (drawn untextured, and said).
    #[test]
    fn groups_take_their_library_s_materials_and_textures() {
        let dir = tempfile::tempdir().unwrap();
        image::RgbaImage::from_pixel(2, 2, image::Rgba([0, 255, 0, 255])).save(dir.path().join("green.png")).unwrap();
        let mtl = "newmtl red\nKd 1 0 0\nnewmtl green\nKd 1 1 1\nmap_Kd .\\green.png\nKe 0.5 0.5 0.5\n\
                   newmtl lost\nKd 0 0 1\nmap_Kd missing.png\n";
        std::fs::write(dir.path().join("lib.mtl"), mtl).unwrap();
        let obj = "mtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n\
                   usemtl red\nf 1 2 3\nusemtl green\nf 2/2 4/1 3/3\nusemtl lost\nf 1 3 4\nusemtl\n";
        let path = dir.path().join("model.obj");
        std::fs::write(&path, obj).unwrap();
        let model = load(&path).unwrap();
        assert_eq!(model.file.objects.len(), 3);
        let material = |name: &str| model.file.materials[&format!("material {name:?}")].clone();
        assert!(matches!(material("red"), MaterialDesc::Diffuse { color: [1.0, 0.0, 0.0], texture: None, .. }));
        let MaterialDesc::Diffuse { texture: Some(t), emission: Some(e), .. } = material("green") else { panic!() };
        assert_eq!((t.file.as_str(), t.image.as_ref().map(|i| i.width)), ("./green.png", Some(2)));
        assert_eq!(e.color, [0.5; 3]);
        assert!(matches!(material("lost"), MaterialDesc::Diffuse { color: [0.0, 0.0, 1.0], texture: None, .. }));
        let said: Vec<_> = model.ignored.iter().filter(|i| i.contains("missing.png")).collect();
        assert_eq!(said.len(), 1, "{:?}", model.ignored);
        // The faces' texture coordinates came with them, v turned to run down the image.
        let green = &model.meshes[&model.file.objects[1].shape];
        assert!(green.vertices.iter().any(|v| v.uv.y == 0.0) && green.vertices.iter().any(|v| v.uv.x == 1.0));
    }

    #[test]
    fn a_missing_library_leaves_the_default_material_and_is_said() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("model.obj");
        std::fs::write(&path, "mtllib nowhere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n").unwrap();
        let model = load(&path).unwrap();
        assert_eq!(model.file.objects[0].material, DEFAULT_MATERIAL);
        assert!(model.ignored.iter().any(|i| i.contains("nowhere.mtl")), "{:?}", model.ignored);
        std::fs::write(&path, "v 0 0 0\nv 1 0 0\n").unwrap();
        assert_eq!(load(&path).err().as_deref(), Some("it has no faces"));
    }
}
