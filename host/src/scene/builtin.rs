//! The built-in scenes: every file of `scenes/` and the mesh files they use, embedded by
//! `host/build.rs`, so a new scene file is a built-in scene without a line of code.

include!(concat!(env!("OUT_DIR"), "/builtin_scenes.rs"));

/// The scene `twinray render` and `compare` use when none is named.
pub const DEFAULT_SCENE: &str = "spheres";
