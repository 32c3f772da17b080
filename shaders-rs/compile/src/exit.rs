//! What the exit status of a `twinray` command means, for the loops that run one per save
//! (`cargo xtask watch`, `twinray view`): the codes are `twinray`'s (see its `main.rs`).

use std::process::ExitStatus;

/// The words for a `twinray compare` (or `explain`) that ended in `status`, beyond what it
/// printed: none when it compared (0: pass, 1: fail).
pub fn exit_words(status: ExitStatus) -> Option<String> {
    use std::os::unix::process::ExitStatusExt;
    match (status.code(), status.signal()) {
        (Some(0 | 1), _) => None,
        (Some(2), _) => Some("the sets or the scene were refused (see the error above); fix and save again".into()),
        (Some(3), _) => {
            Some("a stage did not finish in time, or the device was lost (see above); fix and save again".into())
        }
        (Some(4), _) => Some("the driver crashed on the new modules (see above); fix and save again".into()),
        (Some(code), _) => Some(format!("twinray failed with exit code {code} (see above)")),
        (None, Some(signal)) => Some(format!("twinray was killed by signal {signal}; fix and save again")),
        (None, None) => Some(format!("twinray ended with {status}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_way_a_compare_ends_is_a_verdict() {
        use std::os::unix::process::ExitStatusExt;
        let ended = |raw: i32| exit_words(ExitStatus::from_raw(raw));
        assert_eq!(ended(0), None);
        assert_eq!(ended(1 << 8), None, "a failed parity prints its own verdict");
        assert!(ended(2 << 8).unwrap().contains("refused"));
        assert!(ended(3 << 8).unwrap().contains("did not finish in time"));
        assert!(ended(4 << 8).unwrap().contains("crashed"));
        // A raw wait status of 11: killed by SIGSEGV, with no handler to report it.
        assert!(ended(11).unwrap().contains("killed by signal 11"));
    }
}
