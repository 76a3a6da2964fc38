//! Stopping a run from outside: an interrupt (Ctrl-C) and a time limit.
//!
//! Every long loop of the solvers — time steps, parameter points of sweeps and maps, the steps of
//! a time-domain check — calls [`check`] once per pass. It costs two atomic loads and, only when a
//! time limit is set, one clock read. When a stop is requested the loop returns
//! [`SolveError::Stopped`] with where it was, and the caller writes what it has computed (the
//! dynamic audit, the rod and plane observers' records).
//!
//! The interrupt and [`set_time_limit`] are global to the process (one user, one run); [`reset`]
//! clears them. [`with_time_limit`] bounds only the calling thread (and the threads a solver
//! spawns from it, which inherit the deadline): the fuzz campaign bounds each of its scenes so,
//! while other work goes on.

use std::cell::Cell;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Mutex, OnceLock};
use std::time::{Duration, Instant};

use crate::error::SolveError;

static INTERRUPTED: AtomicBool = AtomicBool::new(false);
/// The deadline in nanoseconds after [`origin`]; `u64::MAX` for none.
static DEADLINE: AtomicU64 = AtomicU64::new(u64::MAX);
/// The time limit in milliseconds, for the message.
static LIMIT_MS: AtomicU64 = AtomicU64::new(0);

thread_local! {
    /// This thread's own deadline and its time limit (for the message).
    static LOCAL: Cell<Option<(Instant, Duration)>> = const { Cell::new(None) };
}

/// The calling thread's own deadline (for a solver that spawns threads: pass it to
/// [`with_deadline`] in each).
pub fn current_deadline() -> Option<(Instant, Duration)> {
    LOCAL.with(Cell::get)
}

/// Runs `f` with `deadline` as the calling thread's own deadline, then restores the previous one.
pub fn with_deadline<R>(deadline: Option<(Instant, Duration)>, f: impl FnOnce() -> R) -> R {
    let previous = LOCAL.with(|c| c.replace(deadline));
    struct Restore(Option<(Instant, Duration)>);
    impl Drop for Restore {
        fn drop(&mut self) {
            LOCAL.with(|c| c.set(self.0));
        }
    }
    let _restore = Restore(previous);
    f()
}

/// Runs `f` with a time limit from now on the calling thread only.
pub fn with_time_limit<R>(limit: Duration, f: impl FnOnce() -> R) -> R {
    with_deadline(Some((Instant::now() + limit, limit)), f)
}

fn origin() -> Instant {
    static ORIGIN: OnceLock<Instant> = OnceLock::new();
    *ORIGIN.get_or_init(Instant::now)
}

static DONE: AtomicU64 = AtomicU64::new(0);
static TOTAL: AtomicU64 = AtomicU64::new(0);
static LABEL: Mutex<&'static str> = Mutex::new("");

/// Records the progress of the running loop (`label`: "steps", "grid rows", …): two atomic
/// stores, and a lock only when the label changes. A front end reads it with [`progress`].
#[inline]
pub fn report_progress(label: &'static str, done: u64, total: u64) {
    if let Ok(mut l) = LABEL.lock() {
        if *l != label {
            *l = label;
        }
    }
    TOTAL.store(total, Ordering::Relaxed);
    DONE.store(done, Ordering::Relaxed);
}

/// The last progress recorded: (label, done, total).
pub fn progress() -> (&'static str, u64, u64) {
    let label = LABEL.lock().map(|l| *l).unwrap_or("");
    (
        label,
        DONE.load(Ordering::Relaxed),
        TOTAL.load(Ordering::Relaxed),
    )
}

/// Requests a stop (e.g. from a Ctrl-C handler): every running loop stops at its next check.
pub fn interrupt() {
    INTERRUPTED.store(true, Ordering::SeqCst);
}

/// Sets a time limit from now (`None`: no limit).
pub fn set_time_limit(limit: Option<Duration>) {
    let start = origin();
    match limit {
        Some(d) => {
            let at = (Instant::now() + d).saturating_duration_since(start);
            let nanos = u64::try_from(at.as_nanos()).unwrap_or(u64::MAX - 1);
            LIMIT_MS.store(
                u64::try_from(d.as_millis()).unwrap_or(u64::MAX),
                Ordering::SeqCst,
            );
            DEADLINE.store(nanos, Ordering::SeqCst);
        }
        None => DEADLINE.store(u64::MAX, Ordering::SeqCst),
    }
}

/// Clears the interrupt and the time limit.
pub fn reset() {
    INTERRUPTED.store(false, Ordering::SeqCst);
    DEADLINE.store(u64::MAX, Ordering::SeqCst);
}

/// Why the run must stop, if it must.
pub fn stop_reason() -> Option<String> {
    if INTERRUPTED.load(Ordering::Relaxed) {
        return Some("interrupted (Ctrl-C)".into());
    }
    let deadline = DEADLINE.load(Ordering::Relaxed);
    if deadline != u64::MAX {
        let now = Instant::now()
            .saturating_duration_since(origin())
            .as_nanos();
        if now >= u128::from(deadline) {
            let ms = LIMIT_MS.load(Ordering::Relaxed);
            return Some(format!(
                "the time limit of {} s was reached",
                ms as f64 / 1000.0
            ));
        }
    }
    if let Some((deadline, limit)) = current_deadline() {
        if Instant::now() >= deadline {
            return Some(format!(
                "the time limit of {} s was reached",
                limit.as_secs_f64()
            ));
        }
    }
    None
}

/// `Err(SolveError::Stopped)` when a stop was requested; `at` says where the loop is (called only
/// then).
#[inline]
pub fn check(at: impl FnOnce() -> String) -> Result<(), SolveError> {
    match stop_reason() {
        None => Ok(()),
        Some(reason) => Err(SolveError::Stopped { at: at(), reason }),
    }
}

#[cfg(test)]
mod tests {
    //! The stop state: a time limit of zero stops at the next check, reset clears it. (One test:
    //! the state is global to the process.)
    use super::*;

    #[test]
    fn a_passed_time_limit_stops_and_reset_clears_it() {
        reset();
        assert!(check(|| "nowhere".into()).is_ok());
        set_time_limit(Some(Duration::ZERO));
        match check(|| "step 3 of 10".into()) {
            Err(SolveError::Stopped { at, reason }) => {
                assert_eq!(at, "step 3 of 10");
                assert!(reason.contains("time limit of 0 s"), "{reason}");
            }
            other => panic!("expected a stop, got {other:?}"),
        }
        set_time_limit(Some(Duration::from_secs(3600)));
        assert!(check(|| "a".into()).is_ok());
        interrupt();
        assert!(matches!(
            check(|| "b".into()),
            Err(SolveError::Stopped { .. })
        ));
        reset();
        assert!(check(|| "c".into()).is_ok());
        // a thread's own limit: only inside the closure, and inherited explicitly
        let stopped = with_time_limit(Duration::ZERO, || {
            let inherited = current_deadline();
            let other =
                std::thread::spawn(move || with_deadline(inherited, || check(|| "d".into())));
            (
                check(|| "e".into()).is_err(),
                other.join().map(|r| r.is_err()).unwrap_or(false),
            )
        });
        assert_eq!(stopped, (true, true));
        assert!(check(|| "f".into()).is_ok());
    }
}
