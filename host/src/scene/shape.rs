//! `[shapes.NAME]` of a scene file: a kind from the shape registry (`twinray_shared::shapes`)
//! with the keys its description lists, or a triangle mesh. The registry is the only list of
//! kinds and keys; an unknown kind or key is an error with the file's line and column.

use crate::sets::own::{CrateKinds, OwnShapeRef};
use serde::de::Error as _;
use serde::{Deserialize, Deserializer};
use twinray_shared::shapes::spec::{Param, ParamType, ShapeKind, Value, Values};
use twinray_shared::shapes::{self, Shape, SHAPES};

/// Which intersection formula a shape uses: the robust one, or the textbook one it replaced,
/// kept on purpose so that probes can show what robustness buys and costs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Formula {
    /// The robust form (the default).
    #[default]
    Robust,
    /// The textbook form it replaced.
    Naive,
}

/// One shape of a scene file.
#[derive(Clone, Debug)]
pub enum ShapeDesc {
    /// A kind drawn by a registered shape's intersection stage.
    Procedural(ProceduralDesc),
    /// A kind of a shader crate's own, drawn by its intersection stage.
    Own(OwnDesc),
    /// A triangle mesh: a generated one (`builtin`) or an OBJ file (`file`, relative to the
    /// scene file's folder), with flat or smooth normals.
    Mesh(MeshDesc),
    /// A glTF 2.0 model (`file`, relative to the scene file's folder): each object of it
    /// becomes the model's objects, placed by the object (see `gltf::place`), before the scene
    /// is built.
    Gltf(GltfDesc),
}

/// A glTF model as a shape: its file, and which of its scenes (its default one if not given).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GltfDesc {
    pub file: String,
    pub scene: Option<usize>,
}

/// A procedural shape: its kind, every key's value (given or default), and the formula.
#[derive(Clone)]
pub struct ProceduralDesc {
    pub shape: &'static Shape,
    pub kind: &'static ShapeKind,
    pub values: Values,
    pub formula: Formula,
}

/// Written out by value (no addresses), so that the reference cache's key of a scene is the
/// same in every run.
impl std::fmt::Debug for ProceduralDesc {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} {:?} {:?}", self.kind.name, self.values.0, self.formula)
    }
}

/// A shape of a crate's own kind: its kind and keys as written, until the scene is loaded with
/// the sets that know the kind ([`resolve_own`]); then the crate's shape and every key's value.
#[derive(Clone)]
pub struct OwnDesc {
    pub kind: String,
    keys: toml::Table,
    pub resolved: Option<(OwnShapeRef, Values)>,
}

/// Written out by value, as [`ProceduralDesc`] is.
impl std::fmt::Debug for OwnDesc {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.resolved {
            Some((_, values)) => write!(f, "{} {:?}", self.kind, values.0),
            None => write!(f, "{} {:?}", self.kind, self.keys),
        }
    }
}

/// A mesh shape: exactly one of `builtin` and `file`, and its normals.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshDesc {
    pub builtin: Option<MeshBuiltin>,
    pub file: Option<String>,
    #[serde(default)]
    pub normals: Normals,
}

/// Meshes twinray generates, each fitting the unit cube about the origin.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MeshBuiltin {
    /// A unit cube.
    Box,
    /// A square pyramid, base at y = -0.5, apex at +0.5.
    Pyramid,
    /// A triangular prism along z.
    Prism,
    /// An icosahedron of circumradius 0.5.
    Icosahedron,
}

/// How a mesh's shading normals are made.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Normals {
    /// One normal per face.
    #[default]
    Flat,
    /// Area-weighted vertex normals, interpolated across faces.
    Smooth,
}

/// Every shape kind a scene can name: the registry's, then `mesh` and `gltf`.
pub fn kind_names() -> Vec<&'static str> {
    let mut names: Vec<_> = SHAPES.iter().flat_map(|s| s.spec.kinds.iter().map(|k| k.name)).collect();
    names.extend(["mesh", "gltf"]);
    names
}

impl<'de> Deserialize<'de> for ShapeDesc {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let mut table = toml::Table::deserialize(deserializer)?;
        let kind = match table.remove("kind") {
            Some(toml::Value::String(kind)) => kind,
            Some(other) => return Err(D::Error::custom(format!("kind must be a string (got {other})"))),
            None => return Err(D::Error::missing_field("kind")),
        };
        if kind == "mesh" {
            return toml::Value::Table(table).try_into().map(ShapeDesc::Mesh).map_err(D::Error::custom);
        }
        if kind == "gltf" {
            return toml::Value::Table(table).try_into().map(ShapeDesc::Gltf).map_err(D::Error::custom);
        }
        let Some((shape, spec)) = shapes::kind(&kind) else {
            // Perhaps a shader crate's own kind, known once the scene meets its set.
            let well_formed = kind.starts_with(|c: char| c.is_ascii_lowercase())
                && kind.chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_');
            if well_formed {
                return Ok(ShapeDesc::Own(OwnDesc { kind, keys: table, resolved: None }));
            }
            let kinds = kind_names().join(", ");
            return Err(D::Error::custom(format!("unknown shape kind {kind:?} (kinds: {kinds})")));
        };
        procedural(shape, spec, table).map(ShapeDesc::Procedural).map_err(D::Error::custom)
    }
}

/// Gives every shape of a crate's own kind in `shapes` its crate's shape and values, from the
/// kinds of `own` (the sets' crates'); an error names a kind none of them knows, or a key.
pub fn resolve_own<'a>(
    shapes: impl IntoIterator<Item = (&'a String, &'a mut ShapeDesc)>,
    own: &[&'static CrateKinds],
) -> Result<(), String> {
    for (name, shape) in shapes {
        let ShapeDesc::Own(desc) = shape else { continue };
        if desc.resolved.is_some() {
            continue;
        }
        let Some(found) = own.iter().find_map(|o| o.find(&desc.kind)) else {
            let mut kinds = kind_names();
            kinds.extend(own.iter().flat_map(|o| o.shapes.iter().map(|s| s.name)));
            let hint = if own.is_empty() {
                "; a shader crate's own kinds come with the set built from it (--shaders DIR)"
            } else {
                ""
            };
            return Err(format!(
                "shape {name:?}: unknown shape kind {:?} (kinds: {}){hint}",
                desc.kind,
                kinds.join(", ")
            ));
        };
        let values = keys(found.shape().name, found.shape().params, desc.keys.clone(), false)
            .map_err(|e| format!("shape {name:?}: {e}"))?;
        desc.resolved = Some((found, values));
    }
    Ok(())
}

/// The keys of a `kind` table, checked against the kind's description: each key known and of
/// its type, each required key present.
fn procedural(
    shape: &'static Shape,
    kind: &'static ShapeKind,
    mut table: toml::Table,
) -> Result<ProceduralDesc, String> {
    let formula = match table.remove("formula") {
        Some(v) if shape.naive_module.is_some() => {
            v.try_into::<Formula>().map_err(|e| format!("formula: {}", e.to_string().trim()))?
        }
        Some(_) => return Err(format!("a {} has no naive variant, so no `formula` key", kind.name)),
        None => Formula::Robust,
    };
    let values = keys(kind.name, kind.params, table, shape.naive_module.is_some())?;
    Ok(ProceduralDesc { shape, kind, values, formula })
}

/// The values of `params` in `table` (defaults where left out); an unknown key is an error
/// that lists the kind's keys (and `formula`, where the kind takes one).
pub(super) fn keys(
    kind: &str,
    params: &'static [Param],
    mut table: toml::Table,
    formula: bool,
) -> Result<Values, String> {
    let mut values = Vec::new();
    for param in params {
        let value = match table.remove(param.name) {
            Some(v) => parse(&v, param.ty).map_err(|e| format!("{}: {e}", param.name))?,
            None => param.default.ok_or_else(|| format!("missing key `{}` for a {kind}", param.name))?,
        };
        values.push((param.name, value));
    }
    if let Some(key) = table.keys().next() {
        let mut known: Vec<&str> = params.iter().map(|p| p.name).collect();
        if formula {
            known.push("formula");
        }
        return Err(format!("unknown key `{key}` for a {kind} (keys: kind, {})", known.join(", ")));
    }
    Ok(Values(values))
}

fn parse(value: &toml::Value, ty: ParamType) -> Result<Value, String> {
    let number = |v: &toml::Value| match v {
        toml::Value::Float(f) => Ok(*f as f32),
        toml::Value::Integer(i) => Ok(*i as f32),
        other => Err(format!("expected a number, got {other}")),
    };
    let numbers = |n: usize| -> Result<Vec<f32>, String> {
        match value {
            toml::Value::Array(items) if items.len() == n => items.iter().map(number).collect(),
            other => Err(format!("expected an array of {n} numbers, got {other}")),
        }
    };
    let integer = |max: u64| match value {
        toml::Value::Integer(i) if *i >= 0 && (*i as u64) <= max => Ok(*i as u64),
        other => Err(format!("expected an integer in 0..={max}, got {other}")),
    };
    Ok(match ty {
        ParamType::Number => Value::Number(number(value)?),
        ParamType::Pair => {
            let v = numbers(2)?;
            Value::Pair([v[0], v[1]])
        }
        ParamType::Triple => {
            let v = numbers(3)?;
            Value::Triple([v[0], v[1], v[2]])
        }
        ParamType::Count => Value::Count(integer(u64::from(u32::MAX))? as u32),
        ParamType::Seed => Value::Seed(integer(u64::MAX)?),
    })
}

impl ShapeDesc {
    /// Whether the shape has a naive variant.
    pub fn has_naive(&self) -> bool {
        matches!(self, ShapeDesc::Procedural(p) if p.shape.naive_module.is_some())
    }

    /// Sets the formula of a shape that has a naive variant; other shapes are left as they are.
    pub fn set_formula(&mut self, to: Formula) {
        if let ShapeDesc::Procedural(p) = self {
            if p.shape.naive_module.is_some() {
                p.formula = to;
            }
        }
    }

    /// How many primitives the shape has (a mesh's triangles are not primitives).
    pub fn primitive_count(&self) -> u64 {
        match self {
            ShapeDesc::Procedural(p) => (p.kind.count)(&p.values),
            // The crate's primitives are made, and counted, when the shape is checked.
            ShapeDesc::Own(_) | ShapeDesc::Mesh(_) | ShapeDesc::Gltf(_) => 0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shape(text: &str) -> Result<ShapeDesc, String> {
        toml::from_str::<toml::Table>(&format!("[s]\n{text}"))
            .map_err(|e| e.to_string())
            .and_then(|t| t["s"].clone().try_into::<ShapeDesc>().map_err(|e| e.to_string()))
    }

    #[test]
    fn reads_every_key_of_a_kind_with_defaults_and_formula() {
        let ShapeDesc::Procedural(p) =
            shape("kind = \"torus\"\nmajor_radius = 2\nminor_radius = 0.5\nformula = \"naive\"").unwrap()
        else {
            panic!("a torus is procedural")
        };
        assert_eq!((p.kind.name, p.values.number("major_radius"), p.formula), ("torus", 2.0, Formula::Naive));
        let ShapeDesc::Mesh(m) = shape("kind = \"mesh\"\nbuiltin = \"prism\"").unwrap() else { panic!("a mesh") };
        assert_eq!((m.builtin, m.normals), (Some(MeshBuiltin::Prism), Normals::Flat));
    }

    #[test]
    fn unknown_kinds_and_keys_wrong_types_and_missing_keys_are_named() {
        let cases = [
            ("kind = \"Capsule!\"", "unknown shape kind \"Capsule!\" (kinds: sphere"),
            (
                "kind = \"sphere\"\nradius = 1.0\nradiuss = 2.0",
                "unknown key `radiuss` for a sphere (keys: kind, radius, formula)",
            ),
            ("kind = \"box\"\nsize = [1.0, 2.0]", "size: expected an array of 3 numbers"),
            ("kind = \"cone\"\nradius = 1.0", "missing key `height` for a cone"),
            ("kind = \"box\"\nsize = [1, 1, 1]\nformula = \"naive\"", "a box has no naive variant"),
            ("kind = \"sphere_field\"\ncount = -3", "count: expected an integer"),
            ("kind = \"mesh\"\nbuiltin = \"box\"\nfiel = \"x.obj\"", "unknown field `fiel`"),
        ];
        for (text, message) in cases {
            let e = shape(text).err().unwrap_or_else(|| panic!("{text:?} parsed"));
            assert!(e.contains(message), "{text:?}: {e}");
        }
    }

    /// A kind twinray lacks may be a crate's, so it is refused when the scene meets its sets,
    /// naming the shape, the kinds there are, and where a crate's kinds come from.
    #[test]
    fn a_kind_of_no_set_is_refused_when_the_scene_is_resolved() {
        let ShapeDesc::Own(own) = shape("kind = \"capsul\"\nradius = 1").unwrap() else { panic!("a crate's kind") };
        assert_eq!((own.kind.as_str(), own.resolved.is_none()), ("capsul", true));
        let mut shapes = std::collections::BTreeMap::from([("c".to_string(), ShapeDesc::Own(own))]);
        let e = resolve_own(shapes.iter_mut(), &[]).unwrap_err();
        assert!(e.starts_with("shape \"c\": unknown shape kind \"capsul\" (kinds: sphere"), "{e}");
        assert!(e.ends_with("a shader crate's own kinds come with the set built from it (--shaders DIR)"), "{e}");
    }
}
