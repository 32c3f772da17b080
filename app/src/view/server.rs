//! The page's HTTP routes. It serves its own assets (embedded in the binary), the images of
//! the renders it made, its state as server-sent events, and three requests: explain a pixel,
//! show another frame or camera, and time the sets. Anything else is a 404; a bad request is
//! a 4xx with a message.

use super::jobs::{Failed, Shot};
use super::live::{Live, Trigger};
use axum::extract::{Path, Query, State};
use axum::http::{header, StatusCode};
use axum::response::sse::{Event, KeepAlive, Sse};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::{Json, Router};
use std::collections::HashMap;
use std::sync::Arc;
use tokio::sync::mpsc::UnboundedSender;
use tokio_stream::wrappers::WatchStream;
use tokio_stream::StreamExt;

const INDEX: &str = include_str!("assets/index.html");
const SCRIPT: &str = include_str!("assets/app.js");
const STYLE: &str = include_str!("assets/app.css");

/// What every handler shares.
pub struct App {
    pub live: Arc<Live>,
    pub triggers: UnboundedSender<Trigger>,
    /// Whether requests must name this machine (a page on another site cannot reach the
    /// server through a name it controls: DNS rebinding).
    pub loopback_only: bool,
}

type Shared = State<Arc<App>>;

pub fn router(app: Arc<App>) -> Router {
    Router::new()
        .route("/", get(|| async { asset("text/html; charset=utf-8", INDEX) }))
        .route("/app.js", get(|| async { asset("text/javascript; charset=utf-8", SCRIPT) }))
        .route("/app.css", get(|| async { asset("text/css; charset=utf-8", STYLE) }))
        .route("/events", get(events))
        .route("/state", get(state))
        .route("/render/{id}/{name}", get(image))
        .route("/api/explain", get(explain))
        .route("/api/view", post(view))
        .route("/api/timing", post(timing))
        .fallback(|| async {
            refuse(StatusCode::NOT_FOUND, "not found: twinray view serves its page and its renders only")
        })
        .layer(axum::middleware::from_fn_with_state(app.clone(), check_host))
        .with_state(app)
}

fn asset(kind: &'static str, body: &'static str) -> Response {
    ([(header::CONTENT_TYPE, kind), (header::CACHE_CONTROL, "no-store")], body).into_response()
}

fn refuse(status: StatusCode, message: impl Into<String>) -> Response {
    (status, [(header::CONTENT_TYPE, "text/plain; charset=utf-8")], message.into()).into_response()
}

/// Refuses a request for another host name when serving on loopback only.
async fn check_host(State(app): Shared, request: axum::extract::Request, next: axum::middleware::Next) -> Response {
    let host = request.headers().get(header::HOST).and_then(|h| h.to_str().ok()).unwrap_or_default();
    if app.loopback_only && !is_loopback_name(host) {
        return refuse(
            StatusCode::FORBIDDEN,
            format!("host {host:?} is not this machine (twinray view serves loopback)"),
        );
    }
    next.run(request).await
}

/// "localhost:8080", "127.0.0.1", "[::1]:7878": names of this machine, any port.
fn is_loopback_name(host: &str) -> bool {
    let name = match host.strip_prefix('[') {
        Some(rest) => rest.split(']').next().unwrap_or_default(),
        None => host.rsplit_once(':').map_or(host, |(name, _)| name),
    };
    matches!(name, "localhost" | "::1") || name.parse::<std::net::Ipv4Addr>().is_ok_and(|ip| ip.is_loopback())
}

async fn state(State(app): Shared) -> Response {
    Json(app.live.store.get()).into_response()
}

/// The state, once now and again at every change.
async fn events(State(app): Shared) -> impl IntoResponse {
    let stream = WatchStream::new(app.live.store.subscribe()).map(|state| {
        Event::default().event("state").json_data(&state).map_err(|e| std::io::Error::other(e.to_string()))
    });
    Sse::new(stream).keep_alive(KeepAlive::default())
}

async fn image(State(app): Shared, Path((id, name)): Path<(String, String)>) -> Response {
    let Ok(id) = id.parse::<u64>() else {
        return refuse(StatusCode::NOT_FOUND, "not found: renders are numbered");
    };
    match app.live.store.image(id, &name) {
        Some(png) => ([(header::CONTENT_TYPE, "image/png"), (header::CACHE_CONTROL, "no-store")], png).into_response(),
        None => refuse(StatusCode::NOT_FOUND, format!("not found: render {id} has no {name:?} (or is no longer kept)")),
    }
}

/// A whole number from the query, or what was wrong with it.
fn number<T: std::str::FromStr>(query: &HashMap<String, String>, key: &str) -> Result<T, String> {
    let text = query.get(key).ok_or_else(|| format!("missing {key}"))?;
    text.trim().parse().map_err(|_| format!("{key}={text:?} is not a whole number"))
}

/// Render N and pixel (X, Y) of `render=N&x=X&y=Y`.
fn pixel_of(query: &HashMap<String, String>) -> Result<(u64, u32, u32), String> {
    Ok((number(query, "render")?, number(query, "x")?, number(query, "y")?))
}

/// `GET /api/explain?render=N&x=X&y=Y`: every ray of pixel (X, Y) of render N.
async fn explain(State(app): Shared, Query(query): Query<HashMap<String, String>>) -> Response {
    let (id, x, y) = match pixel_of(&query) {
        Ok(asked) => asked,
        Err(e) => return refuse(StatusCode::BAD_REQUEST, e),
    };
    let Some(shot) = app.live.store.shot(id) else {
        return refuse(StatusCode::NOT_FOUND, format!("render {id} is no longer kept: click the image shown now"));
    };
    if x >= shot.width || y >= shot.height {
        let (w, h) = (shot.width, shot.height);
        return refuse(StatusCode::BAD_REQUEST, format!("pixel {x},{y} is outside render {id} ({w}x{h})"));
    }
    let (a, b) = app.live.specs();
    match app.live.jobs.explain(app.live.scene.as_deref(), (&a, &b), &shot, (x, y)).await {
        Ok(report) => Json(report).into_response(),
        Err(Failed(text)) => refuse(StatusCode::UNPROCESSABLE_ENTITY, text),
    }
}

/// What `POST /api/view` takes: a frame, a camera, or both (missing ones keep the scene's).
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct ViewRequest {
    #[serde(default)]
    frame: u32,
    eye: Option<[f32; 3]>,
    look_at: Option<[f32; 3]>,
}

async fn view(State(app): Shared, body: String) -> Response {
    let request: ViewRequest = match serde_json::from_str(&body) {
        Ok(r) => r,
        Err(e) => {
            return refuse(StatusCode::BAD_REQUEST, format!("a view is {{\"frame\", \"eye\", \"look_at\"}}: {e}"))
        }
    };
    let state = app.live.store.get();
    let frames = state.scene.frames;
    if request.frame >= frames {
        let f = request.frame;
        return refuse(StatusCode::BAD_REQUEST, format!("frame {f} is past the end (0 to {})", frames - 1));
    }
    let finite = |p: &Option<[f32; 3]>| p.is_none_or(|p| p.iter().all(|v| v.is_finite()));
    if !finite(&request.eye) || !finite(&request.look_at) {
        return refuse(StatusCode::BAD_REQUEST, "eye and look_at are three finite numbers each");
    }
    let eye = request.eye.unwrap_or(state.scene.eye);
    let target = request.look_at.unwrap_or(state.scene.target);
    if eye == target {
        return refuse(StatusCode::BAD_REQUEST, "eye and look_at must differ");
    }
    let (width, height) = (state.scene.width, state.scene.height);
    let shot = Shot { width, height, frame: request.frame, eye: request.eye, look_at: request.look_at };
    let _ = app.triggers.send(Trigger::View(shot));
    StatusCode::ACCEPTED.into_response()
}

async fn timing(State(app): Shared) -> Response {
    if app.live.store.get().render.is_none() {
        return refuse(StatusCode::CONFLICT, "nothing rendered yet to time");
    }
    let _ = app.triggers.send(Trigger::Timing);
    StatusCode::ACCEPTED.into_response()
}

#[cfg(test)]
mod tests {
    #[test]
    fn only_names_of_this_machine_are_loopback() {
        for host in ["localhost:8080", "localhost", "127.0.0.1:7878", "127.0.0.5", "[::1]:7878"] {
            assert!(super::is_loopback_name(host), "{host}");
        }
        for host in ["evil.example:7878", "10.0.0.2:80", "", "localhost.evil.example", "[::2]:1"] {
            assert!(!super::is_loopback_name(host), "{host}");
        }
    }
}
