//! One line instead of a silent death when the process crashes. A damaged or hostile module
//! can crash a driver while it compiles or runs a user's stages (6 of 200 damaged modules
//! crashed lavapipe with SIGSEGV); the handler writes what twinray was doing (see `activity`)
//! to stderr and ends the process with [`EXIT_CRASHED`]. It only copies bytes, calls
//! `write` and `_exit`, which is all a signal handler may do.
//!
//! A crash that corrupts the stack the handler would run on (a stack overflow in a driver
//! thread, which has no alternate signal stack) still ends the process by the signal.

use super::activity;
use std::sync::atomic::{AtomicBool, Ordering};

/// Exit code of a process that crashed (a fatal signal) while doing GPU work.
pub const EXIT_CRASHED: i32 = 4;

const SIGNALS: [(libc::c_int, &[u8]); 5] = [
    (libc::SIGSEGV, b"SIGSEGV"),
    (libc::SIGBUS, b"SIGBUS"),
    (libc::SIGILL, b"SIGILL"),
    (libc::SIGFPE, b"SIGFPE"),
    (libc::SIGABRT, b"SIGABRT"),
];

/// Installs the handler for fatal signals; later calls do nothing. For programs (the
/// `twinray` command); a library user keeps their own handlers.
pub fn report_crashes() {
    static INSTALLED: AtomicBool = AtomicBool::new(false);
    if INSTALLED.swap(true, Ordering::SeqCst) {
        return;
    }
    for (signal, _) in SIGNALS {
        // SAFETY: a zeroed sigaction with a handler of the right type; SA_ONSTACK uses the
        // alternate stack Rust gives the main thread, so a stack overflow there still reports.
        unsafe {
            let mut action: libc::sigaction = std::mem::zeroed();
            action.sa_sigaction = on_signal as extern "C" fn(libc::c_int) as libc::sighandler_t;
            action.sa_flags = libc::SA_ONSTACK;
            libc::sigemptyset(&mut action.sa_mask);
            libc::sigaction(signal, &action, std::ptr::null_mut());
        }
    }
}

extern "C" fn on_signal(signal: libc::c_int) {
    // Several driver threads may fault at once: the first reports and ends the process, the
    // others wait for that (pause is async-signal-safe).
    static REPORTING: AtomicBool = AtomicBool::new(false);
    if REPORTING.swap(true, Ordering::SeqCst) {
        loop {
            // SAFETY: pause only waits for a signal.
            unsafe { libc::pause() };
        }
    }
    let name = SIGNALS.iter().find(|(s, _)| *s == signal).map_or(&b"a fatal signal"[..], |(_, n)| n);
    let mut doing = activity::snapshot_buffer();
    let n = activity::snapshot(&mut doing);
    let parts: [&[u8]; 5] = [
        b"error: twinray crashed (",
        name,
        b") while ",
        &doing[..n],
        b": a driver or a stage from disk is the likely cause\n",
    ];
    for part in parts {
        // SAFETY: write(2) on stderr with a live buffer is async-signal-safe.
        unsafe { libc::write(2, part.as_ptr().cast(), part.len()) };
    }
    // SAFETY: _exit is async-signal-safe and ends the process.
    unsafe { libc::_exit(EXIT_CRASHED) }
}

thread_local! {
    /// Whether this thread runs inside [`catching`], whose panics are reported as errors.
    static CATCHING: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Installs a panic hook that stays quiet inside [`catching`] (the error it returns says what
/// happened, in one line) and prints as Rust's own elsewhere; later calls do nothing.
pub fn quiet_caught_panics() {
    static INSTALLED: AtomicBool = AtomicBool::new(false);
    if INSTALLED.swap(true, Ordering::SeqCst) {
        return;
    }
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        if !CATCHING.with(|c| c.get()) {
            default(info);
        }
    }));
}

/// Runs `f`, turning a panic in it into `Err` with the panic's message: reading a file from a
/// stranger must end in an error that names the file, never in a crash without a message,
/// even where a bug (twinray's or a crate's) panics on it.
pub fn catching<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    let outer = CATCHING.with(|c| c.replace(true));
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(f));
    CATCHING.with(|c| c.set(outer));
    result.map_err(|panic| {
        let text =
            panic.downcast_ref::<&str>().map(|s| s.to_string()).or_else(|| panic.downcast_ref::<String>().cloned());
        text.unwrap_or_else(|| "a panic without a message".into())
    })
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_panic_inside_catching_is_an_error_with_its_message() {
        super::quiet_caught_panics();
        assert_eq!(super::catching(|| 7), Ok(7));
        let index = std::hint::black_box(9);
        let caught = super::catching(|| [1, 2, 3][index]).unwrap_err();
        assert!(caught.contains("index out of bounds"), "{caught}");
        assert_eq!(super::catching(|| panic!("with {}", "words")).unwrap_err(), "with words");
    }
}
