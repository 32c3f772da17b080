//! What twinray is doing now, in words, for the one line that a deadline or a crash ends
//! with: "twinray render: the trace of glsl,raygen=loop.spv". Each thread keeps its own stack
//! of descriptions (a command pushes its name, a render the set it traces); the latest change
//! of any thread is also copied into a fixed buffer that a signal handler can read without
//! allocating or locking (see `crash`).

use std::cell::RefCell;
use std::sync::atomic::{AtomicU8, Ordering};
use std::sync::Mutex;

thread_local! {
    static STACK: RefCell<Vec<String>> = const { RefCell::new(Vec::new()) };
}

/// Bytes of the description a signal handler reads; longer ones are cut.
const SNAPSHOT_BYTES: usize = 1024;
/// The latest description of any thread, NUL-terminated. Atomic bytes so that a reader racing
/// a writer sees a garbled line at worst, never undefined behaviour.
static SNAPSHOT: [AtomicU8; SNAPSHOT_BYTES] = [const { AtomicU8::new(0) }; SNAPSHOT_BYTES];
/// Writers of the snapshot take turns.
static WRITER: Mutex<()> = Mutex::new(());

/// While alive, `what` is the innermost thing this thread is doing.
#[must_use = "the description is dropped with the guard"]
pub struct Doing {
    // Not Send: it pops the stack of the thread that pushed it.
    _not_send: std::marker::PhantomData<*const ()>,
}

/// Says that this thread is now doing `what`, until the guard is dropped.
pub fn doing(what: impl Into<String>) -> Doing {
    STACK.with(|s| s.borrow_mut().push(what.into()));
    publish();
    Doing { _not_send: std::marker::PhantomData }
}

impl Drop for Doing {
    fn drop(&mut self) {
        STACK.with(|s| s.borrow_mut().pop());
        publish();
    }
}

/// What this thread is doing, outermost first: "twinray compare: the trace of rust".
pub fn describe() -> String {
    let text = STACK.with(|s| s.borrow().join(": "));
    if text.is_empty() {
        "GPU work".into()
    } else {
        text
    }
}

fn publish() {
    let text = describe();
    let _turn = WRITER.lock().unwrap_or_else(|p| p.into_inner());
    let bytes = text.as_bytes();
    let n = bytes.len().min(SNAPSHOT_BYTES - 1);
    for (slot, &b) in SNAPSHOT.iter().zip(&bytes[..n]) {
        slot.store(b, Ordering::Relaxed);
    }
    SNAPSHOT[n].store(0, Ordering::Release);
}

/// Copies the latest description into `out` and returns its length; touches no lock and
/// allocates nothing, so a signal handler may call it.
pub(crate) fn snapshot(out: &mut [u8; SNAPSHOT_BYTES]) -> usize {
    let mut n = 0;
    while n < SNAPSHOT_BYTES {
        let b = SNAPSHOT[n].load(Ordering::Acquire);
        if b == 0 {
            break;
        }
        out[n] = b;
        n += 1;
    }
    n
}

/// A buffer for [`snapshot`].
pub(crate) const fn snapshot_buffer() -> [u8; SNAPSHOT_BYTES] {
    [0; SNAPSHOT_BYTES]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nests_and_unwinds_per_thread() {
        let _outer = doing("twinray render");
        {
            let _inner = doing("the trace of rust");
            assert_eq!(describe(), "twinray render: the trace of rust");
        }
        assert_eq!(describe(), "twinray render");
        let other = std::thread::spawn(describe).join().unwrap();
        assert_eq!(other, "GPU work", "another thread has its own stack");
        let mut buf = snapshot_buffer();
        let n = snapshot(&mut buf);
        assert!(n > 0 && std::str::from_utf8(&buf[..n]).is_ok());
    }
}
