//! The CPU time of the calling thread, for the benchmarks and the report's timings: unlike the
//! wall clock it does not count the time other processes on a shared machine take the core.
//! It calls the C library, so it is one of the few modules allowed `unsafe` (src/lib.rs).

/// Seconds of CPU time this thread has used (`CLOCK_THREAD_CPUTIME_ID`, nanosecond resolution
/// on Linux); None where the clock is not available.
#[cfg(not(windows))]
pub fn thread_cpu_seconds() -> Option<f64> {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `ts` is a valid, writable timespec for the duration of the call.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    (rc == 0).then_some(ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9)
}

/// Seconds of CPU time this thread has used (GetThreadTimes: kernel plus user time, in 100 ns
/// units); None where the call fails.
#[cfg(windows)]
pub fn thread_cpu_seconds() -> Option<f64> {
    #[repr(C)]
    #[derive(Default)]
    struct FileTime {
        low: u32,
        high: u32,
    }
    #[link(name = "kernel32")]
    extern "system" {
        fn GetCurrentThread() -> *mut core::ffi::c_void;
        fn GetThreadTimes(
            thread: *mut core::ffi::c_void,
            creation: *mut FileTime,
            exit: *mut FileTime,
            kernel: *mut FileTime,
            user: *mut FileTime,
        ) -> i32;
    }
    let (mut c, mut e, mut k, mut u) = Default::default();
    // SAFETY: the pseudo-handle of the current thread is always valid; the four FILETIMEs are
    // valid and writable for the duration of the call.
    let ok = unsafe { GetThreadTimes(GetCurrentThread(), &mut c, &mut e, &mut k, &mut u) };
    let ticks = |t: &FileTime| ((t.high as u64) << 32 | t.low as u64) as f64;
    (ok != 0).then(|| (ticks(&k) + ticks(&u)) * 1e-7)
}

/// Measures the thread CPU time of `f`, falling back to the wall clock where the thread clock
/// is missing.
pub fn time_cpu<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let wall = std::time::Instant::now();
    let start = thread_cpu_seconds();
    let out = f();
    let seconds = match (start, thread_cpu_seconds()) {
        (Some(a), Some(b)) => b - a,
        _ => wall.elapsed().as_secs_f64(),
    };
    (out, seconds)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Oracle: a busy loop of known length uses CPU time, and the clock never runs backwards.
    #[test]
    fn counts_the_threads_own_work() {
        let (sum, seconds) =
            time_cpu(|| (0..20_000_000u64).fold(0u64, |a, i| a ^ i.wrapping_mul(i)));
        assert!(sum != 1);
        assert!(seconds > 0.0 && seconds < 60.0, "{seconds}");
    }
}
