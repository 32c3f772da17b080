//! What a scene may use that costs its stages code: the one list of these features, shared by
//! the host (which sets the bits the scene uses) and both shader sets (which skip the code of a
//! feature whose bit is clear). The bits reach every stage as one specialisation constant,
//! `SPEC_FEATURES`, so the driver drops a feature's code where the scene does not use it: a
//! scene pays only for what it uses. GLSL reads the same bits from the generated layout include
//! (`HAS_FEATURE_TEXTURES`, ...).
//!
//! A set can also be built without a feature's code at all (`cargo xtask shaders --without
//! textures --out DIR`: the cargo feature `without-textures`, GLSL's `TWINRAY_WITHOUT_TEXTURES`),
//! the baseline that measures whether specialisation leaves anything of the code behind
//! (twinray's guide, *Measuring*).

/// One feature: its bit in `SPEC_FEATURES`, its name (in `--without` and reports), and what in
/// a scene turns it on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Feature {
    /// Its bit in `SPEC_FEATURES`.
    pub bit: u32,
    /// Its name, as `--without`, scene files and reports write it.
    pub name: &'static str,
    /// What in a scene turns it on, in words.
    pub used_by: &'static str,
}

/// Textures: a material samples a base colour, emission or alpha texture.
pub const TEXTURES: u32 = 1 << 0;
/// Area lights: a rect light, whose N x N shadow samples lie at random places on it.
pub const AREA_LIGHTS: u32 = 1 << 1;
/// Alpha masks: a cutout material, whose holes inline rays (ray queries) must test.
pub const ALPHA_MASKS: u32 = 1 << 2;
/// Emission: a material that emits (an emissive material, or one with emission).
pub const EMISSION: u32 = 1 << 3;
/// Far instances: an object placed far from the world origin for its size, whose
/// intersection stages compute their object-space ray themselves, the translation taken off
/// first (`crate::transform`); elsewhere they take the driver's, which costs nothing.
pub const FAR_INSTANCES: u32 = 1 << 4;
/// Light cones: a point light with a range or a spot cone (`crate::lighting::falloff`).
pub const LIGHT_CONES: u32 = 1 << 5;

/// Every feature, in bit order.
pub const FEATURES: [Feature; 6] = [
    Feature { bit: TEXTURES, name: "textures", used_by: "a material with a texture" },
    Feature { bit: AREA_LIGHTS, name: "area-lights", used_by: "a rect light" },
    Feature { bit: ALPHA_MASKS, name: "alpha-masks", used_by: "a cutout material" },
    Feature { bit: EMISSION, name: "emission", used_by: "an emissive material or one with emission" },
    Feature { bit: FAR_INSTANCES, name: "far-instances", used_by: "an object far from the origin for its size" },
    Feature { bit: LIGHT_CONES, name: "light-cones", used_by: "a point light with a range or a spot cone" },
];

/// Every feature's bit: what a stage assumes when nothing specialises it.
pub const ALL: u32 = TEXTURES | AREA_LIGHTS | ALPHA_MASKS | EMISSION | FAR_INSTANCES | LIGHT_CONES;

/// The features whose code this build of the crate holds: all but those its cargo features
/// `without-NAME` leave out (only a baseline set for measuring is built so).
pub const BUILT: u32 = ALL
    & !(if cfg!(feature = "without-textures") { TEXTURES } else { 0 })
    & !(if cfg!(feature = "without-area-lights") { AREA_LIGHTS } else { 0 })
    & !(if cfg!(feature = "without-alpha-masks") { ALPHA_MASKS } else { 0 })
    & !(if cfg!(feature = "without-emission") { EMISSION } else { 0 })
    & !(if cfg!(feature = "without-far-instances") { FAR_INSTANCES } else { 0 })
    & !(if cfg!(feature = "without-light-cones") { LIGHT_CONES } else { 0 });

/// The features a stage may use: the bits of its `SPEC_FEATURES` that this build holds code for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Features(u32);

impl Features {
    /// From the specialisation constant's value.
    #[inline(always)]
    pub fn new(spec: u32) -> Self {
        Features(spec)
    }

    /// Every feature (what the CPU references and tests assume).
    pub const fn all() -> Self {
        Features(BUILT)
    }

    /// Whether feature `F` (one of the bits above) may be used. Where the build lacks its code
    /// the answer is a constant false and the code after it is never compiled in.
    #[inline(always)]
    pub fn has<const F: u32>(self) -> bool {
        // A constant block, not a mask: rust-gpu folds no arithmetic, but a branch on a
        // constant is no branch, so a build without the feature emits none of its code.
        if const { BUILT & F == 0 } {
            return false;
        }
        self.0 & F != 0
    }
}

impl Feature {
    /// The feature's name in GLSL macros: `TEXTURES` in `FEATURE_TEXTURES`,
    /// `HAS_FEATURE_TEXTURES` and `TWINRAY_WITHOUT_TEXTURES`.
    #[cfg(not(target_arch = "spirv"))]
    pub fn macro_name(&self) -> String {
        self.name.replace('-', "_").to_uppercase()
    }
}

/// The feature named `name`.
pub fn by_name(name: &str) -> Option<&'static Feature> {
    FEATURES.iter().find(|f| f.name == name)
}

/// The names of the features in `bits`, comma-separated ("none" for none); `names(ALL)` lists
/// every feature.
#[cfg(not(target_arch = "spirv"))]
pub fn names(bits: u32) -> String {
    let named: Vec<&str> = FEATURES.iter().filter(|f| bits & f.bit != 0).map(|f| f.name).collect();
    if named.is_empty() {
        "none".into()
    } else {
        named.join(",")
    }
}

/// The bits of `text`: `all`, `none`, or feature names joined by commas (`textures,emission`).
#[cfg(not(target_arch = "spirv"))]
pub fn bits_named(text: &str) -> Result<u32, String> {
    match text.trim() {
        "all" => return Ok(ALL),
        "none" | "" => return Ok(0),
        _ => {}
    }
    let mut bits = 0;
    for name in text.split(',').map(str::trim) {
        match by_name(name) {
            Some(f) => bits |= f.bit,
            None => return Err(format!("no feature {name:?} (features: all, none, {})", names(ALL))),
        }
    }
    Ok(bits)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bits_are_distinct_and_all_is_their_union() {
        let union = FEATURES.iter().fold(0, |acc, f| {
            assert_eq!(f.bit.count_ones(), 1, "{}", f.name);
            assert_eq!(acc & f.bit, 0, "{} repeats a bit", f.name);
            acc | f.bit
        });
        assert_eq!(union, ALL);
        assert_eq!(names(TEXTURES | EMISSION), "textures,emission");
        assert_eq!(names(0), "none");
        assert_eq!(by_name("area-lights").map(|f| f.bit), Some(AREA_LIGHTS));
        assert_eq!(bits_named("all"), Ok(ALL));
        assert_eq!(bits_named("none"), Ok(0));
        assert_eq!(bits_named("textures, emission"), Ok(TEXTURES | EMISSION));
        assert!(bits_named("textures,glow").is_err_and(|e| e.contains("\"glow\"") && e.contains("area-lights")));
    }

    #[test]
    fn a_feature_is_used_only_where_specialised_on_and_built() {
        let f = Features::new(TEXTURES);
        assert!(f.has::<TEXTURES>());
        assert!(!f.has::<AREA_LIGHTS>());
        assert!(Features::all().has::<EMISSION>());
    }
}
