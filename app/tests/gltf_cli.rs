//! Malformed glTF and OBJ files no one here wrote (Debian's assimp-testmodels, installed by
//! `cargo xtask setup`), given to every command that loads a scene: each ends with exit code 2
//! and one line naming the file, writes nothing and never panics. Which files are malformed is
//! what the loader says (tests/assimp.rs pins the known ones); a file that loads is skipped.

use std::path::{Path, PathBuf};
use twinray_tests::cli::{assert_bad_input, twinray, UNTIMED};

use twinray_host::scene::gltf::ASSIMP_TEST_MODELS as MODELS;

#[test]
fn every_command_refuses_a_malformed_model_in_one_line() {
    let malformed: Vec<PathBuf> = twinray_host::scene::gltf::models_under(Path::new(MODELS))
        .into_iter()
        .filter(|p| twinray_host::Scene::load(p.to_str()).is_err())
        .collect();
    assert!(malformed.len() >= 10, "{} malformed models in {MODELS}: run `cargo xtask setup`", malformed.len());
    every_command_refuses(&malformed);
}

/// OBJ files opened as scenes: those that do not parse or have no faces.
#[test]
fn every_command_refuses_a_malformed_obj_file_in_one_line() {
    let folder = Path::new("/usr/share/assimp/models/OBJ");
    let mut malformed: Vec<PathBuf> =
        std::fs::read_dir(folder).into_iter().flatten().flatten().map(|e| e.path()).collect();
    malformed.retain(|p| p.extension().is_some_and(|e| e == "obj") && twinray_host::Scene::load(p.to_str()).is_err());
    assert!(
        malformed.len() >= 3,
        "{} malformed OBJ files in {}: run `cargo xtask setup`",
        malformed.len(),
        folder.display()
    );
    every_command_refuses(&malformed);
}

fn every_command_refuses(malformed: &[PathBuf]) {
    for path in malformed {
        let file = path.to_str().unwrap();
        for command in [
            &["render", file, "--out", "x.png"][..],
            &["compare", file, "--out-dir", "out"],
            &["bisect", file],
            &["explain", file, "--pixel", "1,1"],
            &["reference", file, "--out", "ref.png"],
            &["bench", file, "--out", "bench"],
        ] {
            assert_bad_input(command, &[file]);
        }
    }
}

/// A quad: four float positions and six byte indices, padded to 56 bytes.
fn quad_bytes() -> Vec<u8> {
    let positions = [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0];
    let mut bytes: Vec<u8> = positions.iter().flat_map(|v| v.to_le_bytes()).collect();
    bytes.extend([0, 1, 2, 0, 2, 3, 0, 0]);
    bytes
}

/// A glTF model of the quad whose buffer is the file at `uri`.
fn quad_gltf(uri: &str) -> String {
    format!(
        r#"{{"asset": {{"version": "2.0"}}, "buffers": [{{"byteLength": 56, "uri": "{uri}"}}],
        "bufferViews": [{{"buffer": 0, "byteLength": 48}}, {{"buffer": 0, "byteOffset": 48, "byteLength": 8}}],
        "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
                      {{"bufferView": 1, "componentType": 5121, "count": 6, "type": "SCALAR"}}],
        "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1}}]}}],
        "nodes": [{{"mesh": 0}}], "scenes": [{{"nodes": [0]}}], "scene": 0}}"#
    )
}

/// Every file `twinray args` (run in `dir`) opens, as strace sees the `open` calls of it and its
/// threads, with symbolic links resolved where the file exists.
fn opened_files(args: &[&str], dir: &Path) -> Vec<PathBuf> {
    let log = dir.join("strace.log");
    let traced = std::process::Command::new("strace")
        .args(["-f", "-qq", "-e", "trace=open,openat,openat2,creat", "-o"])
        .arg(&log)
        .arg(env!("CARGO_BIN_EXE_twinray"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("strace (cargo xtask setup installs it)");
    assert_eq!(traced.status.code(), Some(2), "{}", String::from_utf8_lossy(&traced.stderr));
    let text = std::fs::read_to_string(&log).unwrap();
    std::fs::remove_file(&log).unwrap();
    text.lines()
        .filter_map(|line| line.split_once('"').and_then(|(_, rest)| rest.split_once('"')).map(|(path, _)| path))
        .map(|path| dir.join(path))
        .map(|path| std::fs::canonicalize(&path).unwrap_or(path))
        .collect()
}

/// A model cannot lead twinray outside its folder: a glTF buffer, an OBJ's material library
/// or texture, or a scene's mesh file or texture named by an absolute path, by `..` (also
/// %-escaped) out of the folder, or through a symbolic link to a file or folder elsewhere ends
/// with exit code 2 and one line naming it, and nothing of the file is read. The same file
/// inside the folder renders, and so does the one outside when `--asset-root` holds both.
/// strace checks that no file outside is opened, not only that the error says so.
#[test]
fn a_model_cannot_lead_twinray_outside_its_folder() {
    let dir = tempfile::tempdir().unwrap();
    let (model, outside) = (dir.path().join("model"), dir.path().join("outside"));
    for folder in [&model, &outside] {
        std::fs::create_dir_all(folder).unwrap();
        std::fs::write(folder.join("quad.bin"), quad_bytes()).unwrap();
        std::fs::write(folder.join("quad.mtl"), "newmtl a\nKd 1 1 1\n").unwrap();
        std::fs::write(folder.join("quad.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    }
    for ext in ["bin", "mtl", "obj"] {
        std::os::unix::fs::symlink(outside.join(format!("quad.{ext}")), model.join(format!("link.{ext}"))).unwrap();
    }
    std::os::unix::fs::symlink(&outside, model.join("away")).unwrap();
    let absolute = outside.join("quad.bin").display().to_string();
    let write = |name: &str, text: String| {
        let path = model.join(name);
        std::fs::write(&path, text).unwrap();
        path.display().to_string()
    };
    let obj = |mtl: &str, texture: &str| {
        let material = write(&format!("{mtl}-{}.mtl", texture.len()), format!("newmtl a\nmap_Kd {texture}\n"));
        let mtl = if mtl.is_empty() { material.rsplit('/').next().unwrap().to_string() } else { mtl.to_string() };
        format!("mtllib {mtl}\nusemtl a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n")
    };
    let scene = |key: &str, file: &str| {
        let (shape, texture) = match key {
            "mesh" => (format!("kind = \"mesh\"\nfile = \"{file}\""), String::new()),
            _ => ("kind = \"mesh\"\nbuiltin = \"box\"".to_string(), format!("texture = {{ file = \"{file}\" }}\n")),
        };
        format!(
            "[image]\nwidth = 8\nheight = 8\n[camera]\neye = [0.0, 0.0, 5.0]\ntarget = [0.0, 0.0, 0.0]\nup = [0.0, 1.0, 0.0]\nfov_y_degrees = 45.0\n\
             [materials.m]\nkind = \"diffuse\"\ncolor = [1.0, 1.0, 1.0]\n{texture}[shapes.s]\n{shape}\n\
             [[objects]]\nshape = \"s\"\nmaterial = \"m\"\n"
        )
    };
    let ways_out = [
        (absolute.as_str(), "absolute path"),
        ("../outside/quad.bin", "leads outside"),
        ("%2E%2E/outside/quad.bin", "leads outside"),
        ("link.bin", "leads outside"),
        ("away/quad.bin", "leads outside"),
        ("/dev/zero", "absolute path"),
        (".", "not a regular file"),
    ];
    for (i, (uri, why)) in ways_out.iter().enumerate() {
        let gltf = write(&format!("buffer-{i}.gltf"), quad_gltf(uri));
        assert_bad_input(&["render", &gltf, "--out", "x.png"], &[uri, why]);
        let opened = opened_files(&["render", &gltf, "--out", "x.png"], &model);
        let outside_opened: Vec<_> =
            opened.iter().filter(|p| p.starts_with(&outside) || p.starts_with("/dev/zero")).collect();
        assert!(outside_opened.is_empty(), "{uri}: twinray opened {outside_opened:?}");
        let name = uri.replace("%2E", ".").replace(".bin", ".mtl");
        let library = write(&format!("library-{i}.obj"), obj(&name, "none.png"));
        assert_bad_input(&["render", &library, "--out", "x.png"], &[&name, why]);
        let name = uri.replace("%2E", ".");
        let texture = write(&format!("texture-{i}.obj"), obj("", &name));
        assert_bad_input(&["render", &texture, "--out", "x.png"], &[&name, why]);
        let mesh = write(&format!("mesh-{i}.toml"), scene("mesh", &name.replace(".bin", ".obj")));
        assert_bad_input(&["render", &mesh, "--out", "x.png"], &[&name.replace(".bin", ".obj"), why]);
        let texture = write(&format!("texture-{i}.toml"), scene("texture", &name));
        assert_bad_input(&["render", &texture, "--out", "x.png"], &[&name, why]);
    }
    let renders = |args: &[&str]| {
        let out = twinray(&[args, &["--width", "8", "--height", "8", "--out", "x.png"]].concat(), dir.path());
        assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    };
    renders(&["render", &write("inside.gltf", quad_gltf("quad.bin"))]);
    let up = write("up.gltf", quad_gltf("../outside/quad.bin"));
    renders(&["render", &up, "--asset-root", &dir.path().display().to_string()]);
}

/// Warnings read as a tool's: what a model has that is not modelled is one `warning: ...`
/// line, with no timestamp or module path; with `-v` the user asked for logs, and gets them.
#[test]
fn warnings_are_one_line_each_unless_logs_are_asked_for() {
    let dir = sheen_model();
    let render = |verbose: &[&str]| {
        let args = [verbose, &["render", "sheen.gltf", "--width", "8", "--height", "8", "--out", "x.png"]].concat();
        let out = twinray(&args, dir.path());
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    let quiet = render(&[]);
    let warning = quiet.lines().find(|l| l.contains("KHR_materials_sheen")).expect("the ignored extension is named");
    assert!(warning.starts_with("warning: sheen.gltf: not modelled, ignored: "), "{quiet}");
    assert!(!quiet.contains("WARN") && !quiet.contains("twinray_host::"), "{quiet}");
    let logs = render(&["-v"]);
    assert!(
        logs.lines().any(|l| l.contains("WARN") && l.contains("twinray_host::") && l.contains("KHR_materials_sheen")),
        "{logs}"
    );
}

/// A folder holding `sheen.gltf`, a quad that uses an extension twinray does not model.
fn sheen_model() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("quad.bin"), quad_bytes()).unwrap();
    let model = quad_gltf("quad.bin").replacen('{', r#"{"extensionsUsed": ["KHR_materials_sheen"], "#, 1);
    std::fs::write(dir.path().join("sheen.gltf"), model).unwrap();
    dir
}

/// `bench` times each set alone on a fresh device, loading the model again for each: its
/// notice is said once per run all the same (it was said once per device: 6 lines for 2 sets
/// and 3 rounds).
#[test]
fn a_models_notice_is_said_once_per_run() {
    let dir = sheen_model();
    let timing = ["--spp", "1", "--runs", "10", "--warmup", "0", "--placements", "1", "--reference-spp", "1"];
    let alone = ["--processes", "2", "--alone-in", "devices"];
    let skipped = ["--probes", "none", "--images", "none", "--shadow-spp", "none"];
    let args = [
        &["bench", "sheen.gltf", "--sets", "rust,glsl", "--width", "32", "--height", "24", "--out", "b"][..],
        &timing,
        &alone,
        &skipped,
    ]
    .concat();
    let out = twinray(&args, dir.path());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert_eq!(stderr.matches("not modelled").count(), 1, "{stderr}");
}

/// A grid of quads as a glTF model (16-bit indices, positions and normals interleaved), each
/// quad two triangles split along its diagonal, seen head-on so that the diagonals run
/// through pixel centres, at `eye_x` across.
fn diagonal_grid(dir: &Path, eye_x: f32) -> String {
    const N: usize = 16;
    let mut vertices = Vec::new();
    for j in 0..=N {
        for i in 0..=N {
            let (x, y) = (-1.0 + 2.0 * i as f32 / N as f32, -1.0 + 2.0 * j as f32 / N as f32);
            vertices.extend([x, y, 0.0, 0.0, 0.0, 1.0]);
        }
    }
    let mut indices: Vec<u16> = Vec::new();
    for j in 0..N {
        for i in 0..N {
            let v = (j * (N + 1) + i) as u16;
            let (right, up) = (v + 1, v + N as u16 + 1);
            indices.extend([v, right, up + 1, v, up + 1, up]);
        }
    }
    let mut bytes: Vec<u8> = vertices.iter().flat_map(|v| v.to_le_bytes()).collect();
    let vertex_bytes = bytes.len();
    bytes.extend(indices.iter().flat_map(|i| i.to_le_bytes()));
    std::fs::write(dir.join("grid.bin"), &bytes).unwrap();
    let (count, index_bytes) = ((N + 1) * (N + 1), indices.len() * 2);
    let gltf = format!(
        r#"{{"asset": {{"version": "2.0"}}, "buffers": [{{"byteLength": {}, "uri": "grid.bin"}}],
        "bufferViews": [{{"buffer": 0, "byteLength": {vertex_bytes}, "byteStride": 24}},
                        {{"buffer": 0, "byteOffset": {vertex_bytes}, "byteLength": {index_bytes}}}],
        "accessors": [{{"bufferView": 0, "componentType": 5126, "count": {count}, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]}},
                      {{"bufferView": 0, "byteOffset": 12, "componentType": 5126, "count": {count}, "type": "VEC3"}},
                      {{"bufferView": 1, "componentType": 5123, "count": {}, "type": "SCALAR"}}],
        "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "NORMAL": 1}}, "indices": 2}}]}}],
        "nodes": [{{"mesh": 0}}], "scenes": [{{"nodes": [0]}}], "scene": 0}}"#,
        bytes.len(),
        indices.len()
    );
    std::fs::write(dir.join("grid.gltf"), gltf).unwrap();
    let scene = format!(
        "[image]\nwidth = 64\nheight = 64\n[camera]\neye = [{eye_x}, 0.0, 1.0]\ntarget = [{eye_x}, 0.0, 0.0]\n\
         up = [0.0, 1.0, 0.0]\nfov_y_degrees = 90.0\n[materials.m]\nkind = \"diffuse\"\ncolor = [0.3, 0.3, 0.3]\n\
         [[lights]]\nkind = \"directional\"\ndirection = [0.3, 0.4, 1.0]\ncolor = [1.0, 1.0, 1.0]\nintensity = 1.0\n\
         [shapes.grid]\nkind = \"gltf\"\nfile = \"grid.gltf\"\n[[objects]]\nshape = \"grid\"\nmaterial = \"m\"\n"
    );
    let path = dir.join(format!("grid-{eye_x}.toml"));
    std::fs::write(&path, scene).unwrap();
    path.display().to_string()
}

/// A mesh whose diagonals fall on pixel centres passes `compare`: where the two sets' rays
/// (a few ULPs apart) take one triangle or the other of a shared diagonal, the pixel is on an
/// edge inside the mesh, counted apart, not a hit mismatch. On lavapipe the sets split 182 of
/// those pixels; with the camera moved off the pixel centres, none.
#[test]
fn meshes_with_shared_diagonals_pass_compare() {
    let dir = tempfile::tempdir().unwrap();
    for (eye_x, on_centres) in [(0.0, true), (0.01, false)] {
        let scene = diagonal_grid(dir.path(), eye_x);
        let out =
            twinray(&[&["compare", &scene, "--a", "rust", "--b", "glsl", "--json"][..], &UNTIMED].concat(), dir.path());
        let said = format!("{}{}", String::from_utf8_lossy(&out.stderr), String::from_utf8_lossy(&out.stdout));
        assert!(out.status.success(), "{said}");
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
        assert_eq!((json["pass"].as_bool(), json["hit_mismatches"].as_u64()), (Some(true), Some(0)), "{json}");
        let edges = json["internal_edges"].as_u64().expect("internal_edges");
        assert_eq!(edges > 0, on_centres, "{edges} pixels on internal edges, camera at x = {eye_x}");
    }
}

/// A 16384 x 16384 picture in a 64 KB PNG (one bit per pixel, all black), as a model's base
/// colour texture: refused by the size its header gives, against the model's budget, before
/// it is decoded, with one line naming the image, under a 1 GiB address-space limit on the
/// whole render. Decoded to RGBA with its mips it would take 1.3 GiB; the build before issue
/// 54 decoded such a file and peaked at 4.3 GB.
#[test]
fn a_small_file_of_a_huge_image_is_refused_before_it_is_decoded() {
    let dir = tempfile::tempdir().unwrap();
    let side = 16384u32;
    let mut png = Vec::new();
    let mut encoder = png::Encoder::new(&mut png, side, side);
    encoder.set_color(png::ColorType::Grayscale);
    encoder.set_depth(png::BitDepth::One);
    let mut writer = encoder.write_header().unwrap();
    writer.write_image_data(&vec![0u8; (side as usize / 8) * side as usize]).unwrap();
    writer.finish().unwrap();
    assert!(png.len() < 128 << 10, "{} bytes encoded", png.len());
    std::fs::write(dir.path().join("huge.png"), &png).unwrap();
    let model = textured_quad(dir.path(), "huge.png");
    let out = render_within_1_gib(dir.path(), &model);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("huge.png") && stderr.contains("16384x16384"), "{stderr}");
    assert!(!dir.path().join("x.png").exists());
    // The same model with a small picture in that file renders under the same limit.
    let mut small = Vec::new();
    image::GrayImage::new(64, 64).write_to(&mut std::io::Cursor::new(&mut small), image::ImageFormat::Png).unwrap();
    std::fs::write(dir.path().join("huge.png"), &small).unwrap();
    let out = render_within_1_gib(dir.path(), &model);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}

/// A 64 x 64 PNG with a colour profile (iCCP) and a compressed text chunk (zTXt) that each
/// inflate to 1 GiB, as a model's texture: it renders under a 1 GiB address-space limit on
/// the whole render, as its picture does without them. A loader that decoded the
/// metadata too peaked at 1,035 MB on such a file.
#[test]
fn metadata_that_inflates_is_not_inflated() {
    let dir = tempfile::tempdir().unwrap();
    let mut small = Vec::new();
    image::GrayImage::new(64, 64).write_to(&mut std::io::Cursor::new(&mut small), image::ImageFormat::Png).unwrap();
    let (head, tail) = small.split_at(8 + 25); // the signature and IHDR
    let gib = zeros_zlib(1 << 30);
    let mut png = head.to_vec();
    png.extend(png_chunk(b"iCCP", &[b"profile\0\0".as_slice(), &gib].concat()));
    png.extend(png_chunk(b"zTXt", &[b"Comment\0\0".as_slice(), &gib].concat()));
    png.extend(tail);
    std::fs::write(dir.path().join("inflating.png"), &png).unwrap();
    let model = textured_quad(dir.path(), "inflating.png");
    let out = render_within_1_gib(dir.path(), &model);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(dir.path().join("x.png").exists());
}

/// A PNG chunk of `kind` holding `body`, its checksum right.
fn png_chunk(kind: &[u8; 4], body: &[u8]) -> Vec<u8> {
    let mut out = (body.len() as u32).to_be_bytes().to_vec();
    out.extend(kind);
    out.extend(body);
    let mut crc = !0u32;
    for &b in &out[4..] {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 != 0 { 0xedb8_8320 ^ (crc >> 1) } else { crc >> 1 };
        }
    }
    out.extend((!crc).to_be_bytes());
    out
}

/// A zlib stream of about `bytes` zero bytes, written out rather than compressed: one
/// fixed-Huffman block of a literal 0 and then copies of 258 bytes at distance 1, 13 bits
/// each (RFC 1951), so 1 GiB takes 6.5 MB and no time.
fn zeros_zlib(bytes: usize) -> Vec<u8> {
    let copies = bytes / 258;
    let (mut out, mut acc, mut filled) = (vec![0x78, 0x01], 0u32, 0);
    let mut put = |bits: u32, count: u32, msb_first: bool, out: &mut Vec<u8>| {
        for k in 0..count {
            let bit = if msb_first { bits >> (count - 1 - k) } else { bits >> k } & 1;
            acc |= bit << filled;
            filled += 1;
            if filled == 8 {
                out.push(acc as u8);
                (acc, filled) = (0, 0);
            }
        }
    };
    put(0b011, 3, false, &mut out); // the last block, fixed Huffman codes
    put(0x30, 8, true, &mut out); // literal 0
    for _ in 0..copies {
        put(0b1100_0101, 8, true, &mut out); // length 258 (code 285)
        put(0, 5, true, &mut out); // distance 1 (code 0)
    }
    put(0, 7, true, &mut out); // end of block
    if filled > 0 {
        out.push(acc as u8); // the last bits, padded to a byte
    }
    let n = (1 + 258 * copies) as u64;
    let adler = ((n % 65521) << 16) | 1; // all zeros: a = 1, b = n
    out.extend((adler as u32).to_be_bytes());
    out
}

/// A model (written to `dir`) of one quad whose base colour texture is `image`, a file in
/// `dir`.
fn textured_quad(dir: &Path, image: &str) -> PathBuf {
    let mut bin = quad_bytes();
    bin.extend([0.0f32, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0].iter().flat_map(|v| v.to_le_bytes()));
    std::fs::write(dir.join("quad.bin"), &bin).unwrap();
    let gltf = quad_gltf("quad.bin")
        .replace(r#""byteLength": 56, "uri""#, r#""byteLength": 88, "uri""#)
        .replace(
            r#"{"buffer": 0, "byteOffset": 48, "byteLength": 8}]"#,
            r#"{"buffer": 0, "byteOffset": 48, "byteLength": 8}, {"buffer": 0, "byteOffset": 56, "byteLength": 32}]"#,
        )
        .replace(
            r#""type": "SCALAR"}],"#,
            &format!(
                r#""type": "SCALAR"}}, {{"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"}}],
            "images": [{{"uri": "{image}"}}], "textures": [{{"source": 0}}],
            "materials": [{{"pbrMetallicRoughness": {{"baseColorTexture": {{"index": 0}}}}}}],"#
            ),
        )
        .replace(
            r#"{"POSITION": 0}, "indices": 1}"#,
            r#"{"POSITION": 0, "TEXCOORD_0": 2}, "indices": 1, "material": 0}"#,
        );
    assert!(gltf.contains("TEXCOORD_0") && gltf.contains("\"byteOffset\": 56"), "{gltf}");
    let model = dir.join("textured.gltf");
    std::fs::write(&model, gltf).unwrap();
    model
}

/// `twinray render MODEL` at 16 x 16 to `x.png` in `dir`, under a 1 GiB address space.
fn render_within_1_gib(dir: &Path, model: &Path) -> std::process::Output {
    std::process::Command::new("sh")
        .arg("-c")
        .arg("ulimit -v 1048576; exec \"$0\" \"$@\"")
        .arg(env!("CARGO_BIN_EXE_twinray"))
        .arg("render")
        .arg(model)
        .args(["--width", "16", "--height", "16", "--out", "x.png"])
        .current_dir(dir)
        .output()
        .unwrap()
}

/// A valid model whose `extras` are an array, a number, a string, null and a boolean (the
/// schema allows any JSON value), one type at each place: the root, buffer, views, accessor,
/// mesh, primitive, node and scene, and an unknown extension's object of each type on the
/// node. `compare` renders it with both sets and passes: the format allows an array, number or
/// string there, and a loader that took only objects refused them.
#[test]
fn a_model_with_extras_of_every_json_type_passes_compare() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("quad.bin"), quad_bytes()).unwrap();
    let values = ["[1, \"two\"]", "3.5", "\"text\"", "null", "false"];
    let places = [
        "{\"asset\": ",
        "{\"byteLength\"",
        "{\"buffer\": 0",
        "{\"bufferView\": 0",
        "{\"primitives\"",
        "{\"attributes\"",
        "{\"nodes\"",
    ];
    let mut gltf = quad_gltf("quad.bin");
    for (i, place) in places.iter().enumerate() {
        gltf = gltf.replace(place, &format!("{{\"extras\": {}, {}", values[i % values.len()], &place[1..]));
    }
    let unknown: Vec<String> = values.iter().enumerate().map(|(i, v)| format!("\"EXT_nobody_{i}\": {v}")).collect();
    gltf = gltf.replace(
        "{\"mesh\": 0}",
        &format!("{{\"extras\": true, \"extensions\": {{{}}}, \"mesh\": 0}}", unknown.join(", ")),
    );
    assert_eq!(gltf.matches("\"extras\"").count(), 9, "{gltf}");
    std::fs::write(dir.path().join("extras.gltf"), &gltf).unwrap();
    let out =
        twinray(&[&["compare", "extras.gltf", "--width", "32", "--height", "32"][..], &UNTIMED].concat(), dir.path());
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}\n{stdout}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("PASS"), "{stdout}");
}
