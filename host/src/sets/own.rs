//! A shader crate's own shapes, read from the CPU library twinray builds of the crate
//! (`twinray_compile::cpu`): their scene keys, the primitives a shape of each becomes, and the
//! f64 definition the reference judges their GPU intersection by. Only C values cross into the
//! library (`twinray_shared::custom::abi`); a run loads a library once and keeps it.

use super::module::Origin;
use glam::{DVec3, Vec3, Vec4};
use serde::Deserialize;
use std::path::{Path, PathBuf};
use twinray_shared::catalog::ModuleSpec;
use twinray_shared::custom::abi::{self, PARAMETER_FLOATS, PRIMITIVE_FLOATS};
use twinray_shared::custom::{Parameters, FIRST_HIT_KIND, LAST_HIT_KIND};
use twinray_shared::layout::Primitive;
use twinray_shared::shapes::spec::{Aabb, Param, ParamType, Rule, Value, Values};
use twinray_shared::shapes::SHAPES;

type Describe = unsafe extern "C" fn(*mut u8, usize) -> usize;
type Primitives = unsafe extern "C" fn(u32, *const f64, usize, *mut f32, usize, *mut u8, usize) -> i64;
type Distance = unsafe extern "C" fn(u32, *const f64, *const f64) -> f64;
type Normal = unsafe extern "C" fn(u32, *const f64, *const f64, *mut f64);

/// The C functions of a crate's CPU library.
#[derive(Clone, Copy)]
pub struct Functions {
    pub describe: Describe,
    pub primitives: Primitives,
    pub distance: Distance,
    pub normal: Normal,
}

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

/// A crate's shapes, and the library that computes their primitives and definitions.
pub struct CrateShapes {
    /// The library's file (or what stands for it).
    pub source: PathBuf,
    pub shapes: Vec<OwnShape>,
    functions: Functions,
    _library: Option<libloading::Library>,
}

impl std::fmt::Debug for CrateShapes {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let names: Vec<_> = self.shapes.iter().map(|s| s.name).collect();
        write!(f, "{} {names:?}", self.source.display())
    }
}

impl CrateShapes {
    /// Loads the CPU library at `path` and reads its shapes.
    pub fn load(path: &Path) -> Result<CrateShapes, String> {
        let fail = |e: String| format!("{}: {e}", path.display());
        // SAFETY: the library is the CPU side of a shader crate, built by twinray from the
        // crate's `shared/` library around twinray's own wrapper (`twinray_compile::cpu`), whose
        // initialisers are Rust's; it stays loaded while the functions read from it are used,
        // since `_library` is dropped with them.
        let library = unsafe { load_fresh(path) }.map_err(|e| fail(format!("cannot load: {e}")))?;
        // SAFETY: each symbol is one of the wrapper's functions, of the type written here, and
        // `twinray_abi` (checked first) names the version of those types.
        let functions = unsafe {
            let version = *library
                .get::<unsafe extern "C" fn() -> u32>(b"twinray_abi\0")
                .map_err(|_| fail("no twinray_abi: not a library twinray built".into()))?;
            if version() != abi::VERSION {
                return Err(fail(format!(
                    "built for version {} of twinray's CPU functions, not {}: build the crate again",
                    version(),
                    abi::VERSION
                )));
            }
            let get = |name: &[u8]| library.get::<*const ()>(name).map(|s| *s).map_err(|e| fail(e.to_string()));
            Functions {
                describe: std::mem::transmute::<*const (), Describe>(get(b"twinray_describe\0")?),
                primitives: std::mem::transmute::<*const (), Primitives>(get(b"twinray_primitives\0")?),
                distance: std::mem::transmute::<*const (), Distance>(get(b"twinray_distance\0")?),
                normal: std::mem::transmute::<*const (), Normal>(get(b"twinray_normal\0")?),
            }
        };
        let mut shapes = CrateShapes::from_functions(path.to_path_buf(), functions).map_err(fail)?;
        shapes._library = Some(library);
        Ok(shapes)
    }

    /// The shapes `functions` describe (a library's, or a test's own), checked: names and hit
    /// kinds unique and apart from the built-in shapes', each key's type and rule known.
    pub fn from_functions(source: PathBuf, functions: Functions) -> Result<CrateShapes, String> {
        // SAFETY: a null buffer of capacity 0 asks for the length alone.
        let length = unsafe { (functions.describe)(std::ptr::null_mut(), 0) };
        let mut text = vec![0u8; length];
        // SAFETY: `text` holds `length` bytes.
        unsafe { (functions.describe)(text.as_mut_ptr(), length) };
        let described: Described = serde_json::from_slice(&text).map_err(|e| format!("its description: {e}"))?;
        if let Some(error) = described.error {
            return Err(error);
        }
        if let Some(refusal) = twinray_shared::contract::refusal(&described.contract) {
            return Err(refusal);
        }
        let shapes = described.shapes.into_iter().map(own_shape).collect::<Result<Vec<_>, _>>()?;
        Ok(CrateShapes { source, shapes, functions, _library: None })
    }

    /// The shape called `name`.
    pub fn shape(&self, name: &str) -> Option<(usize, &OwnShape)> {
        self.shapes.iter().enumerate().find(|(_, s)| s.name == name)
    }

    /// The shape called `name`, as scenes and hit groups name it.
    pub fn find(&'static self, name: &str) -> Option<OwnShapeRef> {
        self.shape(name).map(|(index, _)| OwnShapeRef { crate_shapes: self, index })
    }

    /// The primitives of shape `index` with `values` (each key's, in its order), each with
    /// its box; or why the crate refuses them (a rule, its `check`, a panic).
    pub fn primitives(&self, index: usize, values: &Values) -> Result<Vec<(Primitive, Aabb)>, String> {
        let flat = abi::flatten(&values.0.iter().map(|(_, v)| *v).collect::<Vec<_>>());
        let mut capacity = 1usize;
        loop {
            let mut out = vec![0f32; capacity * PRIMITIVE_FLOATS];
            let mut message = vec![0u8; 1024];
            // SAFETY: every buffer is as long as the count passed with it.
            let n = unsafe {
                (self.functions.primitives)(
                    index as u32,
                    flat.as_ptr(),
                    flat.len(),
                    out.as_mut_ptr(),
                    capacity,
                    message.as_mut_ptr(),
                    message.len(),
                )
            };
            if n < 0 {
                message.truncate(n.unsigned_abs() as usize);
                return Err(String::from_utf8_lossy(&message).into_owned());
            }
            let n = n as usize;
            if n > twinray_shared::shapes::spec::MAX_PRIMITIVES as usize {
                return Err(format!("{} primitives, more than a shape may have", n));
            }
            if n <= capacity {
                return Ok(out.chunks(PRIMITIVE_FLOATS).take(n).map(primitive).collect());
            }
            capacity = n;
        }
    }

    /// The signed distance of shape `index` at `p`, as the crate defines it.
    pub fn distance(&self, index: usize, parameters: &Parameters, p: DVec3) -> f64 {
        let q = flat_parameters(parameters);
        // SAFETY: 8 parameters and 3 coordinates, as the function reads.
        unsafe { (self.functions.distance)(index as u32, q.as_ptr(), p.to_array().as_ptr()) }
    }

    /// The outward normal of shape `index` at `p`, as the crate defines it.
    pub fn normal(&self, index: usize, parameters: &Parameters, p: DVec3) -> DVec3 {
        let q = flat_parameters(parameters);
        let mut out = [f64::NAN; 3];
        // SAFETY: 8 parameters, 3 coordinates and 3 outputs, as the function takes.
        unsafe { (self.functions.normal)(index as u32, q.as_ptr(), p.to_array().as_ptr(), out.as_mut_ptr()) };
        DVec3::from_array(out)
    }
}

/// The modules of shapes of a user's own in a folder set, and, where the set was built from a
/// crate, what the crate says of its shapes: what such a set adds to twinray's catalog. A folder
/// of GLSL twins has the modules alone; its scenes' kinds come from the crate's set beside it.
#[derive(Debug)]
pub struct OwnShapes {
    pub shapes: Option<CrateShapes>,
    pub(super) modules: Vec<(ModuleSpec, Origin)>,
}

/// Two sets' own shapes are the same when they come from the same library and modules: a
/// crate named twice in one command is one set (`ShaderSet::distinct` then times a salted
/// copy of it, never the same pipeline twice), however many times it was loaded.
impl PartialEq for OwnShapes {
    fn eq(&self, other: &Self) -> bool {
        let modules = |o: &OwnShapes| o.modules.iter().map(|(m, o)| (m.name, o.clone())).collect::<Vec<_>>();
        let source = |o: &OwnShapes| o.shapes.as_ref().map(|c| c.source.clone());
        source(self) == source(other) && modules(self) == modules(other)
    }
}

impl OwnShapes {
    /// The modules of `names` (intersection modules no shape of twinray's has) and of every
    /// shape of `shapes`, each from `origin` (a folder's file, or missing).
    pub(super) fn new(
        shapes: Option<CrateShapes>,
        names: &[String],
        origin: impl Fn(&ModuleSpec) -> Result<Origin, String>,
    ) -> Result<OwnShapes, String> {
        let listed = shapes.iter().flat_map(|c| c.shapes.iter().map(|s| (s.name.to_string(), s.hit_kind)));
        let mut wanted: Vec<(String, u32)> = listed.collect();
        for name in names.iter().filter_map(|n| n.strip_suffix("_intersection")) {
            if !wanted.iter().any(|(w, _)| w == name) {
                wanted.push((name.to_string(), 0));
            }
        }
        let specs = wanted.iter().map(|(name, kind)| twinray_shared::catalog::own_intersection(name, *kind));
        let modules = specs.map(|spec| origin(&spec).map(|o| (spec, o))).collect::<Result<_, _>>()?;
        Ok(OwnShapes { shapes, modules })
    }
}

/// One shape of a crate's, as scenes, hit groups and the reference name it.
#[derive(Clone, Copy, Debug)]
pub struct OwnShapeRef {
    pub crate_shapes: &'static CrateShapes,
    pub index: usize,
}

impl OwnShapeRef {
    /// What the crate says of it.
    pub fn shape(self) -> &'static OwnShape {
        &self.crate_shapes.shapes[self.index]
    }

    /// Its primitives for `values`, or why the crate refuses them.
    pub fn primitives(self, values: &Values) -> Result<Vec<(Primitive, Aabb)>, String> {
        self.crate_shapes.primitives(self.index, values)
    }

    /// Its signed distance at `p` for a primitive's parameters, by the crate's definition.
    pub fn distance(self, parameters: &Parameters, p: DVec3) -> f64 {
        self.crate_shapes.distance(self.index, parameters, p)
    }

    /// Its outward normal at `p`, by the crate's definition.
    pub fn normal(self, parameters: &Parameters, p: DVec3) -> DVec3 {
        self.crate_shapes.normal(self.index, parameters, p)
    }

    fn key(self) -> (&'static str, usize, usize) {
        (self.shape().name, self.crate_shapes as *const CrateShapes as usize, self.index)
    }
}

impl PartialEq for OwnShapeRef {
    fn eq(&self, other: &Self) -> bool {
        self.key() == other.key()
    }
}

impl Eq for OwnShapeRef {}

impl PartialOrd for OwnShapeRef {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

/// By name first, so that hit groups of a crate's shapes sort the same in every run.
impl Ord for OwnShapeRef {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.key().cmp(&other.key())
    }
}

impl std::hash::Hash for OwnShapeRef {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        self.key().hash(state)
    }
}

/// Loads a copy of the library at `path` under a name of its own: the loader keeps a library
/// it loaded by its path, so a crate rebuilt in the same run (`watch`) would otherwise be read
/// as it was first. The copy is removed once loaded.
///
/// # Safety
/// As `libloading::Library::new`: the library's initialisers run.
unsafe fn load_fresh(path: &Path) -> Result<libloading::Library, String> {
    static LOADS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let n = LOADS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let copy = std::env::temp_dir().join(format!("twinray-cpu-{}-{n}.so", std::process::id()));
    std::fs::copy(path, &copy).map_err(|e| e.to_string())?;
    // SAFETY: passed on from the caller.
    let library = unsafe { libloading::Library::new(&copy) }.map_err(|e| e.to_string());
    let _ = std::fs::remove_file(&copy);
    library
}

fn flat_parameters(p: &Parameters) -> [f64; PARAMETER_FLOATS] {
    let (a, b) = (p.a.to_array(), p.b.to_array());
    [a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3]]
}

fn primitive(f: &[f32]) -> (Primitive, Aabb) {
    let v = |i: usize| Vec4::new(f[i], f[i + 1], f[i + 2], f[i + 3]);
    let primitive = Primitive { a: v(0), b: v(4), tint: v(8) };
    (primitive, Aabb { min: Vec3::new(f[12], f[13], f[14]), max: Vec3::new(f[15], f[16], f[17]) })
}

#[derive(Deserialize)]
struct Described {
    contract: String,
    error: Option<String>,
    shapes: Vec<DescribedShape>,
}

#[derive(Deserialize)]
struct DescribedShape {
    name: String,
    about: String,
    hit_kind: u32,
    params: Vec<DescribedParam>,
}

#[derive(Deserialize)]
struct DescribedParam {
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
fn own_shape(s: DescribedShape) -> Result<OwnShape, String> {
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
    let params = s.params.into_iter().map(|p| own_param(&s.name, p)).collect::<Result<Vec<_>, _>>()?;
    Ok(OwnShape {
        module: leak(format!("{}_intersection", s.name)),
        name: leak(s.name),
        about: s.about,
        hit_kind: s.hit_kind,
        params: Box::leak(params.into_boxed_slice()),
    })
}

fn own_param(shape: &str, p: DescribedParam) -> Result<Param, String> {
    let unknown = |what: &str, word: &str| format!("shape {shape:?}: key {:?}: unknown {what} {word:?}", p.name);
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
                "shape {shape:?}: key {:?}: a default of {} values for a {}",
                p.name,
                other.len(),
                p.ty
            ))
        }
    };
    Ok(Param { name: leak(p.name), ty, rule, default })
}

#[cfg(test)]
mod tests;
