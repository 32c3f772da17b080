//! A shader crate's own shapes and materials, read from the CPU library twinray builds of the
//! crate (`twinray_compile::cpu`): their scene keys, the primitives a shape of each becomes, the
//! f64 definition the reference judges their GPU intersection by, and the parameters a
//! material's callable reads. Only C values cross into the
//! library (`twinray_shared::custom::abi`); a run loads a library once and keeps it.

use super::module::Origin;
use described::{own_material, own_shape, Described};
pub use described::{OwnMaterial, OwnShape};
use glam::{DVec3, Vec3, Vec4};
use std::path::{Path, PathBuf};
use twinray_shared::catalog::ModuleSpec;
use twinray_shared::custom::abi::{self, MATERIAL_FLOATS, PARAMETER_FLOATS, PRIMITIVE_FLOATS};
use twinray_shared::custom::Parameters;
use twinray_shared::layout::Primitive;
use twinray_shared::shapes::spec::{Aabb, Values};

type Describe = unsafe extern "C" fn(*mut u8, usize) -> usize;
type Primitives = unsafe extern "C" fn(u32, *const f64, usize, *mut f32, usize, *mut u8, usize) -> i64;
type Distance = unsafe extern "C" fn(u32, *const f64, *const f64) -> f64;
type Normal = unsafe extern "C" fn(u32, *const f64, *const f64, *mut f64);
type MaterialFn = unsafe extern "C" fn(u32, *const f64, usize, *mut f32, *mut u8, usize) -> i64;

/// The C functions of a crate's CPU library.
#[derive(Clone, Copy)]
pub struct Functions {
    pub describe: Describe,
    pub primitives: Primitives,
    pub distance: Distance,
    pub normal: Normal,
    pub material: MaterialFn,
}

/// A crate's shapes and materials, and the library that computes their primitives,
/// definitions and parameters.
pub struct CrateKinds {
    /// The library's file (or what stands for it).
    pub source: PathBuf,
    pub shapes: Vec<OwnShape>,
    pub materials: Vec<OwnMaterial>,
    /// The recursion depth its set's pipelines need (1 unless its hit stages trace).
    pub recursion_depth: u32,
    functions: Functions,
    _library: Option<libloading::Library>,
}

impl std::fmt::Debug for CrateKinds {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let names: Vec<_> = self.shapes.iter().map(|s| s.name).chain(self.materials.iter().map(|m| m.name)).collect();
        write!(f, "{} {names:?}", self.source.display())
    }
}

impl CrateKinds {
    /// Loads the CPU library at `path` and reads its shapes.
    pub fn load(path: &Path) -> Result<CrateKinds, String> {
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
                material: std::mem::transmute::<*const (), MaterialFn>(get(b"twinray_material\0")?),
            }
        };
        let mut shapes = CrateKinds::from_functions(path.to_path_buf(), functions).map_err(fail)?;
        shapes._library = Some(library);
        Ok(shapes)
    }

    /// The shapes `functions` describe (a library's, or a test's own), checked: names and hit
    /// kinds unique and apart from the built-in shapes', each key's type and rule known.
    pub fn from_functions(source: PathBuf, functions: Functions) -> Result<CrateKinds, String> {
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
        let materials = described.materials.into_iter().map(own_material).collect::<Result<Vec<_>, _>>()?;
        let recursion_depth = described.recursion_depth;
        Ok(CrateKinds { source, shapes, materials, recursion_depth, functions, _library: None })
    }

    /// The shape called `name`.
    pub fn shape(&self, name: &str) -> Option<(usize, &OwnShape)> {
        self.shapes.iter().enumerate().find(|(_, s)| s.name == name)
    }

    /// The shape called `name`, as scenes and hit groups name it.
    pub fn find(&'static self, name: &str) -> Option<OwnShapeRef> {
        self.shape(name).map(|(index, _)| OwnShapeRef { crate_kinds: self, index })
    }

    /// The material called `name`, as scenes name it.
    pub fn find_material(&'static self, name: &str) -> Option<OwnMaterialRef> {
        let index = self.materials.iter().position(|m| m.name == name)?;
        Some(OwnMaterialRef { crate_kinds: self, index })
    }

    /// What the callable of material `index` reads for `values` (each key's, in its order):
    /// `Material::color_a` and `color_b`; or why the crate refuses them.
    pub fn material(&self, index: usize, values: &Values) -> Result<[Vec4; 2], String> {
        let flat = abi::flatten(&values.0.iter().map(|(_, v)| *v).collect::<Vec<_>>());
        let mut out = [f32::NAN; MATERIAL_FLOATS];
        let mut message = vec![0u8; 1024];
        // SAFETY: every buffer is as long as the count passed with it.
        let n = unsafe {
            (self.functions.material)(
                index as u32,
                flat.as_ptr(),
                flat.len(),
                out.as_mut_ptr(),
                message.as_mut_ptr(),
                message.len(),
            )
        };
        if n < 0 {
            message.truncate(n.unsigned_abs() as usize);
            return Err(String::from_utf8_lossy(&message).into_owned());
        }
        Ok([Vec4::from_slice(&out[..4]), Vec4::from_slice(&out[4..])])
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

/// The modules of shapes and materials of a user's own in a folder set, and, where the set was
/// built from a crate, what the crate says of them: what such a set adds to twinray's catalog. A folder
/// of GLSL twins has the modules alone; its scenes' kinds come from the crate's set beside it.
#[derive(Debug)]
pub struct OwnKinds {
    pub kinds: Option<CrateKinds>,
    pub(super) modules: Vec<(ModuleSpec, Origin)>,
}

/// Two sets' own shapes are the same when they come from the same library and modules: a
/// crate named twice in one command is one set (`ShaderSet::distinct` then times a salted
/// copy of it, never the same pipeline twice), however many times it was loaded.
impl PartialEq for OwnKinds {
    fn eq(&self, other: &Self) -> bool {
        let modules = |o: &OwnKinds| o.modules.iter().map(|(m, o)| (m.name, o.clone())).collect::<Vec<_>>();
        let source = |o: &OwnKinds| o.kinds.as_ref().map(|c| c.source.clone());
        source(self) == source(other) && modules(self) == modules(other)
    }
}

impl OwnKinds {
    /// The modules of `names` (intersection modules no shape of twinray's has) and of every
    /// shape of `shapes`, each from `origin` (a folder's file, or missing).
    pub(super) fn new(
        kinds: Option<CrateKinds>,
        names: &[String],
        origin: impl Fn(&ModuleSpec) -> Result<Origin, String>,
    ) -> Result<OwnKinds, String> {
        let listed = kinds.iter().flat_map(|c| c.shapes.iter().map(|s| (s.name.to_string(), s.hit_kind)));
        let mut shapes: Vec<(String, u32)> = listed.collect();
        let mut materials: Vec<String> = kinds.iter().flat_map(|c| c.materials.iter().map(|m| m.name.into())).collect();
        for name in names {
            if let Some(shape) = name.strip_suffix("_intersection") {
                if !shapes.iter().any(|(w, _)| w == shape) {
                    shapes.push((shape.to_string(), 0));
                }
            } else if let Some(material) = name.strip_suffix("_material") {
                if !materials.iter().any(|m| m == material) {
                    materials.push(material.to_string());
                }
            }
        }
        let specs = shapes.iter().map(|(name, kind)| twinray_shared::catalog::own_intersection(name, *kind));
        let specs = specs.chain(materials.iter().map(|m| twinray_shared::catalog::own_material(m)));
        let modules = specs.map(|spec| origin(&spec).map(|o| (spec, o))).collect::<Result<_, _>>()?;
        Ok(OwnKinds { kinds, modules })
    }
}

/// One material of a crate's, as scenes and pipeline plans name it.
#[derive(Clone, Copy, Debug)]
pub struct OwnMaterialRef {
    pub crate_kinds: &'static CrateKinds,
    pub index: usize,
}

impl OwnMaterialRef {
    /// What the crate says of it.
    pub fn material(self) -> &'static OwnMaterial {
        &self.crate_kinds.materials[self.index]
    }

    /// What its callable reads for `values`, or why the crate refuses them.
    pub fn parameters(self, values: &Values) -> Result<[Vec4; 2], String> {
        self.crate_kinds.material(self.index, values)
    }
}

/// One shape of a crate's, as scenes, hit groups and the reference name it.
#[derive(Clone, Copy, Debug)]
pub struct OwnShapeRef {
    pub crate_kinds: &'static CrateKinds,
    pub index: usize,
}

impl OwnShapeRef {
    /// What the crate says of it.
    pub fn shape(self) -> &'static OwnShape {
        &self.crate_kinds.shapes[self.index]
    }

    /// Its primitives for `values`, or why the crate refuses them.
    pub fn primitives(self, values: &Values) -> Result<Vec<(Primitive, Aabb)>, String> {
        self.crate_kinds.primitives(self.index, values)
    }

    /// Its signed distance at `p` for a primitive's parameters, by the crate's definition.
    pub fn distance(self, parameters: &Parameters, p: DVec3) -> f64 {
        self.crate_kinds.distance(self.index, parameters, p)
    }

    /// Its outward normal at `p`, by the crate's definition.
    pub fn normal(self, parameters: &Parameters, p: DVec3) -> DVec3 {
        self.crate_kinds.normal(self.index, parameters, p)
    }

    fn key(self) -> (&'static str, usize, usize) {
        (self.shape().name, self.crate_kinds as *const CrateKinds as usize, self.index)
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

mod described;
#[cfg(test)]
pub(crate) mod tests;
