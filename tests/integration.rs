//! The integration tests on lavapipe, one harness: each module is the file of one subject, its
//! own comment saying what it checks (`cargo test --release -p twinray-tests --test
//! integration parity::` runs one). `golden.rs` and `timing.rs` are harnesses of their own.

mod alpha_texture;
mod animation;
mod assimp;
mod box_exits;
mod callables;
mod compute;
mod condition;
mod crosscheck;
mod cutout;
mod docs;
mod explain;
mod gltf_clips;
mod gltf_copies;
mod layout;
mod libraries;
mod merged_meshes;
mod modules;
mod origin;
mod orthographic;
mod parity;
mod pipeline;
mod probe;
mod properties;
mod punctual_lights;
mod ray_query;
mod rays;
mod reach;
mod references;
mod render_sets;
mod retrace;
mod scenes;
mod shared_blases;
mod single_sided;
mod stability;
mod textures;
mod thin_torus;
mod validation;
