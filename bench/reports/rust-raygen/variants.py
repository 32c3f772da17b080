#!/usr/bin/env python3
"""Builds the ray generation variants of bench/reports/rust-raygen/README.md (issue 15) into
OUT (default target/twinray-bench/i15), with the 16-spp scenes they were timed on.

    python3 bench/reports/rust-raygen/variants.py [OUT] [--no-rust] [--only=NAME,...]

Needs spirv-cross, glslangValidator and spirv-as/spirv-dis/spirv-val (Debian spirv-cross,
glslang-tools, spirv-tools). The decompiled variants start from the ray generation modules
committed at 6ad90f5 (the ones timed; the ids of SPIRV-Cross's names depend on them). The
Rust variants patch shaders-rs, run `cargo xtask shaders`, copy spirv/rust/raygen.spv and
restore the tree with git; every patch asserts that the text it replaces is there (written
against 6ad90f5, where they rebuild byte for byte). Run from the repository root with a clean
tree."""
import os
import re
import subprocess
import sys
import time

ROOT = os.getcwd()
GLSL = os.path.join(ROOT, "shaders-glsl")
args = [a for a in sys.argv[1:] if not a.startswith("--")]
OUT = os.path.abspath(args[0] if args else "target/twinray-bench/i15")
WORK = os.path.join(OUT, "work")
os.makedirs(WORK, exist_ok=True)


def run(*cmd, cwd=None):
    subprocess.run(cmd, check=True, cwd=cwd)


def read(path):
    with open(path) as f:
        return f.read()


def write(path, text):
    with open(path, "w") as f:
        f.write(text)


def replace(text, old, new, count=1):
    assert old in text, f"patch does not apply: {old[:60]!r}"
    return text.replace(old, new, count)


def glslang(source, name, include=GLSL):
    run("glslangValidator", "--target-env", "spirv1.4", "-V", "-I" + include, source,
        "-o", os.path.join(OUT, f"raygen_{name}.spv"))


def memory_model_glsl450(spv, name):
    """The module with the GLSL450 memory model rust-gpu's Vulkan one replaced."""
    text = subprocess.run(["spirv-dis", spv], check=True, capture_output=True, text=True).stdout
    text = replace(text, "OpMemoryModel Logical Vulkan", "OpMemoryModel Logical GLSL450")
    text = "\n".join(l for l in text.split("\n")
                     if "OpCapability VulkanMemoryModel" not in l and "SPV_KHR_vulkan_memory_model" not in l)
    asm = os.path.join(WORK, name + ".spvasm")
    write(asm, text)
    out = os.path.join(OUT, f"raygen_{name}.spv")
    run("spirv-as", "--target-env", "spv1.4", asm, "-o", out)
    run("spirv-val", "--target-env", "vulkan1.2", out)


def scenes():
    """The scenes timed at 4 x 4 samples per pixel."""
    for s in ["showcase", "cone", "cylinder", "torus", "sphere", "spheres", "plane"]:
        lines, in_image = [], False
        for line in read(f"scenes/{s}.toml").split("\n"):
            if line.startswith("["):
                in_image = line == "[image]"
                lines.append(line)
                if in_image:
                    lines.append("samples = 4")
                continue
            if in_image and line.startswith("samples"):
                continue
            lines.append(line)
        write(os.path.join(OUT, f"{s}-16.toml"), "\n".join(lines))


TIMED = "6ad90f5"


def timed_module(language):
    """The ray generation module of `language` as committed at TIMED, in WORK."""
    path = os.path.join(WORK, f"{language}-raygen.spv")
    with open(path, "wb") as f:
        f.write(subprocess.run(["git", "show", f"{TIMED}:spirv/{language}/raygen.spv"], check=True,
                               capture_output=True).stdout)
    return path


def decompiled():
    """The Rust ray generation through SPIRV-Cross and glslang (x), and the GLSL one (glsl_x,
    the control), and the Rust one under the GLSL450 memory model."""
    for language, name in [("rust", "x"), ("glsl", "glsl_x")]:
        rgen = os.path.join(WORK, f"raygen_{name}.rgen")
        run("spirv-cross", timed_module(language), "--vulkan-semantics", "--version", "460", "--output", rgen)
        glslang(rgen, name)
    memory_model_glsl450(timed_module("rust"), "glsl450")


def glsl_edits():
    """The GLSL ray generation with the Rust one's habits: g1 keeps the first hit's ids in
    locals and writes them after the loops; g2 reads the normal from the payload in the light
    loop; g12 both."""
    for name, first_hit, normal in [("g1", True, False), ("g2", False, True), ("g12", True, True)]:
        d = os.path.join(WORK, name)
        os.makedirs(d, exist_ok=True)
        for f in ["raygen.rgen", "raygen_main.glsl", "trace.glsl"]:
            write(os.path.join(d, f), read(os.path.join(GLSL, f)))
        if first_hit:
            p = os.path.join(d, "raygen_main.glsl")
            s = read(p)
            s = replace(s, "    uint shadow_rays = 0u;", "    uint shadow_rays = 0u;\n    uvec2 first_hit = uvec2(NO_HIT);")
            s = replace(s, "                hit_ids[HIT_IDS_PER_PIXEL * pixel_index] = payload.ids.x;\n"
                           "                hit_ids[HIT_IDS_PER_PIXEL * pixel_index + 1u] = payload.ids.y;",
                        "                first_hit = payload.ids.xy;")
            s = replace(s, "    hit_ids[HIT_IDS_PER_PIXEL * pixel_index + 2u] = shadow_rays;",
                        "    hit_ids[HIT_IDS_PER_PIXEL * pixel_index] = first_hit.x;\n"
                        "    hit_ids[HIT_IDS_PER_PIXEL * pixel_index + 1u] = first_hit.y;\n"
                        "    hit_ids[HIT_IDS_PER_PIXEL * pixel_index + 2u] = shadow_rays;")
            write(p, s)
        if normal:
            p = os.path.join(d, "trace.glsl")
            write(p, replace(read(p), "float cosine = dot(normal, s.direction);",
                             "float cosine = dot(payload.shading_normal.xyz, s.direction);"))
        glslang(os.path.join(d, "raygen.rgen"), name)


# The decompiled Rust ray generation names its values by SPIR-V id; these are the ids of the
# committed module (6ad90f5) under SPIRV-Cross 2021.01.15 (Debian bookworm).
SHADE_START = "                    bool _637 = _39 != 0u;"
SHADE_END = "                    vec3 _866 = _451;"

SHADE_BODY = """uint dimension = 2u + 2u * (l * 64u + j * n + i);
                float r1 = 0.0, r2 = 0.0;
                if (light._m0 == 2u) {
                    r1 = _42(_5._m0._m4, pixel, sample_index, dimension);
                    r2 = _42(_5._m0._m4, pixel, sample_index, dimension + 1u);
                }
                float nf = float(n);
                _41 s = stratified ? _48(light, point, i, j, r1, r2) : _48(light, point, 0u, 0u, r1 * nf, r2 * nf);
                float cosine = dot(normal, s._m0);
                bool casts = shadows && light._m2 != 0u;
                if (cosine > 0.0) {
                    bool lit = true;
                    if (casts) {
                        shadow_rays++;
                        _10._m0 = 1u;
                        traceRayEXT(_8, 4u | 8u, int(1u), 0, 0, int(1u), origin, 0.0, s._m0, s._m1, 1);
                        lit = _10._m0 == 0u;
                    }
                    if (lit) {
                        light_sum += s._m2 * cosine;
                    }
                }"""


def shade_g(nested, bound):
    """trace.glsl's shade() written over the decompiled module's types and helpers (_42 random,
    _45 offset_ray, _47 samples_per_side, _48 light sample): GLSL's loop shape, Rust's math."""
    if nested:
        loop = ("        for (uint j = 0u; j < n; j++) {\n            for (uint i = 0u; i < n; i++) {\n                "
                + SHADE_BODY + "\n            }\n        }")
    else:
        loop = ("        uint i = 0u, j = 0u;\n        while (j < n) {\n            " + SHADE_BODY
                + "\n            i++;\n            if (i == n) { i = 0u; j++; }\n        }")
    check = "        if (l >= uint(_6._m0.length())) { break; }\n" if bound else ""
    return ("\nvec3 shade_g(bool shadows, bool stratified, uint pixel, uint sample_index, inout uint shadow_rays) {\n"
            "    if (_9._m4.w == 4294967295u || _9._m4.z == 1u) {\n        return _9._m3.xyz;\n    }\n"
            "    vec3 point = _9._m0.xyz;\n    vec3 normal = _9._m1.xyz;\n    vec3 origin = _45(point, _9._m2.xyz);\n"
            "    vec3 light_sum = vec3(0.0);\n    for (uint l = 0u; l < _5._m0._m3; l++) {\n" + check
            + "        _37 light = _37(_6._m0[l]._m0, _6._m0[l]._m1, _6._m0[l]._m2, _6._m0[l]._m3, _6._m0[l]._m4,"
              " _6._m0[l]._m5, _6._m0[l]._m6, _6._m0[l]._m7);\n"
            + "        uint n = _47(light);\n" + loop + "\n    }\n    return _9._m3.xyz * light_sum;\n}\n")


CAMERA_EXPANDED = """            float _570 = (((_5._m0._m1._m0.x * ndc.x) + (_5._m0._m1._m1.x * ndc.y)) + (_5._m0._m1._m2.x * 1.0)) + (_5._m0._m1._m3.x * 1.0);
            float _571 = (((_5._m0._m1._m0.y * ndc.x) + (_5._m0._m1._m1.y * ndc.y)) + (_5._m0._m1._m2.y * 1.0)) + (_5._m0._m1._m3.y * 1.0);
            float _572 = (((_5._m0._m1._m0.z * ndc.x) + (_5._m0._m1._m1.z * ndc.y)) + (_5._m0._m1._m2.z * 1.0)) + (_5._m0._m1._m3.z * 1.0);
            float _581 = 1.0 / sqrt(((_570 * _570) + (_571 * _571)) + (_572 * _572));
            float _582 = _570 * _581;
            float _583 = _571 * _581;
            float _584 = _572 * _581;
            vec3 origin = vec3((((_5._m0._m0._m0.x * 0.0) + (_5._m0._m0._m1.x * 0.0)) + (_5._m0._m0._m2.x * 0.0)) + (_5._m0._m0._m3.x * 1.0), (((_5._m0._m0._m0.y * 0.0) + (_5._m0._m0._m1.y * 0.0)) + (_5._m0._m0._m2.y * 0.0)) + (_5._m0._m0._m3.y * 1.0), (((_5._m0._m0._m0.z * 0.0) + (_5._m0._m0._m1.z * 0.0)) + (_5._m0._m0._m2.z * 0.0)) + (_5._m0._m0._m3.z * 1.0));
            vec3 direction = vec3((((_5._m0._m0._m0.x * _582) + (_5._m0._m0._m1.x * _583)) + (_5._m0._m0._m2.x * _584)) + (_5._m0._m0._m3.x * 0.0), (((_5._m0._m0._m0.y * _582) + (_5._m0._m0._m1.y * _583)) + (_5._m0._m0._m2.y * _584)) + (_5._m0._m0._m3.y * 0.0), (((_5._m0._m0._m0.z * _582) + (_5._m0._m0._m1.z * _583)) + (_5._m0._m0._m2.z * _584)) + (_5._m0._m0._m3.z * 0.0));"""

CAMERA_MATRIX = """            mat4 proj_inverse = mat4(_5._m0._m1._m0, _5._m0._m1._m1, _5._m0._m1._m2, _5._m0._m1._m3);
            mat4 view_inverse = mat4(_5._m0._m0._m0, _5._m0._m0._m1, _5._m0._m0._m2, _5._m0._m0._m3);
            vec4 target = proj_inverse * vec4(ndc, 1.0, 1.0);
            vec3 direction = (view_inverse * vec4(normalize(target.xyz), 0.0)).xyz;
            vec3 origin = (view_inverse * vec4(0.0, 0.0, 0.0, 1.0)).xyz;"""


def glsl_main(camera):
    """raygen_main.glsl's main() over the decompiled module's names, with `camera`."""
    return """void main()
{
    uvec2 pixel = gl_LaunchIDEXT.xy;
    uint pixel_index = gl_LaunchIDEXT.y * gl_LaunchSizeEXT.x + gl_LaunchIDEXT.x;
    vec3 sum = vec3(0.0);
    uint shadow_rays = 0u;
    for (uint sy = 0u; sy < _38; sy++) {
        for (uint sx = 0u; sx < _38; sx++) {
            uint sample_index = sy * _38 + sx;
            float r1 = 0.5, r2 = 0.5;
            if (_38 > 1u) {
                r1 = _42(_5._m0._m4, pixel_index, sample_index, 0u);
                r2 = _42(_5._m0._m4, pixel_index, sample_index, 1u);
            }
            vec2 offset = _44(sx, sy, _38, r1, r2);
            vec2 ndc = ((vec2(pixel) + offset) / vec2(gl_LaunchSizeEXT.xy)) * 2.0 - 1.0;
""" + camera + """
            traceRayEXT(_8, 0u, 255, 0, 0, 0, origin, 0.100000001490116119384765625, direction, 1000.0, 0);
            if (sample_index == 0u) {
                _7._m0[3u * pixel_index] = _9._m4.x;
                _7._m0[3u * pixel_index + 1u] = _9._m4.y;
            }
            sum += shade_g(_39 != 0u, _40 == 0u, pixel_index, sample_index, shadow_rays);
        }
    }
    _7._m0[3u * pixel_index + 2u] = shadow_rays;
    vec3 color = sum / float(_38 * _38);
    imageStore(_11, ivec2(pixel), vec4(color, 1.0));
}
"""


HELPERS = {
    "42": ("float _42(uint _135, uint _136, uint _137, uint _138)",
           "float _42(uint a, uint b, uint c, uint d) { return random(a, b, c, d); }"),
    "44": ("vec2 _44(uint _163, uint _164, uint _165, float _166, float _167)",
           "vec2 _44(uint sx, uint sy, uint m, float r1, float r2) { return sample_offset(sx, sy, m, r1, r2); }"),
    "45": ("vec3 _45(vec3 _187, vec3 _188)", "vec3 _45(vec3 p, vec3 n) { return offset_ray(p, n); }"),
    "47": ("uint _47(_37 _232)", "uint _47(_37 l) { return light_samples_per_side(to_light(l)); }"),
    "48": ("_41 _48(_37 _255, vec3 _256, uint _257, uint _258, float _259, float _260)",
           "_41 _48(_37 l, vec3 p, uint i, uint j, float r1, float r2) { LightSample s = "
           "light_sample(to_light(l), p, i, j, r1, r2); return _41(s.direction, s.distance, s.irradiance); }"),
}
INCLUDES = """#extension GL_GOOGLE_include_directive : require
#include "twinray_layout.glsl"
#include "random.glsl"
#include "offset.glsl"
#include "lighting.glsl"
#include "camera.glsl"
Light to_light(_37 l) { return Light(l._m0, l._m1, l._m2, l._m3, l._m4, l._m5, l._m6, l._m7); }
"""


def decompiled_edits():
    """xg: the decompiled Rust ray generation with trace.glsl's shading loop (nested, or
    Rust's one loop, or with Rust's light bound check); xgm: with raygen_main.glsl's pixel loop
    too (camera as Rust expands it, or as mat4 products: xgmc); xgm_hNN: xgm with helper _NN
    replaced by the GLSL twin."""
    x = read(os.path.join(WORK, "raygen_x.rgen"))
    start, end = x.index(SHADE_START), x.index(SHADE_END)
    call = "                    uint _861 = _448;\n                    vec3 _862 = shade_g(_39 != 0u, _40 == 0u, _428, _466, _861);\n"
    main = x.index("void main()")
    for name, nested, bound in [("xg", True, False), ("xg_single", False, False), ("xg_bound", True, True)]:
        text = x[:main] + shade_g(nested, bound) + x[main:start] + call + x[end:]
        write(os.path.join(WORK, f"raygen_{name}.rgen"), text)
        glslang(os.path.join(WORK, f"raygen_{name}.rgen"), name)
    head = x[:main] + shade_g(True, False)
    for name, camera in [("xgm", CAMERA_EXPANDED), ("xgmc", CAMERA_MATRIX)]:
        write(os.path.join(WORK, f"raygen_{name}.rgen"), head + glsl_main(camera))
        glslang(os.path.join(WORK, f"raygen_{name}.rgen"), name)
    xgm = head + glsl_main(CAMERA_EXPANDED)
    layout = xgm.index("layout(set = 0, binding = 2, std140)")
    for name, keys in [("h42", ["42"]), ("h44", ["44"]), ("h45", ["45"]), ("h48", ["47", "48"]),
                       ("hall", ["42", "44", "45", "47", "48"])]:
        text = xgm[:layout] + INCLUDES + xgm[layout:]
        for k in keys:
            old, new = HELPERS[k]
            text = replace(text, old, old.replace(f" _{k}(", f" old_{k}("))
            at = text.index("\nvec3 shade_g(")
            text = text[:at] + "\n" + new + text[at:]
        write(os.path.join(WORK, f"raygen_xgm_{name}.rgen"), text)
        glslang(os.path.join(WORK, f"raygen_xgm_{name}.rgen"), f"xgm_{name}")


TRACE = "shaders-rs/shaders/src/trace.rs"
LIB = "shaders-rs/shaders/src/lib.rs"


def light_by_reference(files):
    s = files[TRACE]
    s = replace(s, "let light = unsafe { *lights.get_unchecked(index) };", "let light = unsafe { lights.get_unchecked(index) };")
    s = replace(s, "let n = lighting::samples_per_side(&light);", "let n = lighting::samples_per_side(light);")
    files[TRACE] = replace(s, "let s = lighting::sample(&light, point, si, sj, r1, r2);",
                           "let s = lighting::sample(light, point, si, sj, r1, r2);")


def albedo_copied(files):
    s = replace(files[TRACE], "    let point = hit.position.xyz();\n",
                "    let albedo = hit.color.xyz();\n    let point = hit.position.xyz();\n")
    files[TRACE] = replace(s, "    hit.color.xyz() * light_sum\n}", "    albedo * light_sum\n}")


def ids_in_loop(files):
    s = replace(files[LIB], "    let mut first_hit = (NO_HIT, NO_HIT);",
                "    let base = (HIT_IDS_PER_PIXEL * pixel_index) as usize;\n    let ids_fit = base + 2 < hit_ids.len();")
    s = replace(s, """            if sample == 0 {
                first_hit = ($payload.ids.x, $payload.ids.y);
            }""", """            if sample == 0 {
                if ids_fit {
                    unsafe {
                        *hit_ids.get_unchecked_mut(base) = $payload.ids.x;
                        *hit_ids.get_unchecked_mut(base + 1) = $payload.ids.y;
                    }
                }
            }""")
    files[LIB] = replace(s, """    let base = (HIT_IDS_PER_PIXEL * pixel_index) as usize;
    hit_ids[base] = first_hit.0;
    hit_ids[base + 1] = first_hit.1;
    hit_ids[base + 2] = shadow_rays;""", "    hit_ids[base + 2] = shadow_rays;")


def one_sample_loop(files):
    s = replace(files[LIB], """    let mut sy = 0;
    while sy < samples_per_side {
        let mut sx = 0;
        while sx < samples_per_side {""", """    let (mut sx, mut sy) = (0, 0);
    while sy < samples_per_side {
        {""")
    files[LIB] = replace(s, """            sx += 1;
        }
        sy += 1;
    }""", """            sx += 1;
            if sx == samples_per_side {
                sx = 0;
                sy += 1;
            }
        }
    }""")


SHADE_CALL_END = """                &mut shadow_rays,
            );
"""


def primary_only(files):
    """The pixel's samples shaded by the payload's colour alone: no lights, no shadow rays."""
    s = files[LIB]
    start = s.index("            sum += $shade(")
    end = s.index(SHADE_CALL_END, start) + len(SHADE_CALL_END)
    # The lights, spec constants and shading helpers it no longer uses stay declared.
    files[LIB] = "#![allow(unused)]\n" + s[:start] + "            sum += $payload.color.xyz();\n" + s[end:]


def do_while_loops(files):
    """The pixel's sample loops tested at the bottom (`loop { ...; if done { break; } }`):
    there is at least one sample per side, so the test at the top is not needed."""
    s = replace(files[LIB], """    let mut sy = 0;
    while sy < samples_per_side {
        let mut sx = 0;
        while sx < samples_per_side {""", """    let mut sy = 0;
    loop {
        let mut sx = 0;
        loop {""")
    files[LIB] = replace(s, """            sx += 1;
        }
        sy += 1;
    }""", """            sx += 1;
            if sx >= samples_per_side {
                break;
            }
        }
        sy += 1;
        if sy >= samples_per_side {
            break;
        }
    }""")


def glsl_primary_only():
    """The GLSL twin of `primary_only` (m_glsl)."""
    d = os.path.join(WORK, "m_glsl")
    os.makedirs(d, exist_ok=True)
    write(os.path.join(d, "raygen.rgen"), read(os.path.join(GLSL, "raygen.rgen")))
    s = read(os.path.join(GLSL, "raygen_main.glsl"))
    s = replace(s, """            sum += shade(SHADOWS != 0u, SHADOW_SAMPLER == SHADOW_SAMPLER_STRATIFIED, pixel_index, sample_index,
                         shadow_rays);""", "            sum += payload.color.xyz;")
    write(os.path.join(d, "raygen_main.glsl"), s)
    glslang(os.path.join(d, "raygen.rgen"), "m_glsl")


def rust_variants():
    """Rust ray generation variants: the Light by reference (l1), the albedo read before the
    shadow rays (r_copy), the first hit's ids written in the loop (r_ids), one loop over the
    samples (r_single), the sample loops tested at the bottom (r_dowhile), and combinations;
    m_*: the primary-only ray generation (no shading, no shadow rays) with the same loop
    variants, the pair for the upstream report beside m_glsl. `--only=a,b` builds those alone."""
    only = [a.split("=", 1)[1].split(",") for a in sys.argv[1:] if a.startswith("--only=")]
    variants = {
        "l1": [light_by_reference],
        "r_copy": [albedo_copied],
        "r_ids": [ids_in_loop],
        "r_copy_ids": [albedo_copied, ids_in_loop],
        "r_single": [one_sample_loop],
        "r_single_ids": [one_sample_loop, ids_in_loop],
        "r_dowhile": [do_while_loops],
        "r_dowhile_ids": [do_while_loops, ids_in_loop],
        "m_rust": [primary_only],
        "m_rust_ids": [primary_only, ids_in_loop],
        "m_rust_dowhile": [primary_only, do_while_loops],
    }
    for name, patches in variants.items():
        if only and name not in only[0]:
            continue
        files = {p: read(p) for p in [TRACE, LIB]}
        try:
            for patch in patches:
                patch(files)
            for p, text in files.items():
                write(p, text)
            built = "spirv/rust/raygen.spv"
            if name.startswith("m_"):
                # The primary-only stage no longer binds the lights, so the shader build's
                # check against the GLSL set's bindings fails after building it: take it
                # from the build folder.
                built = "target/xtask-shaders/rust/raygen.spv"
                started = time.time()
                subprocess.run(["cargo", "xtask", "shaders"])
                assert os.path.getmtime(built) >= started, f"{name}: not built"
            else:
                run("cargo", "xtask", "shaders")
            write_bytes = open(built, "rb").read()
            with open(os.path.join(OUT, f"raygen_{name}.spv"), "wb") as f:
                f.write(write_bytes)
        finally:
            run("git", "checkout", "-q", "--", "shaders-rs", "spirv")
    if not only or "l1" in only[0]:
        memory_model_glsl450(os.path.join(OUT, "raygen_l1.spv"), "l1_glsl450")


def spirv_opt_sets():
    """Every module of both committed sets through spirv-opt -O (O_rust, O_glsl), and the
    Rust set through inlining and block merging alone (inl_rust), as sets from disk in
    OUT/opt: what a SPIR-V transform in `cargo xtask shaders` could do (not yet timed)."""
    passes = {"O": ["-O"], "inl": ["--inline-entry-points-exhaustive", "--eliminate-dead-functions",
                                   "--ssa-rewrite", "--merge-blocks", "--cfg-cleanup",
                                   "--eliminate-dead-code-aggressive"]}
    for name, flags in passes.items():
        for language in ["rust", "glsl"] if name == "O" else ["rust"]:
            d = os.path.join(OUT, "opt", f"{name}_{language}")
            os.makedirs(d, exist_ok=True)
            for module in sorted(os.listdir(f"spirv/{language}")):
                run("spirv-opt", "--target-env=vulkan1.2", *flags, f"spirv/{language}/{module}",
                    "-o", os.path.join(d, module))


if __name__ == "__main__":
    scenes()
    decompiled()
    glsl_edits()
    decompiled_edits()
    glsl_primary_only()
    spirv_opt_sets()
    if "--no-rust" not in sys.argv:
        rust_variants()
    print(f"variants in {OUT}")
