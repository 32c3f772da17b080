//! A crate's description of its shapes and materials, as its CPU library writes it
//! (`twinray_shared::custom::abi::description`), read into what the host keeps: every name,
//! hit kind, key type and rule checked again here, since the library is the crate's code.

use serde::Deserialize;
use twinray_shared::custom::{BUILTIN_MATERIALS, FIRST_HIT_KIND, LAST_HIT_KIND};
use twinray_shared::shapes::spec::{Param, ParamType, Rule, Value};
use twinray_shared::shapes::SHAPES;

/// One shape of a crate, as its library describes it.
#[derive(Clone, Debug)]
pub struct OwnShape {
    /// The scene kind, and its module's name less `_intersection`.
    pub name: &'static str,
    /// Its module: `NAME_intersection`.
    pub module: &'static str,
    pub about: String,
    pub hit_kind: u32,
    /// Its keys, with their rules and defaults.
    pub params: &'static [Param],
}

/// One material of a crate, as its library describes it.
#[derive(Clone, Debug)]
pub struct OwnMaterial {
    /// The scene kind, and its module's name less `_material`.
    pub name: &'static str,
    /// Its callable module: `NAME_material`.
    pub module: &'static str,
    pub about: String,
    /// Its keys, with their rules and defaults.
    pub params: &'static [Param],
}

#[derive(Deserialize)]
pub(super) struct Described {
    pub contract: String,
    pub error: Option<String>,
    pub shapes: Vec<DescribedShape>,
    pub materials: Vec<DescribedMaterial>,
    #[serde(default = "twinray_depth")]
    pub recursion_depth: u32,
}

fn twinray_depth() -> u32 {
    twinray_shared::interface::MAX_RECURSION_DEPTH
}

#[derive(Deserialize)]
pub(super) struct DescribedShape {
    name: String,
    about: String,
    hit_kind: u32,
    params: Vec<DescribedParam>,
}

#[derive(Deserialize)]
pub(super) struct DescribedParam {
    name: String,
    #[serde(rename = "type")]
    ty: String,
    rule: String,
    max: Option<u32>,
    default: Option<Vec<f64>>,
}

fn leak(text: String) -> &'static str {
    Box::leak(text.into_boxed_str())
}

/// A described shape as the host keeps it, or why it cannot be one of a scene's kinds.
pub(super) fn own_shape(s: DescribedShape) -> Result<OwnShape, String> {
    let builtin = SHAPES.iter().flat_map(|b| b.spec.kinds.iter().map(|k| k.name)).chain(["mesh", "gltf"]);
    if builtin.clone().any(|k| k == s.name) {
        return Err(format!("shape {:?}: twinray has a shape kind of that name", s.name));
    }
    if !(FIRST_HIT_KIND..=LAST_HIT_KIND).contains(&s.hit_kind) {
        return Err(format!(
            "shape {:?}: hit kind {} is not in {FIRST_HIT_KIND}..={LAST_HIT_KIND}",
            s.name, s.hit_kind
        ));
    }
    let params = own_params("shape", &s.name, s.params)?;
    Ok(OwnShape {
        module: leak(format!("{}_intersection", s.name)),
        name: leak(s.name),
        about: s.about,
        hit_kind: s.hit_kind,
        params,
    })
}

#[derive(Deserialize)]
pub(super) struct DescribedMaterial {
    name: String,
    about: String,
    params: Vec<DescribedParam>,
}

/// A described material as the host keeps it, or why it cannot be one of a scene's kinds.
pub(super) fn own_material(m: DescribedMaterial) -> Result<OwnMaterial, String> {
    if BUILTIN_MATERIALS.contains(&m.name.as_str()) {
        return Err(format!("material {:?}: twinray has a material kind of that name", m.name));
    }
    let params = own_params("material", &m.name, m.params)?;
    Ok(OwnMaterial { module: leak(format!("{}_material", m.name)), name: leak(m.name), about: m.about, params })
}

fn own_params(what: &str, name: &str, params: Vec<DescribedParam>) -> Result<&'static [Param], String> {
    let params = params.into_iter().map(|p| own_param(what, name, p)).collect::<Result<Vec<_>, _>>()?;
    Ok(Box::leak(params.into_boxed_slice()))
}

fn own_param(what: &str, name: &str, p: DescribedParam) -> Result<Param, String> {
    let unknown = |item: &str, word: &str| format!("{what} {name:?}: key {:?}: unknown {item} {word:?}", p.name);
    let ty = match p.ty.as_str() {
        "number" => ParamType::Number,
        "pair" => ParamType::Pair,
        "triple" => ParamType::Triple,
        "count" => ParamType::Count,
        other => return Err(unknown("type", other)),
    };
    let rule = match (p.rule.as_str(), p.max) {
        ("finite", _) => Rule::Finite,
        ("positive", _) => Rule::Positive,
        ("any", _) => Rule::Any,
        ("count_up_to", Some(max)) => Rule::CountUpTo(max),
        (other, _) => return Err(unknown("rule", other)),
    };
    let default = match (ty, p.default.as_deref()) {
        (_, None) => None,
        (ParamType::Count, Some([x])) => Some(Value::Count(*x as u32)),
        (ParamType::Number, Some([x])) => Some(Value::Number(*x as f32)),
        (ParamType::Pair, Some([x, y])) => Some(Value::Pair([*x as f32, *y as f32])),
        (ParamType::Triple, Some([x, y, z])) => Some(Value::Triple([*x as f32, *y as f32, *z as f32])),
        (_, Some(other)) => {
            return Err(format!(
                "{what} {name:?}: key {:?}: a default of {} values for a {}",
                p.name,
                other.len(),
                p.ty
            ))
        }
    };
    Ok(Param { name: leak(p.name), ty, rule, default })
}
