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
