//! `twinray view` in a real browser (Debian's chromium through chromedriver): the page shows
//! both sets; the wipe moves; a save to a GLSL stage in a scratch copy of the sources shows the
//! new images and their difference within a stated time; a click on a pixel of the planted
//! difference explains the ray that parts; a broken save shows its error and the next good one
//! recovers. And, over plain HTTP: a stage that never returns is a message while the server
//! keeps running, and every request outside what the server serves is refused.

#[path = "view/harness.rs"]
mod harness;

use fantoccini::actions::{InputSource, MouseActions, PointerAction, MOUSE_BUTTON_LEFT};
use fantoccini::Locator;
use harness::{Browser, Server};
use serde_json::Value;
use std::path::Path;
use std::time::{Duration, Instant};
use twinray_tests::cli::assert_bad_input;
use twinray_tests::repo_root as repo;

/// The planted difference: set B's miss stage shows half the background.
const MISS: &str = "payload.color = frame.background;";
const HALF_MISS: &str = "payload.color = frame.background * 0.5;";
const BROKEN_MISS: &str = "payload.color = frame.background * ;";

/// Longest a save may take to reach the page at the preview size on lavapipe here: a bound that
/// catches a page that never follows, not a slow one. Measured alone: about 3 s (2.2 s of it
/// compiling the 28 GLSL modules). `cargo xtask test` runs two other test binaries beside this
/// one on CI's 2 cores, where compiling the GLSL set took 13.9 s and a save took over 30 s.
const SAVE_TO_PAGE: Duration = Duration::from_secs(90);
/// The first build and render, and a full-size render after a preview.
const FIRST_RENDER: Duration = Duration::from_secs(120);
/// The page's timing: 6 placements, each compiling its spacer pipelines. With a cold shader
/// cache and another test binary beside it on 2 cores it took over 120 s; since the mesh
/// stages sample textures, over 400 s: lavapipe compiles a pipeline of them in 3.86 s
/// against 0.45 s before (`twinray render meshes --no-pipeline-cache` with
/// MESA_SHADER_CACHE_DISABLE=true, this set against the modules of e30b23a).
const TIMING: Duration = Duration::from_secs(900);

/// Copies `shaders-glsl/` into `dir`: a checkout of the GLSL sources to edit.
fn scratch_sources(dir: &Path) {
    let to = dir.join("shaders-glsl");
    let mut stack = vec![(repo().join("shaders-glsl"), to)];
    while let Some((from, to)) = stack.pop() {
        std::fs::create_dir_all(&to).unwrap();
        for entry in std::fs::read_dir(&from).unwrap() {
            let path = entry.unwrap().path();
            let target = to.join(path.file_name().unwrap());
            if path.is_dir() {
                stack.push((path, target));
            } else {
                std::fs::copy(&path, &target).unwrap();
            }
        }
    }
}

fn edit(file: &Path, from: &str, to: &str) {
    let text = std::fs::read_to_string(file).unwrap();
    assert!(text.contains(from), "{} has no {from:?}", file.display());
    std::fs::write(file, text.replace(from, to)).unwrap();
}

/// The id of the render the page draws (0 before any).
async fn shown(browser: &Browser) -> u64 {
    browser.js("return Number(document.body.dataset.shown || 0)").await.as_u64().unwrap()
}

/// Clicks image pixel (x, y) of canvas A with the WebDriver mouse.
async fn click_pixel(browser: &Browser, x: u32, y: u32) {
    let script = format!(
        "const c = document.getElementById('canvas-a'); const t = transform(c); \
         const r = c.getBoundingClientRect(); \
         return [r.left + t.ox + ({x} + 0.5) * t.scale, r.top + t.oy + ({y} + 0.5) * t.scale];"
    );
    let at = browser.js(&script).await;
    let (px, py) = (at[0].as_f64().unwrap(), at[1].as_f64().unwrap());
    let mouse = MouseActions::new("mouse".into())
        .then(PointerAction::MoveTo { duration: None, x: px.round(), y: py.round() })
        .then(PointerAction::Down { button: MOUSE_BUTTON_LEFT })
        .then(PointerAction::Up { button: MOUSE_BUTTON_LEFT });
    browser.client.perform_actions(mouse).await.unwrap();
}

/// What canvas A shows at image pixel (x, y) after the wipe is put at `wipe`, and A's and B's
/// values there.
async fn wipe_at(browser: &Browser, wipe: f64, (x, y): (u32, u32)) -> (Value, Value, Value) {
    let script = format!(
        "const w = document.getElementById('wipe'); w.value = '{wipe}'; w.dispatchEvent(new Event('input')); \
         const c = document.getElementById('canvas-a'); const t = transform(c); \
         const sx = Math.floor(t.ox + ({x} + 0.5) * t.scale), sy = Math.floor(t.oy + ({y} + 0.5) * t.scale); \
         const i = ({y} * page.images.width + {x}) * 4; \
         const rgb = (d, k) => [d[k], d[k + 1], d[k + 2]]; \
         return [rgb(c.getContext('2d').getImageData(sx, sy, 1, 1).data, 0), \
                 rgb(page.images.dataA.data, i), rgb(page.images.dataB.data, i)];"
    );
    let v = browser.js(&script).await;
    (v[0].clone(), v[1].clone(), v[2].clone())
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_page_follows_saves_explains_pixels_and_recovers_from_broken_stages() {
    let dir = tempfile::tempdir().unwrap();
    scratch_sources(dir.path());
    let rust = repo().join("spirv/rust").display().to_string();
    let sources = dir.path().display().to_string();
    let args = ["showcase", "--a", &rust, "--b", "glsl", "--sources", &sources, "--validate"];
    let server = Server::start(
        &[&args[..], &["--width", "256", "--height", "144", "--preview-width", "128"]].concat(),
        dir.path(),
    );
    let browser = Browser::start(&dir.path().join("profile")).await;
    browser.client.goto(&server.url).await.unwrap();

    // Both images, at full size, and the verdict of identical sources.
    browser.wait_for(FIRST_RENDER, "return document.body.dataset.preview === 'false'").await;
    assert_eq!(browser.js("return [page.images.width, page.images.height]").await, serde_json::json!([256, 144]));
    assert_eq!(browser.text("verdict").await, "PASS");
    for canvas in ["canvas-a", "canvas-b"] {
        let drawn = format!(
            "const c = document.getElementById('{canvas}'); \
             const d = c.getContext('2d').getImageData(c.width / 2, c.height / 2, 1, 1).data; \
             return c.width > 100 && !(d[0] === 0x11 && d[1] === 0x11 && d[2] === 0x11);"
        );
        assert_eq!(browser.js(&drawn).await, Value::Bool(true), "{canvas} shows no image");
    }

    // A save to the scratch copy's miss stage: the page shows its preview, then the full size.
    let before = shown(&browser).await;
    let miss = dir.path().join("shaders-glsl/miss.rmiss");
    let saved = Instant::now();
    edit(&miss, MISS, HALF_MISS);
    browser.wait_for(SAVE_TO_PAGE, &format!("return Number(document.body.dataset.shown) > {before}")).await;
    let to_page = saved.elapsed();
    let said = browser.js("return Number(document.body.dataset.saveToPageMs)").await;
    println!(
        "save to page (preview, 128x72): {:.2} s by the test's clock, {said} ms by the page's",
        to_page.as_secs_f64()
    );
    browser.wait_for(FIRST_RENDER, "return document.body.dataset.preview === 'false'").await;
    assert_eq!(browser.text("verdict").await, "FAIL");
    assert!(browser.text("latency").await.starts_with("save → page"), "{}", browser.text("latency").await);

    // The wipe: A left of it, B right of it, at a background pixel where they differ.
    browser.client.find(Locator::Css("button[data-mode=wipe]")).await.unwrap().click().await.unwrap();
    let (right, a, b) = wipe_at(&browser, 0.98, (10, 5)).await;
    assert_ne!(a, b, "the planted miss must change the background");
    assert_eq!(right, a, "wipe at the right edge: pixel 10,5 shows A");
    let (left, _, _) = wipe_at(&browser, 0.02, (10, 5)).await;
    assert_eq!(left, b, "wipe at the left edge: pixel 10,5 shows B");

    // A click on that pixel explains it: the first sample's ray misses in both, and B's miss
    // stage describes another colour.
    click_pixel(&browser, 10, 5).await;
    browser.wait_for(FIRST_RENDER, "return document.querySelector('#explain-body .parting') !== null").await;
    let explained = browser.text("explain-body").await;
    assert!(explained.contains("pixel 10,5"), "{explained}");
    assert!(explained.contains("sample 0"), "{explained}");
    assert!(explained.contains("stage: B's miss"), "{explained}");
    wipe_at(&browser, 0.5, (10, 5)).await;
    let screenshot = browser.client.screenshot().await.unwrap();
    keep_screenshot(&screenshot);

    // A broken save: its error in the page, the last images kept; a good one recovers.
    let shown_before = shown(&browser).await;
    edit(&miss, HALF_MISS, BROKEN_MISS);
    browser.wait_for(SAVE_TO_PAGE, "return !document.getElementById('problem').hidden").await;
    let problem = browser.text("problem").await;
    assert!(problem.contains("does not build") && problem.contains("miss.rmiss"), "{problem}");
    assert_eq!(shown(&browser).await, shown_before, "a broken save keeps the last images");
    edit(&miss, BROKEN_MISS, MISS);
    browser.wait_for(SAVE_TO_PAGE, "return document.getElementById('problem').hidden").await;
    browser.wait_for(FIRST_RENDER, "return document.body.dataset.preview === 'false'").await;
    assert_eq!(browser.text("verdict").await, "PASS");

    // Anything outside the page and its renders is refused.
    for path in ["/Cargo.toml", "/render/1/../../Cargo.toml", "/render/999/a.png", "/render/1/secret.txt"] {
        browser.client.goto(&format!("{}{}", server.url.trim_end_matches('/'), path)).await.unwrap();
        let body = browser.client.find(Locator::Css("body")).await.unwrap().text().await.unwrap();
        assert!(body.contains("not found"), "{path}: {body}");
    }
    browser.close().await;
}

/// The screenshot goes to target/; `cargo xtask screenshot` makes this test put it in docs/.
fn keep_screenshot(png: &[u8]) {
    let image = image::load_from_memory(png).expect("a PNG screenshot");
    assert!(image.width() >= 1000, "a screenshot of the whole window: {}x{}", image.width(), image.height());
    std::fs::write(repo().join("target/view-screenshot.png"), png).unwrap();
    if std::env::var_os("TWINRAY_REFRESH_SCREENSHOT").is_some() {
        std::fs::write(repo().join("docs/images/view.png"), png).unwrap();
    }
}

/// Stage `name` of the hostile stages (`tests/hostile/stages/`), compiled into `dir`.
fn hostile_stage(name: &str, dir: &Path) -> std::path::PathBuf {
    let spv = dir.join(format!("{name}.spv"));
    let out = std::process::Command::new("glslangValidator")
        .args(["-V", "--target-env", "spirv1.4"])
        .arg(format!("-I{}", repo().join("shaders-glsl").display()))
        .arg("-o")
        .arg(&spv)
        .arg(repo().join("tests/hostile/stages").join(name))
        .output()
        .expect("glslangValidator (cargo xtask setup installs it)");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stdout));
    spv
}

#[test]
fn a_stage_that_never_returns_is_a_message_and_bad_requests_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let set = dir.path().join("set");
    std::fs::create_dir(&set).unwrap();
    for entry in std::fs::read_dir(repo().join("spirv/glsl")).unwrap() {
        let path = entry.unwrap().path();
        std::fs::copy(&path, set.join(path.file_name().unwrap())).unwrap();
    }
    let b = set.display().to_string();
    let size = ["--width", "64", "--height", "48", "--preview-width", "64"];
    // Run outside any checkout: set A is the embedded GLSL set, set B a folder, watched.
    // Lavapipe compiles a pipeline at its first trace, inside the deadline, and the hang below
    // lasts the whole deadline, one core spinning. On `sphere` (procedural shapes, shadows),
    // not cutout: what is checked is the server, and cutout's textured pipelines took 5.7 to
    // 6.1 s to compile from nothing on an idle 2-core machine (over 10 s in a clean-clone CI
    // run), which set the deadline at 30 s; sphere's take 0.55 s, so 10 s. The test took 81 s
    // alone with empty caches on cutout.
    let server =
        Server::start(&[&["sphere", "--a", "glsl", "--b", &b, "--gpu-timeout", "10"], &size[..]].concat(), dir.path());
    let idle = |s: &Value| s["status"] == "idle" && s["render"]["id"].as_u64().is_some();
    let state = server.wait_for(FIRST_RENDER, "the first render", idle);
    let live = state["live"].to_string();
    assert!(live.contains("the built-in modules") && live.contains("modules from disk"), "{live}");
    let id = state["render"]["id"].as_u64().unwrap();

    let (status, body) = server.get(&format!("/api/explain?render={id}&x=20&y=30"));
    assert_eq!(status, 200, "{body}");
    let report: Value = serde_json::from_str(&body).unwrap();
    assert_eq!(report["pixel"], serde_json::json!([20, 30]));
    let here = format!("127.0.0.1:{}", server.port);
    let refused = [
        ("GET", format!("/api/explain?render={id}&x=64&y=0"), "", 400, "outside render"),
        ("GET", format!("/api/explain?render={id}&x=a&y=0"), "", 400, "not a whole number"),
        ("GET", format!("/api/explain?render={id}&x=1"), "", 400, "missing y"),
        ("GET", "/api/explain?render=999&x=0&y=0".into(), "", 404, "no longer kept"),
        ("POST", "/api/view".into(), r#"{"frame": 1}"#, 400, "past the end"),
        ("POST", "/api/view".into(), "garbage", 400, "a view is"),
        ("POST", "/api/view".into(), r#"{"eye": [0, 0]}"#, 400, "a view is"),
        ("POST", "/api/view".into(), r#"{"eye": [0, 0.6, 0], "look_at": [0, 0.6, 0]}"#, 400, "must differ"),
        ("GET", "/etc/passwd".into(), "", 404, "not found"),
        ("GET", format!("/render/{id}/../../../etc/passwd"), "", 404, "not found"),
        ("GET", "/render/x/a.png".into(), "", 404, "not found"),
    ];
    for (method, path, body, code, needle) in refused {
        let (status, said) = server.request(method, &path, &here, body);
        assert_eq!(status, code, "{method} {path}: {said}");
        assert!(said.contains(needle), "{method} {path}: {said:?} does not say {needle:?}");
    }
    let (status, said) = server.request("GET", "/", "evil.example:80", "");
    assert_eq!(status, 403, "another host name (DNS rebinding) is refused: {said}");

    // Another camera: a render from there, and an explain of it from there too.
    let (status, said) = server.request("POST", "/api/view", &here, r#"{"eye": [0, 6, 7]}"#);
    assert_eq!(status, 202, "{said}");
    let moved = |s: &Value| s["status"] == "idle" && s["render"]["shot"]["eye"] == serde_json::json!([0.0, 6.0, 7.0]);
    let state = server.wait_for(FIRST_RENDER, "the render from the new camera", moved);
    let id = state["render"]["id"].as_u64().unwrap();
    let (status, body) = server.get(&format!("/api/explain?render={id}&x=20&y=30"));
    assert_eq!(status, 200, "{body}");
    let origin = serde_json::from_str::<Value>(&body).unwrap()["samples"][0]["origin"].clone();
    // The ray origin is the eye carried through the camera's f32 matrices: equal to rounding.
    let eye = [0.0, 6.0, 7.0];
    let near = (0..3).all(|i| (origin[i].as_f64().unwrap() - eye[i]).abs() < 1e-5);
    assert!(near, "{origin} is not the eye {eye:?}: explained from the camera of the render clicked");

    // The GPU-time ratio with its interval, and the null control's.
    let (status, said) = server.request("POST", "/api/timing", &here, "");
    assert_eq!(status, 202, "{said}");
    let timed = |s: &Value| s["timing"]["running"] == false && !s["timing"]["ab"].is_null();
    let state = server.wait_for(TIMING, "the timing", timed);
    let timing = &state["timing"];
    assert_eq!(timing["ab"]["placements"], 6, "{timing}");
    assert_eq!(timing["null"]["null_control"], true, "{timing}");
    let interval = &timing["ab"]["timing"];
    assert!(interval["low"].as_f64().unwrap() <= interval["high"].as_f64().unwrap(), "{interval}");

    // Set B's ray generation stage never returns: the page says so, the server goes on, and
    // putting the good module back recovers.
    let good = std::fs::read(set.join("raygen.spv")).unwrap();
    std::fs::copy(hostile_stage("loop.rgen", dir.path()), set.join("raygen.spv")).unwrap();
    let state = server.wait_for(FIRST_RENDER, "the stalled render's message", |s| !s["problem"].is_null());
    let text = state["problem"]["text"].as_str().unwrap();
    assert!(text.contains("did not finish in 10 s"), "{text}");
    assert_eq!(state["render"]["id"].as_u64(), Some(id), "the last good render stays");
    assert_eq!(server.get("/state").0, 200, "the server goes on");
    std::fs::write(set.join("raygen.spv"), &good).unwrap();
    let state =
        server.wait_for(FIRST_RENDER, "recovery", |s| s["problem"].is_null() && s["render"]["id"].as_u64() > Some(id));
    assert_eq!(state["render"]["report"]["pass"], true, "{state:#}");

    // A ray generation stage that writes nothing: a render, whose verdict says so.
    let id = state["render"]["id"].as_u64();
    std::fs::copy(hostile_stage("noop.rgen", dir.path()), set.join("raygen.spv")).unwrap();
    let state = server.wait_for(FIRST_RENDER, "the unwritten render", |s| s["render"]["id"].as_u64() > id);
    let failures = state["render"]["report"]["failures"].to_string();
    assert!(failures.contains("3072 pixels not written by set b"), "{failures}");
    assert_eq!(state["render"]["report"]["written_b"]["unwritten"], 3072);
}

/// A save to the scene file re-renders it; a broken one is shown, and the next good one
/// recovers, at the size `view` was given.
#[test]
fn the_scene_file_is_followed_too() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("scene.toml");
    std::fs::copy(repo().join("scenes/cutout.toml"), &scene).unwrap();
    let args = [scene.to_str().unwrap(), "--a", "glsl", "--b", "glsl", "--width", "32", "--height", "24"];
    let server = Server::start(&args, dir.path());
    let first = server.wait_for(FIRST_RENDER, "the first render", |s| s["status"] == "idle" && !s["render"].is_null());
    let id = first["render"]["id"].as_u64();
    edit(&scene, "eye = [0.0, 3.2, 8.5]", "eye = [0.0, 5.0, 8.5]");
    let moved =
        server.wait_for(FIRST_RENDER, "the edited scene", |s| s["render"]["id"].as_u64() > id && s["status"] == "idle");
    assert_eq!(moved["scene"]["eye"], serde_json::json!([0.0, 5.0, 8.5]));
    assert_eq!(moved["render"]["shot"]["width"], 32, "the size view was given holds");
    let id = moved["render"]["id"].as_u64();
    edit(&scene, "[camera]", "[camera");
    let broken = server.wait_for(FIRST_RENDER, "the broken scene", |s| !s["problem"].is_null());
    assert_eq!(broken["problem"]["what"], "scene", "{broken:#}");
    assert!(broken["problem"]["text"].as_str().unwrap().contains("scene.toml"), "{broken:#}");
    edit(&scene, "[camera", "[camera]");
    server.wait_for(FIRST_RENDER, "recovery", |s| s["problem"].is_null() && s["render"]["id"].as_u64() > id);
}

/// A moving scene: the frame asked for is rendered, and explained at that frame.
#[test]
fn a_moving_scene_renders_and_explains_the_frame_asked_for() {
    let dir = tempfile::tempdir().unwrap();
    let size = ["--width", "48", "--height", "27", "--preview-width", "48"];
    let server = Server::start(&[&["orbit", "--a", "glsl", "--b", "glsl"], &size[..]].concat(), dir.path());
    let here = format!("127.0.0.1:{}", server.port);
    let state = server.wait_for(FIRST_RENDER, "the first render", |s| s["status"] == "idle" && !s["render"].is_null());
    assert_eq!(state["scene"]["frames"], 48);
    let (status, said) = server.request("POST", "/api/view", &here, r#"{"frame": 47}"#);
    assert_eq!(status, 202, "{said}");
    let at = |s: &Value| s["status"] == "idle" && s["render"]["shot"]["frame"] == 47;
    let state = server.wait_for(FIRST_RENDER, "frame 47", at);
    assert_eq!(state["render"]["report"]["pass"], true, "the same set twice agrees: {state:#}");
    let id = state["render"]["id"].as_u64().unwrap();
    let (status, body) = server.get(&format!("/api/explain?render={id}&x=24&y=13"));
    assert_eq!(status, 200, "{body}");
    assert_eq!(serde_json::from_str::<Value>(&body).unwrap()["frame"], 47);
    let (status, said) = server.request("POST", "/api/view", &here, r#"{"frame": 48}"#);
    assert_eq!((status, said.contains("past the end")), (400, true), "{said}");
}

#[test]
fn bad_view_arguments_get_one_line_and_exit_2() {
    assert_bad_input(&["view", "--a", "/no/such/set"], &["/no/such/set"]);
    assert_bad_input(&["view", "--sources", "/no/such/checkout"], &["--sources", "/no/such/checkout"]);
    assert_bad_input(&["view", "no-such-scene"], &["no-such-scene"]);
    assert_bad_input(&["view", "--width", "0"], &["width"]);
    assert_bad_input(&["view", "--bind", "not-an-address"], &["--bind"]);
}
