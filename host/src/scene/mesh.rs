//! Triangle meshes: the generated box, pyramid, prism and icosahedron (each fitting the unit
//! cube about the origin), and OBJ files read with tobj. Normals are the host's: flat meshes
//! repeat each vertex per face with the face normal, smooth meshes average the normals of the
//! faces around a vertex weighted by the face's angle there (Thurmer and Wuthrich 1998), which
//! does not depend on how the faces were split into triangles.

use super::shape::{MeshBuiltin, Normals};
use crate::util::input::read_bounded;
use glam::{Vec3, Vec4};
use std::path::Path;
use twinray_shared::layout::Vertex;
use twinray_shared::shapes::spec::MAX_LENGTH;

/// A mesh ready to upload: vertices and three indices per triangle.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshData {
    pub vertices: Vec<Vertex>,
    pub indices: Vec<u32>,
}

/// Positions and triangles before normals are chosen.
pub(super) struct Polyhedron {
    pub positions: Vec<Vec3>,
    pub triangles: Vec<[u32; 3]>,
}

/// A generated mesh, with flat or smooth normals.
pub fn builtin(kind: MeshBuiltin, normals: Normals) -> MeshData {
    let p = match kind {
        MeshBuiltin::Box => box_mesh(),
        MeshBuiltin::Pyramid => pyramid(),
        MeshBuiltin::Prism => prism(),
        MeshBuiltin::Icosahedron => icosahedron(),
    };
    with_normals(&outward(p), normals)
}

pub(super) const OBJ_OPTIONS: tobj::LoadOptions =
    tobj::LoadOptions { triangulate: true, single_index: true, ignore_points: true, ignore_lines: true };

/// Largest mesh file read, in bytes, unless `TWINRAY_MAX_MESH_BYTES` says otherwise.
pub const DEFAULT_MAX_MESH_BYTES: u64 = 64 << 20;

/// Most triangles of one mesh (a glTF primitive, an OBJ file): 2^24. A procedural shape's
/// primitives are bounded by `MAX_PRIMITIVES`, a device's by its `maxPrimitiveCount`
/// (checked when a scene is uploaded); the bytes a mesh may take, by `max_mesh_bytes`.
pub const MAX_MESH_TRIANGLES: usize = 1 << 24;

/// The mesh file size limit: `TWINRAY_MAX_MESH_BYTES` if set (a byte count), else the default.
pub fn max_mesh_bytes() -> Result<u64, String> {
    match std::env::var("TWINRAY_MAX_MESH_BYTES") {
        Ok(v) => v.trim().parse().map_err(|_| format!("TWINRAY_MAX_MESH_BYTES must be a byte count (got {v:?})")),
        Err(_) => Ok(DEFAULT_MAX_MESH_BYTES),
    }
}

/// Reads an OBJ file (all its models, triangulated); the error says why it could not. Only a
/// regular file no larger than `max_mesh_bytes` is read, and never past that bound: a device
/// or a FIFO (which would never end, or never start) is refused before it is opened.
pub fn load_obj(path: &Path, normals: Normals) -> Result<MeshData, String> {
    let cannot = |why: String| format!("cannot read mesh file {}: {why}", path.display());
    let limit = max_mesh_bytes().map_err(cannot)?;
    let bytes = read_bounded(path, limit).map_err(|e| {
        let raise = if e.contains("limit") { " (TWINRAY_MAX_MESH_BYTES raises it)" } else { "" };
        cannot(format!("{e}{raise}"))
    })?;
    parse_obj(&bytes, &path.display().to_string(), normals)
}

/// Reads OBJ text (a mesh file shipped in the binary, or one read by `load_obj`); `name` names
/// it in errors. Material libraries are not read: twinray's materials come from the scene.
pub fn parse_obj(text: &[u8], name: &str, normals: Normals) -> Result<MeshData, String> {
    let text = obj_text(text, false);
    let mut reader = std::io::BufReader::new(text.as_bytes());
    let (models, _) = tobj::load_obj_buf(&mut reader, &OBJ_OPTIONS, |_| Err(tobj::LoadError::OpenFileFailed))
        .map_err(|e| format!("cannot read mesh file {name}: {e}"))?;
    from_models(&models, name, normals)
}

/// The lines of an OBJ file, as UTF-8: UTF-16 with a byte order mark is decoded, bytes that
/// are not UTF-8 become U+FFFD. `usemtl` statements without a name are dropped (they would
/// fail the parse), and unless `materials`, `mtllib` and every `usemtl` (whose names, in
/// another encoding in files written elsewhere, would fail the parse of geometry read without
/// them).
pub(super) fn obj_text(bytes: &[u8], materials: bool) -> String {
    let utf16 = |be: bool| {
        let units = bytes[2..].chunks_exact(2).map(|c| {
            if be {
                u16::from_be_bytes([c[0], c[1]])
            } else {
                u16::from_le_bytes([c[0], c[1]])
            }
        });
        char::decode_utf16(units).map(|c| c.unwrap_or(char::REPLACEMENT_CHARACTER)).collect::<String>()
    };
    let text = match bytes {
        [0xfe, 0xff, ..] => utf16(true),
        [0xff, 0xfe, ..] => utf16(false),
        _ => String::from_utf8_lossy(bytes).into_owned(),
    };
    let mut out = String::with_capacity(text.len());
    for line in text.lines() {
        match material_statement(line) {
            Some((keyword, name)) if materials && !name.is_empty() => out += &format!("{keyword} {name}\n"),
            Some(_) => {}
            None => out.extend([line, "\n"]),
        }
    }
    out
}

/// A `usemtl` or `mtllib` statement's keyword and name (which tobj reads after a single
/// space).
fn material_statement(line: &str) -> Option<(&str, &str)> {
    let keyword = line.split_whitespace().next().filter(|&w| w == "usemtl" || w == "mtllib")?;
    Some((keyword, line.trim()[keyword.len()..].trim()))
}

/// The triangles of an OBJ file's models, with their texture coordinates (`vt`, v turned to
/// run down the image as glTF's and Vulkan's do; 0 where a model has none).
pub(super) fn from_models(models: &[tobj::Model], name: &str, normals: Normals) -> Result<MeshData, String> {
    let path = name;
    let mut p = Polyhedron { positions: Vec::new(), triangles: Vec::new() };
    let mut attributes = Vec::new();
    for model in models {
        let base = p.positions.len() as u32;
        let m = &model.mesh;
        p.positions.extend(m.positions.chunks_exact(3).map(|c| Vec3::new(c[0], c[1], c[2])));
        p.triangles.extend(m.indices.chunks_exact(3).map(|t| [base + t[0], base + t[1], base + t[2]]));
        let count = m.positions.len() / 3;
        let uv = |i: usize| match m.texcoords.get(2 * i..2 * i + 2) {
            Some(&[u, v]) if m.texcoords.len() == 2 * count && u.is_finite() && v.is_finite() => {
                Vec4::new(u, 1.0 - v, 0.0, 0.0)
            }
            _ => Vec4::ZERO,
        };
        attributes.extend((0..count).map(|i| (uv(i), Vec4::ONE)));
    }
    checked(&p, &format!("mesh file {path}"))?;
    Ok(with_attributes(with_normals(&p, normals), &p, &attributes, normals == Normals::Flat))
}

/// Whether `p` is a mesh the GPU can take: some triangles, not too many, every vertex finite
/// and within `MAX_LENGTH`, every index naming a vertex. `what` starts the error.
pub(super) fn checked(p: &Polyhedron, what: &str) -> Result<(), String> {
    if p.triangles.is_empty() {
        return Err(format!("{what} has no triangles"));
    }
    if p.triangles.len() > MAX_MESH_TRIANGLES {
        return Err(format!("{what} has {} triangles (at most {MAX_MESH_TRIANGLES})", p.triangles.len()));
    }
    let far = p.positions.iter().find(|v| !v.is_finite() || v.abs().max_element() > MAX_LENGTH);
    if let Some(v) = far {
        return Err(format!("{what} has a vertex at {v}: coordinates must be finite, at most {MAX_LENGTH:e}"));
    }
    if let Some(i) = p.triangles.iter().flatten().find(|&&i| i as usize >= p.positions.len()) {
        return Err(format!("{what} indexes vertex {i}, past its {} vertices", p.positions.len()));
    }
    Ok(())
}

fn face_normal(p: &Polyhedron, t: [u32; 3]) -> Vec3 {
    let [a, b, c] = t.map(|i| p.positions[i as usize]);
    (b - a).cross(c - a)
}

/// `mesh` (made of `p`, by [`with_normals`] with flat normals if `flat`, else one vertex per
/// vertex of `p`) with each vertex's texture coordinates and colour from `attributes`, one per
/// vertex of `p`.
pub(super) fn with_attributes(mut mesh: MeshData, p: &Polyhedron, attributes: &[(Vec4, Vec4)], flat: bool) -> MeshData {
    // Flat normals repeat each triangle's corners, in order.
    for (k, v) in mesh.vertices.iter_mut().enumerate() {
        let source = if flat { p.triangles[k / 3][k % 3] as usize } else { k };
        (v.uv, v.color) = attributes[source];
    }
    mesh
}

pub(super) fn with_normals(p: &Polyhedron, normals: Normals) -> MeshData {
    let vertex = |position: Vec3, normal: Vec3| Vertex {
        normal: normal.normalize_or_zero().extend(0.0),
        ..Vertex::at(position)
    };
    match normals {
        Normals::Flat => {
            let mut mesh = MeshData::default();
            for &t in &p.triangles {
                let n = face_normal(p, t);
                let base = mesh.vertices.len() as u32;
                mesh.vertices.extend(t.map(|i| vertex(p.positions[i as usize], n)));
                mesh.indices.extend([base, base + 1, base + 2]);
            }
            mesh
        }
        Normals::Smooth => {
            let mut sums = vec![Vec3::ZERO; p.positions.len()];
            for &t in &p.triangles {
                let n = face_normal(p, t).normalize_or_zero();
                for k in 0..3 {
                    let [a, b, c] = [t[k], t[(k + 1) % 3], t[(k + 2) % 3]].map(|i| p.positions[i as usize]);
                    let angle = (b - a).normalize_or_zero().dot((c - a).normalize_or_zero()).clamp(-1.0, 1.0).acos();
                    sums[t[k] as usize] += n * angle;
                }
            }
            MeshData {
                vertices: p.positions.iter().zip(&sums).map(|(&pos, &n)| vertex(pos, n)).collect(),
                indices: p.triangles.iter().flatten().copied().collect(),
            }
        }
    }
}

/// Orders every triangle of a mesh that is convex about the origin counter-clockwise seen
/// from outside, so averaged normals point out.
fn outward(mut p: Polyhedron) -> Polyhedron {
    for i in 0..p.triangles.len() {
        let t = p.triangles[i];
        let centroid = t.iter().map(|&v| p.positions[v as usize]).sum::<Vec3>() / 3.0;
        if face_normal(&p, t).dot(centroid) < 0.0 {
            p.triangles[i] = [t[0], t[2], t[1]];
        }
    }
    p
}

/// Quads (as corner indices) split into two triangles each.
fn quads(quads: &[[u32; 4]]) -> Vec<[u32; 3]> {
    quads.iter().flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]).collect()
}

fn box_mesh() -> Polyhedron {
    let positions = (0..8)
        .map(|i| Vec3::new((i & 1) as f32 - 0.5, ((i >> 1) & 1) as f32 - 0.5, ((i >> 2) & 1) as f32 - 0.5))
        .collect();
    let faces = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]];
    Polyhedron { positions, triangles: quads(&faces) }
}

fn pyramid() -> Polyhedron {
    let positions = vec![
        Vec3::new(-0.5, -0.5, -0.5),
        Vec3::new(0.5, -0.5, -0.5),
        Vec3::new(0.5, -0.5, 0.5),
        Vec3::new(-0.5, -0.5, 0.5),
        Vec3::new(0.0, 0.5, 0.0),
    ];
    let mut triangles = quads(&[[0, 1, 2, 3]]);
    triangles.extend([[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]);
    Polyhedron { positions, triangles }
}

/// A triangular prism along z: the cross-section has corners (-0.5, -0.5), (0.5, -0.5), (0, 0.5).
fn prism() -> Polyhedron {
    let section = [Vec3::new(-0.5, -0.5, 0.0), Vec3::new(0.5, -0.5, 0.0), Vec3::new(0.0, 0.5, 0.0)];
    let positions = [-0.5f32, 0.5].iter().flat_map(|&z| section.map(|p| p + Vec3::new(0.0, 0.0, z))).collect();
    let mut triangles = vec![[0, 1, 2], [3, 4, 5]];
    triangles.extend(quads(&[[0, 1, 4, 3], [1, 2, 5, 4], [2, 0, 3, 5]]));
    Polyhedron { positions, triangles }
}

/// The regular icosahedron with circumradius 0.5.
fn icosahedron() -> Polyhedron {
    let phi = (1.0 + 5.0f32.sqrt()) / 2.0;
    let mut positions = Vec::new();
    for (a, b) in [(-1.0, phi), (1.0, phi), (-1.0, -phi), (1.0, -phi)] {
        positions.push(Vec3::new(a, b, 0.0));
    }
    for (a, b) in [(-1.0, phi), (1.0, phi), (-1.0, -phi), (1.0, -phi)] {
        positions.push(Vec3::new(0.0, a, b));
    }
    for (a, b) in [(-1.0, phi), (1.0, phi), (-1.0, -phi), (1.0, -phi)] {
        positions.push(Vec3::new(b, 0.0, a));
    }
    let positions: Vec<Vec3> = positions.into_iter().map(|p| p.normalize() * 0.5).collect();
    // The 20 faces are the triples of mutually nearest vertices (edge length 1/sin(2 pi / 5) * ...).
    let edge = positions[0].distance(positions[1]).min(positions[0].distance(positions[4]));
    let near = |a: usize, b: usize| (positions[a].distance(positions[b]) - edge).abs() < 1e-4;
    let mut triangles = Vec::new();
    for a in 0..12 {
        for b in a + 1..12 {
            for c in b + 1..12 {
                if near(a, b) && near(b, c) && near(a, c) {
                    triangles.push([a as u32, b as u32, c as u32]);
                }
            }
        }
    }
    Polyhedron { positions, triangles }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn closed_and_outward(p: &Polyhedron, faces: usize) {
        assert_eq!(p.triangles.len(), faces);
        for &t in &p.triangles {
            let centroid = t.iter().map(|&v| p.positions[v as usize]).sum::<Vec3>() / 3.0;
            assert!(face_normal(p, t).dot(centroid) > 0.0, "inward face {t:?}");
        }
        // Closed: every edge is shared by exactly two triangles, in opposite directions.
        let mut edges = std::collections::HashMap::new();
        for t in &p.triangles {
            for k in 0..3 {
                *edges.entry((t[k], t[(k + 1) % 3])).or_insert(0) += 1;
            }
        }
        for (&(a, b), &n) in &edges {
            assert_eq!((n, edges.get(&(b, a))), (1, Some(&1)), "edge {a}-{b}");
        }
    }

    #[test]
    fn generated_meshes_are_closed_and_face_outwards() {
        closed_and_outward(&outward(box_mesh()), 12);
        closed_and_outward(&outward(pyramid()), 6);
        closed_and_outward(&outward(prism()), 8);
        closed_and_outward(&outward(icosahedron()), 20);
    }

    #[test]
    fn flat_and_smooth_normals() {
        let flat = builtin(MeshBuiltin::Box, Normals::Flat);
        assert_eq!((flat.vertices.len(), flat.indices.len()), (36, 36));
        let smooth = builtin(MeshBuiltin::Box, Normals::Smooth);
        assert_eq!((smooth.vertices.len(), smooth.indices.len()), (8, 36));
        for v in &smooth.vertices {
            let corner = v.position.truncate().normalize();
            assert!(v.normal.truncate().dot(corner) > 0.99, "corner normal {:?}", v.normal);
        }
    }

    #[test]
    fn obj_files_load_and_bad_ones_are_named() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("tri.obj");
        std::fs::write(&path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3 4\n").unwrap();
        let mesh = load_obj(&path, Normals::Flat).unwrap();
        assert_eq!(mesh.indices.len(), 6, "the quad is triangulated");
        let missing = load_obj(&dir.path().join("nope.obj"), Normals::Flat).unwrap_err();
        assert!(missing.contains("nope.obj"), "{missing}");
        std::fs::write(&path, "v 0 0 0\n").unwrap();
        assert!(load_obj(&path, Normals::Flat).unwrap_err().contains("no triangles"));
    }

    #[test]
    fn obj_text_in_other_encodings_and_with_odd_material_names_loads() {
        let plain = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        let want = parse_obj(plain.as_bytes(), "a.obj", Normals::Flat).unwrap();
        let odd = "mtllib x.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl \nusemtl Terraind\u{e4}k\nf 1 2 3\n";
        let mut latin1 = odd.replace('\u{e4}', "?").into_bytes();
        let at = latin1.iter().position(|&b| b == b'?').unwrap();
        latin1[at] = 0xe4; // not UTF-8
        let mut utf16: Vec<u8> = vec![0xfe, 0xff];
        utf16.extend(plain.encode_utf16().flat_map(u16::to_be_bytes));
        for (label, bytes) in [("materials", odd.as_bytes().to_vec()), ("latin-1", latin1), ("utf-16", utf16)] {
            assert_eq!(parse_obj(&bytes, "a.obj", Normals::Flat).as_ref(), Ok(&want), "{label}");
        }
    }
}
