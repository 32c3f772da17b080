//! How a procedural shape appears outside the shaders: the scene kinds it provides, their keys
//! and checks, the primitives (parameters and boxes) a shape of each kind becomes, and the
//! constants its GLSL twin needs. The host's scene format, its checks, the docs table and the
//! GLSL include all read these descriptions; nothing else lists a shape's keys.

use crate::layout::Primitive;
use glam::{Vec3, Vec4};

/// Largest length or coordinate a scene may give (a radius, a size, a translation, a vertex):
/// the shaders square lengths and multiply squares (a cone's coefficients), which must stay
/// finite in f32 (3.4e38).
pub const MAX_LENGTH: f32 = 1.0e9;
/// Smallest length > 0 a shape may have: its square and their products stay normal f32s.
pub const MIN_LENGTH: f32 = 1.0e-9;

/// What a scene key holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ParamType {
    /// A number (f32).
    Number,
    /// Two numbers, `[a, b]`.
    Pair,
    /// Three numbers, `[x, y, z]`.
    Triple,
    /// A count: an integer that fits in 32 bits.
    Count,
    /// A seed: a non-negative integer of up to 64 bits.
    Seed,
}

/// A value of a scene key, as the host parsed it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    /// A number (`ParamType::Number`).
    Number(f32),
    /// Two numbers.
    Pair([f32; 2]),
    /// Three numbers.
    Triple([f32; 3]),
    /// A count.
    Count(u32),
    /// A random seed.
    Seed(u64),
}

/// What a key's value must satisfy on its own (relations between keys are the kind's `check`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rule {
    /// Every number finite, of magnitude at most `MAX_LENGTH`.
    Finite,
    /// Every number in [`MIN_LENGTH`, `MAX_LENGTH`].
    Positive,
    /// A count in `1..=max`.
    CountUpTo(u32),
    /// Any value of the type.
    Any,
}

/// One scene key of a shape kind.
#[derive(Clone, Copy, Debug)]
pub struct Param {
    /// The key as the scene file writes it.
    pub name: &'static str,
    /// The type of its value.
    pub ty: ParamType,
    /// What its value must satisfy.
    pub rule: Rule,
    /// Used when the key is left out; the key is required when `None`.
    pub default: Option<Value>,
}

impl Param {
    /// A required number > 0 (a radius, a height).
    pub const fn positive(name: &'static str) -> Param {
        Param { name, ty: ParamType::Number, rule: Rule::Positive, default: None }
    }

    /// A required pair or triple of numbers > 0 (a size).
    pub const fn positive_each(name: &'static str, ty: ParamType) -> Param {
        Param { name, ty, rule: Rule::Positive, default: None }
    }

    /// A required key of any value of its type that is finite.
    pub const fn finite(name: &'static str, ty: ParamType) -> Param {
        Param { name, ty, rule: Rule::Finite, default: None }
    }

    /// Checks `value` against the rule, naming the key (`size[1] must be > 0 (got -1)`).
    pub fn check(&self, value: Value) -> Result<(), String> {
        let numbers: &[f32] = match &value {
            Value::Number(v) => core::slice::from_ref(v),
            Value::Pair(v) => v,
            Value::Triple(v) => v,
            Value::Count(n) => {
                return match self.rule {
                    Rule::CountUpTo(max) if *n == 0 || *n > max => {
                        Err(format!("{} must be in 1..={max} (got {n})", self.name))
                    }
                    _ => Ok(()),
                }
            }
            Value::Seed(_) => return Ok(()),
        };
        let (low, positive) = match self.rule {
            Rule::Finite => (-MAX_LENGTH, false),
            Rule::Positive => (MIN_LENGTH, true),
            _ => return Ok(()),
        };
        for (i, v) in numbers.iter().enumerate() {
            if !(*v >= low && *v <= MAX_LENGTH) {
                let name = if numbers.len() > 1 { format!("{}[{i}]", self.name) } else { self.name.into() };
                return Err(if positive && *v <= 0.0 {
                    format!("{name} must be > 0 (got {v})")
                } else {
                    format!("{name} must be in [{low:e}, {MAX_LENGTH:e}] (got {v:e}): beyond, its GPU data overflows or degenerates in f32")
                });
            }
        }
        Ok(())
    }

    /// How the docs write this key: `radius` > 0, `size` [x, y, z] > 0, `count` 1..1048576.
    pub fn describe(&self) -> String {
        let ty = match self.ty {
            ParamType::Number | ParamType::Count | ParamType::Seed => "",
            ParamType::Pair => " [a, b]",
            ParamType::Triple => " [x, y, z]",
        };
        let rule = match self.rule {
            Rule::Positive => " > 0".to_string(),
            Rule::CountUpTo(max) => format!(" 1..{max}"),
            Rule::Finite | Rule::Any => String::new(),
        };
        let default = match self.default {
            Some(v) => format!(" (default {})", v.describe()),
            None => String::new(),
        };
        format!("`{}`{ty}{rule}{default}", self.name)
    }
}

impl Value {
    fn describe(&self) -> String {
        match self {
            Value::Number(v) => format!("{v}"),
            Value::Pair(v) => format!("{v:?}"),
            Value::Triple(v) => format!("{v:?}"),
            Value::Count(n) => format!("{n}"),
            Value::Seed(n) => format!("{n}"),
        }
    }
}

/// The keys of one shape in a scene file, checked against its kind's `params`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Values(pub Vec<(&'static str, Value)>);

impl Values {
    /// The value of key `name`, if the kind has that key.
    pub fn value(&self, name: &str) -> Option<Value> {
        self.0.iter().find(|(n, _)| *n == name).map(|(_, v)| *v)
    }

    fn get(&self, name: &str) -> Value {
        match self.value(name) {
            Some(v) => v,
            // The host fills every key of the kind (given or default) before building.
            None => panic!("shape key {name:?} is not one of its kind's params"),
        }
    }

    /// The number `name` holds; a kind reads only its own keys, so any other is a bug (a panic).
    pub fn number(&self, name: &str) -> f32 {
        match self.get(name) {
            Value::Number(v) => v,
            other => panic!("shape key {name:?} is {other:?}, not a number"),
        }
    }

    /// The pair `name` holds (see [`Self::number`]).
    pub fn pair(&self, name: &str) -> [f32; 2] {
        match self.get(name) {
            Value::Pair(v) => v,
            other => panic!("shape key {name:?} is {other:?}, not a pair"),
        }
    }

    /// The triple `name` holds (see [`Self::number`]).
    pub fn triple(&self, name: &str) -> [f32; 3] {
        match self.get(name) {
            Value::Triple(v) => v,
            other => panic!("shape key {name:?} is {other:?}, not a triple"),
        }
    }

    /// The count `name` holds (see [`Self::number`]).
    pub fn count(&self, name: &str) -> u32 {
        match self.get(name) {
            Value::Count(v) => v,
            other => panic!("shape key {name:?} is {other:?}, not a count"),
        }
    }

    /// The seed `name` holds (see [`Self::number`]).
    pub fn seed(&self, name: &str) -> u64 {
        match self.get(name) {
            Value::Seed(v) => v,
            other => panic!("shape key {name:?} is {other:?}, not a seed"),
        }
    }
}

/// Axis-aligned box of one procedural primitive, in object space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// The corner of smallest coordinates.
    pub min: Vec3,
    /// The corner of largest coordinates.
    pub max: Vec3,
}

impl Aabb {
    /// The box of half extents `half` about the origin.
    pub fn centered(half: Vec3) -> Aabb {
        Aabb { min: -half, max: half }
    }
}

/// One kind of shape a scene can name (`kind = "sphere"`), drawn by its shape's intersection
/// stage.
#[derive(Clone, Copy)]
pub struct ShapeKind {
    /// The scene file's `kind`.
    pub name: &'static str,
    /// One sentence for the docs table and `twinray scenes`.
    pub about: &'static str,
    /// Its scene keys.
    pub params: &'static [Param],
    /// Relations between keys that single keys cannot check (say, minor < major radius).
    pub check: fn(&Values) -> Result<(), String>,
    /// `check`'s relations as the docs write them (empty when none).
    pub relations: &'static str,
    /// How many primitives a shape of this kind has, before building them.
    pub count: fn(&Values) -> u64,
    /// The primitives of one shape of this kind, with their boxes, in object space.
    pub primitives: fn(&Values) -> Vec<(Primitive, Aabb)>,
    /// The same shape in Mitsuba 3, for `twinray crosscheck` (twinray's guide, *Shading model*); none
    /// (`mitsuba::none`) where there is no equivalent.
    pub mitsuba: fn(&Values) -> Vec<super::mitsuba::MitsubaPart>,
}

impl core::fmt::Debug for ShapeKind {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name)
    }
}

/// No relations to check.
pub fn no_check(_: &Values) -> Result<(), String> {
    Ok(())
}

/// One primitive.
pub fn one(_: &Values) -> u64 {
    1
}

/// A primitive with parameters `a` (and `b` zero, tint white) and the box of half extents `half`.
pub fn single(a: Vec4, half: Vec3) -> Vec<(Primitive, Aabb)> {
    vec![(Primitive { a, b: Vec4::ZERO, tint: Vec4::ONE }, Aabb::centered(half))]
}

/// The keys of a shape about the y axis, centred at the origin: `radius` and `height`.
pub const RADIUS_AND_HEIGHT: &[Param] = &[Param::positive("radius"), Param::positive("height")];

/// The primitive of a shape of [`RADIUS_AND_HEIGHT`]: `a.x` the radius, `a.y` half the height.
pub fn radius_and_half_height(v: &Values) -> Vec<(Primitive, Aabb)> {
    let (r, h) = (v.number("radius"), v.number("height"));
    single(Vec4::new(r, h / 2.0, 0.0, 0.0), Vec3::new(r, h / 2.0, r))
}

/// What the host needs of a procedural shape beyond its registration line.
#[derive(Clone, Copy, Debug)]
pub struct ShapeSpec {
    /// The scene kinds this shape draws; usually one, named like the shape.
    pub kinds: &'static [ShapeKind],
    /// Constants the GLSL twin reads, written into `twinray_layout.glsl` as `#define`s.
    pub glsl_constants: &'static [(&'static str, f32)],
}

/// Largest number of primitives one shape may have.
pub const MAX_PRIMITIVES: u32 = 1 << 20;
