//! The process's peak host memory, as the kernel counts it: what a command reports so that
//! a model's cost in memory can be read off a run (docs/gltf.md, "Peak memory").

/// The most resident memory the process has held, in bytes (Linux's `VmHWM`); `None` where
/// the system does not say.
pub fn peak_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    high_water(&status)
}

/// `VmHWM` of a `/proc/PID/status` text, in bytes.
fn high_water(status: &str) -> Option<u64> {
    let line = status.lines().find_map(|l| l.strip_prefix("VmHWM:"))?;
    let kib: u64 = line.trim().strip_suffix("kB")?.trim().parse().ok()?;
    Some(kib * 1024)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_high_water_mark_is_read_in_bytes() {
        let status = "Name:\ttwinray\nVmPeak:\t  900 kB\nVmHWM:\t  123456 kB\nVmRSS:\t 100 kB\n";
        assert_eq!(high_water(status), Some(123456 * 1024));
        assert_eq!(high_water("VmRSS:\t 100 kB\n"), None);
        assert_eq!(high_water("VmHWM:\t lots\n"), None);
    }

    #[test]
    fn this_process_has_a_peak_at_least_what_it_holds() {
        if cfg!(target_os = "linux") {
            let held = std::hint::black_box(vec![1u8; 64 << 20]);
            let peak = peak_bytes().expect("Linux reports VmHWM");
            assert!(peak >= 64 << 20, "peak {peak} with 64 MiB held");
            drop(held);
        }
    }
}
