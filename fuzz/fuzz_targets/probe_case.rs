#![no_main]
// See twinray_host::fuzz::probe_case: what it feeds the bytes to, and what counts as a finding.
libfuzzer_sys::fuzz_target!(|data: &[u8]| twinray_host::fuzz::probe_case(data));
