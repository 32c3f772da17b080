#![no_main]
// See twinray::fuzz::gltf: what it feeds the bytes to, and what counts as a finding.
libfuzzer_sys::fuzz_target!(|data: &[u8]| twinray::fuzz::gltf(data));
