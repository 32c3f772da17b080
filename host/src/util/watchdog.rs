//! A deadline on work that cannot be waited on with a timeout: a driver call that compiles a
//! user's stages may never return (one damaged module in 200 hung lavapipe's compiler), and
//! nothing can take such a call back. Past its deadline the process prints one line naming
//! what was being done and ends with [`EXIT_STALLED`], without running destructors (a thread
//! of the driver is still inside the call). Fence waits have their own deadline
//! (`vk::commands`) and end in an error instead.

use super::activity;
use std::collections::BTreeMap;
use std::io::Write;
use std::sync::{Condvar, Mutex, OnceLock};
use std::time::{Duration, Instant};

/// Exit code of a process whose GPU work did not finish in time, or whose device was lost.
pub const EXIT_STALLED: i32 = 3;

#[derive(Default)]
struct Armed {
    next_id: u64,
    /// Deadline, what was being done and the limit, by guard.
    by_id: BTreeMap<u64, (Instant, String, Duration)>,
}

struct Watchdog {
    armed: Mutex<Armed>,
    changed: Condvar,
}

fn watchdog() -> &'static Watchdog {
    static DOG: OnceLock<&'static Watchdog> = OnceLock::new();
    DOG.get_or_init(|| {
        let dog: &'static Watchdog =
            Box::leak(Box::new(Watchdog { armed: Mutex::new(Armed::default()), changed: Condvar::new() }));
        let spawned = std::thread::Builder::new().name("twinray-watchdog".into()).spawn(move || dog.watch());
        if let Err(e) = spawned {
            log::warn!("no deadline on driver calls: the watchdog thread did not start ({e})");
        }
        dog
    })
}

impl Watchdog {
    fn watch(&self) {
        let mut armed = self.armed.lock().unwrap_or_else(|p| p.into_inner());
        loop {
            let first = armed.by_id.values().min_by_key(|(at, ..)| *at).cloned();
            match first {
                None => armed = self.changed.wait(armed).unwrap_or_else(|p| p.into_inner()),
                Some((at, what, limit)) if Instant::now() >= at => expire(&what, limit),
                Some((at, ..)) => {
                    let wait = at.saturating_duration_since(Instant::now());
                    armed = self.changed.wait_timeout(armed, wait).unwrap_or_else(|p| p.into_inner()).0;
                }
            }
        }
    }
}

/// Prints the line and ends the process now: the stalled call never returns, so neither
/// unwinding nor `exit` (whose handlers would join the driver's threads) can end it.
fn expire(what: &str, limit: Duration) -> ! {
    let _ = writeln!(
        std::io::stderr(),
        "error: {what} did not finish in {} s: a driver call or a stage may never return (if it is only slow, raise --gpu-timeout)",
        seconds(limit)
    );
    let _ = std::io::stdout().flush();
    // SAFETY: _exit ends the process at once; nothing after it runs.
    unsafe { libc::_exit(EXIT_STALLED) }
}

/// A limit in words: "10", "0.5".
pub fn seconds(limit: Duration) -> String {
    let s = limit.as_secs_f64();
    if s.fract() == 0.0 {
        format!("{s:.0}")
    } else {
        format!("{s}")
    }
}

/// While alive, the process ends if this thread's current work (see `activity`) has not
/// finished within `limit`.
#[must_use = "the deadline is lifted when the guard is dropped"]
pub struct Guard {
    id: u64,
}

/// Arms a deadline of `limit` on what this thread is doing now.
pub fn arm(limit: Duration) -> Guard {
    let dog = watchdog();
    let mut armed = dog.armed.lock().unwrap_or_else(|p| p.into_inner());
    let id = armed.next_id;
    armed.next_id += 1;
    let at = Instant::now().checked_add(limit).unwrap_or_else(|| Instant::now() + Duration::from_secs(1 << 40));
    armed.by_id.insert(id, (at, activity::describe(), limit));
    dog.changed.notify_all();
    Guard { id }
}

impl Drop for Guard {
    fn drop(&mut self) {
        let dog = watchdog();
        dog.armed.lock().unwrap_or_else(|p| p.into_inner()).by_id.remove(&self.id);
        dog.changed.notify_all();
    }
}
