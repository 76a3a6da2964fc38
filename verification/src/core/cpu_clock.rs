//! The CPU time of the calling thread: what a measured piece of code cost, whatever else shares
//! the cores.
//!
//! A wall-clock time measures the machine as much as the code: on a loaded machine (other
//! processes running) a time loop is preempted and its wall time grows, while a short reference
//! measurement (one sparse solve, best of many) is rarely hit, so a ratio of the two drifts with the
//! load. The thread's CPU time (`clock_gettime(CLOCK_THREAD_CPUTIME_ID)`, nanosecond resolution)
//! counts only the time the thread ran, so ratios of CPU times are what the code does. The timed
//! code must run on the calling thread (the solvers' time loops do: no parallelism inside them).

/// CPU seconds used by the calling thread so far (an arbitrary origin: use differences).
#[cfg(unix)]
pub fn thread_cpu_seconds() -> f64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `ts` is a valid, writable timespec; CLOCK_THREAD_CPUTIME_ID is supported on Linux and
    // macOS. On failure the call leaves `ts` at zero and we fall back to the wall clock below.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    if rc == 0 {
        ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9
    } else {
        wall_seconds()
    }
}

/// Without a thread CPU clock: the wall clock.
#[cfg(not(unix))]
pub fn thread_cpu_seconds() -> f64 {
    wall_seconds()
}

fn wall_seconds() -> f64 {
    use std::sync::OnceLock;
    use std::time::Instant;
    static ORIGIN: OnceLock<Instant> = OnceLock::new();
    ORIGIN.get_or_init(Instant::now).elapsed().as_secs_f64()
}

/// The least CPU time of the calling thread over `repeats` (≥ 1) runs of `run` (s): the run's
/// own cost, the disturbances of a shared machine filtered out.
///
/// # Errors
/// The first error of a run.
pub fn min_thread_cpu_seconds<E>(
    repeats: usize,
    mut run: impl FnMut() -> Result<(), E>,
) -> Result<f64, E> {
    let mut best = f64::INFINITY;
    for _ in 0..repeats.max(1) {
        let start = thread_cpu_seconds();
        run()?;
        best = best.min(thread_cpu_seconds() - start);
    }
    Ok(best)
}

#[cfg(test)]
mod tests {
    //! The clock advances with work done on the thread, and not while the thread sleeps.
    use super::*;

    #[test]
    fn the_clock_counts_work_not_sleep() {
        let t0 = thread_cpu_seconds();
        std::thread::sleep(std::time::Duration::from_millis(50));
        let slept = thread_cpu_seconds() - t0;
        let t1 = thread_cpu_seconds();
        let mut x = 0.0_f64;
        for i in 0..5_000_000 {
            x += (i as f64).sqrt();
        }
        std::hint::black_box(x);
        let worked = thread_cpu_seconds() - t1;
        assert!(slept < 0.02, "sleeping used {slept} s of CPU");
        assert!(worked > 1e-4, "work used {worked} s of CPU");
    }
}
