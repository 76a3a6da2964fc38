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

use std::cell::RefCell;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, OnceLock};
use std::time::{Duration, Instant};

use crate::error::SolveError;

static INTERRUPTED: AtomicBool = AtomicBool::new(false);
/// The deadline in nanoseconds after [`origin`]; `u64::MAX` for none.
static DEADLINE: AtomicU64 = AtomicU64::new(u64::MAX);
/// The time limit in milliseconds, for the message.
static LIMIT_MS: AtomicU64 = AtomicU64::new(0);

/// The checks' clock of one thread-local time limit, shared by the threads that inherit it: how
/// long the passes between two checks took before the deadline, when a check first found the
/// deadline passed, and how many did. It measures the promise "a stop within one step": every
/// loop checks once per pass, and a stop must be honoured at the first check that finds the
/// deadline passed — one fired check per thread that shares the clock. A loop that swallows the
/// stop and goes on fires again; a stretch left without a check shows as a stop later after the
/// deadline than the steps measured before it (reported, not gated: the step that holds the
/// deadline may be the longest by chance).
#[derive(Debug)]
struct StopClock {
    start: Instant,
    /// Checks that found the deadline ahead.
    checks_before: AtomicU64,
    /// The last such check, in ns after `start` (0: none yet; the start counts as one).
    last_before_ns: AtomicU64,
    /// The longest time between two consecutive checks (or the start and the first check) before
    /// the deadline, in ns.
    longest_gap_ns: AtomicU64,
    /// When a check first found the deadline passed, in ns after `start` (`u64::MAX`: never).
    fired_ns: AtomicU64,
    /// Checks that found the deadline passed.
    fired: AtomicU64,
    /// Threads that ran with this deadline.
    sharers: AtomicU64,
}

/// A thread's own deadline, its time limit (for the message) and its checks' clock.
#[derive(Debug, Clone)]
pub struct Deadline {
    at: Instant,
    limit: Duration,
    clock: Arc<StopClock>,
}

impl Deadline {
    /// A deadline `limit` from now.
    pub fn from_now(limit: Duration) -> Self {
        let start = Instant::now();
        Self {
            at: start + limit,
            limit,
            clock: Arc::new(StopClock {
                start,
                checks_before: AtomicU64::new(0),
                last_before_ns: AtomicU64::new(0),
                longest_gap_ns: AtomicU64::new(0),
                fired_ns: AtomicU64::new(u64::MAX),
                fired: AtomicU64::new(0),
                sharers: AtomicU64::new(0),
            }),
        }
    }

    /// Whether the deadline has passed, recording the check on the clock.
    fn passed(&self) -> bool {
        let now = Instant::now();
        let ns = |t: Instant| {
            u64::try_from(t.saturating_duration_since(self.clock.start).as_nanos())
                .unwrap_or(u64::MAX - 1)
        };
        let c = &self.clock;
        if now < self.at {
            let at = ns(now);
            // threads sharing the clock interleave their checks: the gaps are then between any
            // two threads' checks (a lower bound of each thread's own steps)
            let last = c.last_before_ns.swap(at, Ordering::Relaxed);
            c.longest_gap_ns
                .fetch_max(at.saturating_sub(last), Ordering::Relaxed);
            c.checks_before.fetch_add(1, Ordering::Relaxed);
            false
        } else {
            let _ = c.fired_ns.compare_exchange(
                u64::MAX,
                ns(now),
                Ordering::Relaxed,
                Ordering::Relaxed,
            );
            c.fired.fetch_add(1, Ordering::Relaxed);
            true
        }
    }

    /// What the clock measured so far.
    pub fn timing(&self) -> StopTiming {
        let c = &self.clock;
        let fired = c.fired_ns.load(Ordering::Relaxed);
        let limit_ns = u64::try_from(self.limit.as_nanos()).unwrap_or(u64::MAX);
        StopTiming {
            checks_before: c.checks_before.load(Ordering::Relaxed),
            longest_step_before: Duration::from_nanos(c.longest_gap_ns.load(Ordering::Relaxed)),
            fired_after_limit: (fired != u64::MAX)
                .then(|| Duration::from_nanos(fired.saturating_sub(limit_ns))),
            fired_checks: c.fired.load(Ordering::Relaxed),
            threads: c.sharers.load(Ordering::Relaxed),
        }
    }
}

/// What a time limit's clock measured: how many checks found the deadline ahead, the longest
/// stretch between two of them (the start counts as a check), how long after the deadline a check
/// first found it passed (`None`: no check did), how many checks did, and how many threads ran
/// with the deadline.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StopTiming {
    pub checks_before: u64,
    pub longest_step_before: Duration,
    pub fired_after_limit: Option<Duration>,
    pub fired_checks: u64,
    pub threads: u64,
}

impl StopTiming {
    /// Whether the stop was honoured at the first check that found the deadline passed: at most
    /// one such check per thread (a loop that swallowed the stop would check again).
    pub fn honoured_at_first_check(&self) -> bool {
        self.fired_checks <= self.threads.max(1)
    }

    /// Whether the stop came no later after the deadline than the longest step measured before
    /// it (a stretch without a check shows here; so may, by chance, a step longer than those
    /// before the deadline).
    pub fn within_longest_step(&self) -> bool {
        match self.fired_after_limit {
            None => true,
            Some(late) => self.checks_before > 0 && late <= self.longest_step_before,
        }
    }
}

thread_local! {
    /// This thread's own deadline.
    static LOCAL: RefCell<Option<Deadline>> = const { RefCell::new(None) };
}

/// The calling thread's own deadline (for a solver that spawns threads: pass it to
/// [`with_deadline`] in each; the threads then share its clock).
pub fn current_deadline() -> Option<Deadline> {
    LOCAL.with(|c| c.borrow().clone())
}

/// Runs `f` with `deadline` as the calling thread's own deadline, then restores the previous one.
pub fn with_deadline<R>(deadline: Option<Deadline>, f: impl FnOnce() -> R) -> R {
    if let Some(d) = &deadline {
        d.clock.sharers.fetch_add(1, Ordering::Relaxed);
    }
    let previous = LOCAL.with(|c| c.replace(deadline));
    struct Restore(Option<Option<Deadline>>);
    impl Drop for Restore {
        fn drop(&mut self) {
            let previous = self.0.take().flatten();
            LOCAL.with(|c| *c.borrow_mut() = previous);
        }
    }
    let _restore = Restore(Some(previous));
    f()
}

/// Runs `f` with a time limit from now on the calling thread only.
pub fn with_time_limit<R>(limit: Duration, f: impl FnOnce() -> R) -> R {
    with_time_limit_measured(limit, f).0
}

/// [`with_time_limit`], with what the limit's clock measured: whether a stop came within one
/// step of the deadline.
pub fn with_time_limit_measured<R>(limit: Duration, f: impl FnOnce() -> R) -> (R, StopTiming) {
    let deadline = Deadline::from_now(limit);
    let r = with_deadline(Some(deadline.clone()), f);
    (r, deadline.timing())
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
    LOCAL.with(|c| {
        c.borrow().as_ref().and_then(|d| {
            d.passed()
                .then(|| format!("the time limit of {} s was reached", d.limit.as_secs_f64()))
        })
    })
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
    fn a_passed_time_limit_stops_reset_clears_it_and_the_clock_measures_the_stop() {
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
        the_clock_tells_a_stop_within_one_step_from_an_unchecked_stretch();
    }

    /// The clock tells a stop within one step from an unchecked stretch (called from the test
    /// above: the global state must not change while it runs).
    fn the_clock_tells_a_stop_within_one_step_from_an_unchecked_stretch() {
        // steps of 4 ms, each ending in a check: the stop fires within one step
        let step = Duration::from_millis(4);
        let (stopped_at, timing) = with_time_limit_measured(Duration::from_millis(30), || {
            (1..1000).find(|_| {
                std::thread::sleep(step);
                check(|| "a step".into()).is_err()
            })
        });
        assert!(stopped_at.is_some());
        assert!(timing.checks_before >= 3, "{timing:?}");
        assert!(timing.within_longest_step(), "{timing:?}");
        assert!(timing.honoured_at_first_check(), "{timing:?}");
        assert_eq!((timing.fired_checks, timing.threads), (1, 1));
        // an unchecked stretch (a "setup" of 60 ms) past a deadline of 20 ms, then steps: the
        // first check comes after the deadline, with no step measured before it
        let (_, timing) = with_time_limit_measured(Duration::from_millis(20), || {
            std::thread::sleep(Duration::from_millis(60));
            (1..1000).find(|_| {
                std::thread::sleep(step);
                check(|| "a step".into()).is_err()
            })
        });
        assert_eq!(timing.checks_before, 0, "{timing:?}");
        assert!(!timing.within_longest_step(), "{timing:?}");
        // steps of 2 ms, then one unchecked stretch of 80 ms across the deadline
        let (_, timing) = with_time_limit_measured(Duration::from_millis(30), || {
            for i in 0..1000 {
                std::thread::sleep(if i == 5 {
                    Duration::from_millis(80)
                } else {
                    step / 2
                });
                if check(|| "a step".into()).is_err() {
                    break;
                }
            }
        });
        assert!(!timing.within_longest_step(), "{timing:?}");
        // a loop that swallows the stop and goes on: three fired checks on one thread
        let (_, timing) = with_time_limit_measured(Duration::ZERO, || {
            for _ in 0..3 {
                let _ = check(|| "a step".into());
            }
        });
        assert_eq!(timing.fired_checks, 3);
        assert!(!timing.honoured_at_first_check(), "{timing:?}");
    }
}
