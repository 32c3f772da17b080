//! Shapes of a user's own crate. Its `shared` library (the code its stages and the CPU share)
//! lists them in `pub const SHAPES: &[CustomShape]`; twinray builds that library for the CPU
//! once per change and reads the list through the C functions of [`abi`], so that a scene can
//! name `kind = "NAME"` with the keys the shape states, and the f64 reference can judge the
//! shape's GPU intersection against the definition the crate states in f64.
//!
//! The definition is a signed distance, negative inside, in the primitive's own space. It must
//! never exceed the true distance to the surface (an exact distance, or a lower bound), so that
//! the reference's sphere tracing cannot step past the surface. It is meant to be written apart
//! from the intersection routine: a slip in one is then caught by the other, not copied.
//!
//! Its materials ([`CustomMaterial`], `pub const MATERIALS`) are callables of its own,
//! `NAME_material`, which twinray's closest-hit stages call for the colour of a surface at a
//! point and light as any albedo. A scene's keys become the two vectors of
//! [`Material`](crate::layout::Material) the callable reads (`color_a`, `color_b`).

pub mod abi;

use crate::layout::Primitive;
use crate::shapes::spec::{Aabb, Param, Values};
use glam::{DVec3, DVec4, Vec4};

/// The first hit kind a crate's shape may report; built-in shapes report hit kinds below it.
/// Vulkan takes hit kinds up to 127 from an intersection stage.
pub const FIRST_HIT_KIND: u32 = 32;
/// The last hit kind a crate's shape may report.
pub const LAST_HIT_KIND: u32 = 127;

/// A primitive's parameters in f64, as the reference reads them: `Primitive::a` and `b`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Parameters {
    /// `Primitive::a`.
    pub a: DVec4,
    /// `Primitive::b`.
    pub b: DVec4,
}

impl Parameters {
    /// The parameters of `primitive`, widened to f64.
    pub fn of(primitive: &Primitive) -> Parameters {
        Parameters { a: primitive.a.as_dvec4(), b: primitive.b.as_dvec4() }
    }
}

/// A procedural shape a crate adds: its scene kind and keys, the primitives a shape of it
/// becomes, and its f64 definition.
#[derive(Clone, Copy)]
pub struct CustomShape {
    /// The scene kind (`kind = "NAME"`); its intersection stage is the entry point and module
    /// `NAME_intersection`. Lower-case letters, digits and `_`, a letter first.
    pub name: &'static str,
    /// One sentence for `twinray scenes` and errors.
    pub about: &'static str,
    /// What its intersection stage reports: in [`FIRST_HIT_KIND`]..=[`LAST_HIT_KIND`], one per shape.
    pub hit_kind: u32,
    /// Its scene keys (their types, rules and defaults).
    pub params: &'static [Param],
    /// Relations between keys that single keys cannot check (say, a radius below a length).
    pub check: fn(&Values) -> Result<(), String>,
    /// The primitives of one shape, each with its box, in object space.
    pub primitives: fn(&Values) -> Vec<(Primitive, Aabb)>,
    /// The signed distance from `p` to the surface of the primitive of `parameters`, negative
    /// inside; never more than the true distance.
    pub distance: fn(p: DVec3, parameters: &Parameters) -> f64,
    /// The outward normal at a point `p` of the surface (any length).
    pub normal: fn(p: DVec3, parameters: &Parameters) -> DVec3,
}

impl core::fmt::Debug for CustomShape {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name)
    }
}

/// Built-in material kinds, which no crate's material may be called.
pub const BUILTIN_MATERIALS: [&str; 4] = ["diffuse", "emissive", "checker", "cutout"];

/// A material a crate adds: its scene kind and keys, and the parameters its callable reads.
#[derive(Clone, Copy)]
pub struct CustomMaterial {
    /// The scene kind (`kind = "NAME"`); its callable stage is the entry point and module
    /// `NAME_material`. Lower-case letters, digits and `_`, a letter first.
    pub name: &'static str,
    /// One sentence for errors and the crate's scenes.
    pub about: &'static str,
    /// Its scene keys (their types, rules and defaults).
    pub params: &'static [Param],
    /// Relations between keys that single keys cannot check.
    pub check: fn(&Values) -> Result<(), String>,
    /// What its callable reads from the keys: `Material::color_a` and `Material::color_b`.
    pub parameters: fn(&Values) -> [Vec4; 2],
}

impl core::fmt::Debug for CustomMaterial {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name)
    }
}

/// Why `materials` cannot be read as a crate's list: a bad, repeated or built-in name, a key
/// named twice or a default that fails its rule.
pub fn check_materials(materials: &[CustomMaterial]) -> Result<(), String> {
    for (i, m) in materials.iter().enumerate() {
        check_name("material", m.name, materials[..i].iter().map(|o| o.name))?;
        if BUILTIN_MATERIALS.contains(&m.name) {
            return Err(format!("material {:?}: twinray has a material kind of that name", m.name));
        }
        check_keys("material", m.name, m.params)?;
    }
    Ok(())
}

/// Why `shapes` cannot be read as a crate's list: a bad or repeated name, a hit kind out of
/// range or taken, a key named twice or a default that fails its rule.
pub fn check_list(shapes: &[CustomShape]) -> Result<(), String> {
    for (i, s) in shapes.iter().enumerate() {
        check_name("shape", s.name, shapes[..i].iter().map(|o| o.name))?;
        if !(FIRST_HIT_KIND..=LAST_HIT_KIND).contains(&s.hit_kind) {
            return Err(format!(
                "shape {:?}: hit kind {} is not in {FIRST_HIT_KIND}..={LAST_HIT_KIND}",
                s.name, s.hit_kind
            ));
        }
        if let Some(o) = shapes[..i].iter().find(|o| o.hit_kind == s.hit_kind) {
            return Err(format!("shapes {:?} and {:?} both report hit kind {}", o.name, s.name, s.hit_kind));
        }
        check_keys("shape", s.name, s.params)?;
    }
    Ok(())
}

/// Why `name` cannot name a crate's shape or material (`what`), among the `earlier` names of
/// its list: lower-case letters, digits and `_`, a letter first, 48 at most, and each once.
fn check_name<'a>(what: &str, name: &str, mut earlier: impl Iterator<Item = &'a str>) -> Result<(), String> {
    let well_formed = name.starts_with(|c: char| c.is_ascii_lowercase())
        && name.chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_');
    if !well_formed || name.len() > 48 {
        return Err(format!("{what} {name:?}: a name is lower-case letters, digits and _, a letter first"));
    }
    if earlier.any(|o| o == name) {
        return Err(format!("{what} {name:?} is listed twice"));
    }
    Ok(())
}

/// Why `params`, the keys of the crate's shape or material `name`, cannot be a scene's: a key
/// named `kind` or twice, a seed, or a default that fails its own rule.
fn check_keys(what: &str, name: &str, params: &[Param]) -> Result<(), String> {
    for (j, p) in params.iter().enumerate() {
        if p.name == "kind" || params[..j].iter().any(|o| o.name == p.name) {
            return Err(format!("{what} {name:?}: key {:?} is taken", p.name));
        }
        if p.ty == crate::shapes::spec::ParamType::Seed {
            return Err(format!(
                "{what} {name:?}: key {:?} is a seed; a crate's {what} takes numbers, pairs, triples and counts",
                p.name
            ));
        }
        if let Some(v) = p.default {
            p.check(v).map_err(|e| format!("{what} {name:?}: the default of {e}"))?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests;
