#![no_main]
// See twinray_host::fuzz::gltf: what it feeds the bytes to, and what counts as a finding. The
// mutator (twinray_host::fuzz::mutate) edits the JSON as JSON and a GLB's binary chunk as bytes,
// and writes the container back whole; libFuzzer's own mutator does the byte-level edits.
use twinray_host::fuzz::mutate::{self, Rng};

libfuzzer_sys::fuzz_target!(|data: &[u8]| twinray_host::fuzz::gltf(data));

libfuzzer_sys::fuzz_mutator!(|data: &mut [u8], size: usize, max_size: usize, seed: u32| {
    let mut rng = Rng::new(seed as u64);
    let mut bytes = |chunk: &mut Vec<u8>, rng: &mut Rng| {
        let len = chunk.len();
        chunk.resize(len + 64 + rng.below(256), 0);
        let capacity = chunk.len();
        let kept = libfuzzer_sys::fuzzer_mutate(chunk, len, capacity);
        chunk.truncate(kept);
    };
    let out = mutate::gltf(&data[..size], &mut rng, &mut bytes);
    if out.len() > max_size {
        return libfuzzer_sys::fuzzer_mutate(data, size, max_size);
    }
    data[..out.len()].copy_from_slice(&out);
    out.len()
});
