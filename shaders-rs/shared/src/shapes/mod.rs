//! The procedural shapes. Each is a module of this folder (its f32 intersection routines, its
//! scene kinds and CPU tests) and one line of [`procedural_shapes!`](crate::procedural_shapes).
//! The module catalog, the GLSL include, the host's scene format and hit groups and the docs'
//! shape table follow from that line; its Rust intersection stages are written out in the
//! shaders crate (`cargo xtask new-shape` writes them).

pub mod boxes;
pub mod cone;
pub mod cylinder;
#[cfg(not(target_arch = "spirv"))]
pub mod mitsuba;
pub mod plane;
#[cfg(not(target_arch = "spirv"))]
pub mod spec;
pub mod sphere;
pub mod torus;
pub mod uv;

pub use uv::ShapeUv;

/// The registry of procedural shapes, one line each, in hit-kind order:
///
/// `"NAME" => MODULE (HIT_KIND): NAME_intersection [, naive NAME_naive_intersection];`
///
/// - `NAME` names the shape in reports; its GLSL twin is `shapes/NAME.glsl` among the GLSL twins, with
///   `bool NAME_intersect(..)` (and `NAME_naive_intersect`), and its hit kind is
///   `HIT_KIND_NAME` in GLSL.
/// - `MODULE` is the module of this folder holding `intersect` (and `naive_intersect`), `uv`
///   (its texture coordinates, by the conventions of [`uv`]) and, on the CPU, `SHAPE`, the
///   [`spec::ShapeSpec`] with its scene kinds.
/// - `HIT_KIND` is what its intersection stage reports (`hit_kind::MODULE`): unique, from 1.
/// - `NAME_intersection` is the name of the compiled module in both sets, and of its Rust
///   entry point (in the shaders crate's `intersection.rs`, written out by hand); `naive`
///   adds the textbook variant kept on purpose, for shapes that have one.
///
/// Call it with the name of a macro that takes the lines (see `catalog.rs` and the shaders
/// crate): `procedural_shapes!(m)` expands to `m! { LINES }`, the lines below, so each user
/// of the registry writes one macro that turns the lines into what it needs.
#[macro_export]
macro_rules! procedural_shapes {
    ($callback:ident) => {
        $callback! {
            "sphere" => sphere (1): sphere_intersection, naive sphere_naive_intersection;
            "plane" => plane (2): plane_intersection;
            "box" => boxes (3): box_intersection;
            "cylinder" => cylinder (4): cylinder_intersection, naive cylinder_naive_intersection;
            "cone" => cone (5): cone_intersection;
            "torus" => torus (6): torus_intersection, naive torus_naive_intersection;
        }
    };
}

/// Added to a shape's hit kind in [`crate::layout::ObjectData::shape`] for its naive variant.
pub const SHAPE_NAIVE: u32 = 0x80;

/// Expands the registry's lines to `hit_kind`, and to `intersect_shape`, one `if` per shape
/// (and its naive variant).
macro_rules! dispatch {
    ($($name:literal => $module:ident ($kind:literal): $entry:ident $(, naive $naive:ident)?;)*) => {
        /// Each shape's hit kind, named by its module: what its intersection stages report.
        #[allow(non_upper_case_globals)]
        pub mod hit_kind {
            $(
                #[doc = concat!("The hit kind of ", $name, ".")]
                pub const $module: u32 = $kind;
            )*
        }

        /// The first hit of `shape`'s routine (its hit kind, plus [`SHAPE_NAIVE`] for the naive
        /// variant) with the primitive, as its intersection stage finds it; for stages that
        /// meet procedural primitives themselves (ray queries). `None` for an unknown shape.
        pub fn intersect_shape(
            shape: u32,
            origin: glam::Vec3,
            direction: glam::Vec3,
            primitive: &crate::layout::Primitive,
            t_min: f32,
            t_max: f32,
        ) -> Option<crate::surface::SurfaceHit> {
            $(
                if shape == $kind {
                    return $module::intersect(origin, direction, primitive, t_min, t_max);
                }
                $(
                    // The naive variant `$naive`.
                    if shape == $kind + SHAPE_NAIVE {
                        let _ = stringify!($naive);
                        return $module::naive_intersect(origin, direction, primitive, t_min, t_max);
                    }
                )?
            )*
            None
        }

        /// The sphere shape `shape`'s `primitive` lies in (its module's `bound`), where
        /// `transform::stage_ray` brings far rays before the transform; zero, which brings no
        /// ray anywhere, for an unknown shape and for the naive variants, which keep the
        /// textbook transform as they keep the textbook formula.
        pub fn shape_bound(shape: u32, primitive: &crate::layout::Primitive) -> glam::Vec4 {
            $(
                if shape == $kind {
                    return $module::bound(primitive);
                }
            )*
            glam::Vec4::ZERO
        }

        /// The texture coordinates of shape `kind` (its hit kind: the naive variant's too) at
        /// the object-space point `p` of `primitive`, where its intersection reported the
        /// normal `n` (`uv` of its module). Zero for an unknown shape.
        pub fn shape_uv(kind: u32, primitive: &crate::layout::Primitive, p: glam::Vec3, n: glam::Vec3) -> ShapeUv {
            $(
                if kind == $kind {
                    return $module::uv(primitive, p, n);
                }
            )*
            ShapeUv { uv: glam::Vec2::ZERO, du: glam::Vec3::ZERO, dv: glam::Vec3::ZERO }
        }
    };
}

crate::procedural_shapes!(dispatch);

/// A registered procedural shape.
#[cfg(not(target_arch = "spirv"))]
#[derive(Debug)]
pub struct Shape {
    /// Its name: the scene format's shape kind family and its hit group's name.
    pub name: &'static str,
    /// The hit kind its intersection stage reports (`bindings::HIT_KIND_*`).
    pub hit_kind: u32,
    /// The intersection module: `NAME_intersection`.
    pub module: &'static str,
    /// The textbook variant's module, for shapes that keep one.
    pub naive_module: Option<&'static str>,
    /// Its scene keys and what they make (`spec::ShapeSpec`).
    pub spec: &'static spec::ShapeSpec,
}

/// Expands to `None`, or to `Some("NAME")` for an identifier: a shape's optional naive module.
#[cfg(not(target_arch = "spirv"))]
macro_rules! optional_name {
    () => {
        None
    };
    ($name:ident) => {
        Some(stringify!($name))
    };
}

/// Expands the registry's lines to `SHAPES`, one [`Shape`] per line.
#[cfg(not(target_arch = "spirv"))]
macro_rules! shape_table {
    ($($name:literal => $module:ident ($kind:literal): $entry:ident $(, naive $naive:ident)?;)*) => {
        /// Every procedural shape, in registration order.
        pub const SHAPES: &[Shape] = &[$(Shape {
            name: $name,
            hit_kind: $kind,
            module: stringify!($entry),
            naive_module: optional_name!($($naive)?),
            spec: &$module::SHAPE,
        },)*];
    };
}

#[cfg(not(target_arch = "spirv"))]
crate::procedural_shapes!(shape_table);

/// The shape called `name`.
#[cfg(not(target_arch = "spirv"))]
pub fn shape(name: &str) -> Option<&'static Shape> {
    SHAPES.iter().find(|s| s.name == name)
}

/// The scene kind called `name`, with the shape that draws it.
#[cfg(not(target_arch = "spirv"))]
pub fn kind(name: &str) -> Option<(&'static Shape, &'static spec::ShapeKind)> {
    SHAPES.iter().find_map(|s| s.spec.kinds.iter().find(|k| k.name == name).map(|k| (s, k)))
}

/// Marks the start and end of the shape table in twinray's guide, *Scene format*.
#[cfg(not(target_arch = "spirv"))]
pub const DOCS_BEGIN: &str = "<!-- shape table: generated by `cargo xtask shaders` from twinray_shared::shapes -->";
#[cfg(not(target_arch = "spirv"))]
/// Marks the end of the shape table in twinray's guide, *Scene format*.
pub const DOCS_END: &str = "<!-- end of the generated shape table -->";

/// The docs' table of shape kinds: every registered kind, then meshes (the host's own kind),
/// and which kinds take `formula`; between [`DOCS_BEGIN`] and [`DOCS_END`].
#[cfg(not(target_arch = "spirv"))]
pub fn docs_table() -> String {
    let mut rows =
        vec![DOCS_BEGIN.to_string(), "| kind | keys | hit group | meaning |".into(), "|---|---|---|---|".into()];
    let mut naive = Vec::new();
    for s in SHAPES {
        for k in s.spec.kinds {
            let mut keys: Vec<String> = k.params.iter().map(|p| p.describe()).collect();
            if !k.relations.is_empty() {
                keys.push(k.relations.to_string());
            }
            rows.push(format!("| `{}` | {} | {} | {} |", k.name, keys.join(", "), s.name, k.about));
            if s.naive_module.is_some() {
                naive.push(format!("`{}`", k.name));
            }
        }
    }
    rows.push("| `mesh` | `builtin` or `file`, `normals` | triangles | a triangle mesh (below) |".into());
    rows.push("| `gltf` | `file`, `scene` | triangles | a glTF 2.0 model's parts (below) |".into());
    rows.push(String::new());
    rows.push(format!("Kinds that also take `formula` (`\"robust\"` or `\"naive\"`): {}.", naive.join(", ")));
    rows.push(DOCS_END.to_string());
    rows.join("\n") + "\n"
}

/// `doc` with its shape table replaced by [`docs_table`]; an error if the markers are missing.
#[cfg(not(target_arch = "spirv"))]
pub fn with_docs_table(doc: &str) -> Result<String, String> {
    let start = doc.find(DOCS_BEGIN).ok_or("the shape table's start marker is missing")?;
    let end = doc[start..].find(DOCS_END).ok_or("the shape table's end marker is missing")? + start + DOCS_END.len();
    let end = end + usize::from(doc[end..].starts_with('\n'));
    Ok(format!("{}{}{}", &doc[..start], docs_table(), &doc[end..]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_hit_kinds_and_modules_follow_the_conventions() {
        for (i, s) in SHAPES.iter().enumerate() {
            assert_eq!(s.module, format!("{}_intersection", s.name), "{}", s.name);
            if let Some(naive) = s.naive_module {
                assert_eq!(naive, format!("{}_naive_intersection", s.name), "{}", s.name);
            }
            assert!(s.hit_kind >= 1, "{}: hit kinds start at 1", s.name);
            assert!(SHAPES[..i].iter().all(|o| o.hit_kind != s.hit_kind), "{}: hit kind {} taken", s.name, s.hit_kind);
            assert!(SHAPES[..i].iter().all(|o| o.name != s.name), "{} registered twice", s.name);
            assert!(!s.spec.kinds.is_empty(), "{} has no scene kind", s.name);
        }
    }

    #[test]
    fn scene_kinds_are_unique_and_their_defaults_pass_their_rules() {
        let mut seen = Vec::new();
        for s in SHAPES {
            for k in s.spec.kinds {
                assert!(!seen.contains(&k.name) && k.name != "mesh", "kind {} defined twice", k.name);
                seen.push(k.name);
                for p in k.params {
                    if let Some(v) = p.default {
                        p.check(v).unwrap_or_else(|e| panic!("{}.{}: default fails: {e}", k.name, p.name));
                    }
                }
            }
        }
    }
}
