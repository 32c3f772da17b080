//! The binary's and the library's tests that need no harness of their own, one harness: each
//! module is the file of one subject, its own comment saying what it checks (`cargo test
//! --release -p twinray --test commands cli::` runs one). `bench.rs` (long), `hostile_stages.rs`
//! (GPU deadlines, timed) and `view.rs` (a browser) are harnesses of their own.

mod alpha_ties;
mod architecture;
mod bisect;
mod bundle_script;
mod cli;
mod crosscheck_cli;
mod disk_sets;
mod doc_words;
mod explain_cli;
mod features;
mod frames_cli;
mod fuzz_seeds;
mod gltf_cli;
mod gltf_time;
mod history_words;
mod hostile;
mod inspect_cli;
mod install;
mod own_stages;
mod own_stages_tutorial;
mod peak_memory;
mod pipeline_cache;
mod probe_cli;
mod reference_ambiguity;
mod reference_cache;
mod reports;
mod set_loading;
mod stage_bench;
