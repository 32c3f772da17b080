#![no_main]
// See twinray_host::fuzz::obj: what it feeds the bytes to, and what counts as a finding.
libfuzzer_sys::fuzz_target!(|data: &[u8]| twinray_host::fuzz::obj(data));
