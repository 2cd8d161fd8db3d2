//! Clocks that other processes on a shared machine do not inflate: the CPU time of the calling
//! thread or of the whole process (`clock_gettime`, 64-bit Linux; `None` elsewhere), and a
//! [`Clock`] that a benchmark selects from the environment (criterion timing with it:
//! `oblique-bench`).

use std::time::{Duration, Instant};

/// CPU time of the calling thread (`CLOCK_THREAD_CPUTIME_ID`); `None` where unavailable.
pub fn thread_cpu_time() -> Option<Duration> {
    clock_gettime(3)
}

/// CPU time of the whole process, all threads (`CLOCK_PROCESS_CPUTIME_ID`); `None` where
/// unavailable.
pub fn process_cpu_time() -> Option<Duration> {
    clock_gettime(2)
}

/// `clock_gettime(clock)`; `None` where unavailable or when the call fails.
fn clock_gettime(clock: i32) -> Option<Duration> {
    #[cfg(all(target_os = "linux", target_pointer_width = "64"))]
    {
        #[repr(C)]
        struct Timespec {
            tv_sec: i64,
            tv_nsec: i64,
        }
        extern "C" {
            fn clock_gettime(clock: i32, tp: *mut Timespec) -> i32;
        }
        let mut ts = Timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: `ts` is a valid, writable timespec with the C layout on 64-bit Linux.
        let rc = unsafe { clock_gettime(clock, &mut ts) };
        (rc == 0).then(|| Duration::new(ts.tv_sec as u64, ts.tv_nsec as u32))
    }
    #[cfg(not(all(target_os = "linux", target_pointer_width = "64")))]
    {
        let _ = clock;
        None
    }
}

/// Time since the first call of this function in the process (a monotonic origin).
pub fn elapsed_since_start() -> Duration {
    use std::sync::OnceLock;
    static START: OnceLock<Instant> = OnceLock::new();
    START.get_or_init(Instant::now).elapsed()
}

/// Which clock a benchmark reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Clock {
    /// Elapsed (wall-clock) time.
    Wall,
    /// CPU time of the benchmarking thread ([`thread_cpu_time`]): not inflated by other
    /// processes taking the core.
    ThreadCpu,
    /// CPU time of the whole process ([`process_cpu_time`]), for benchmarks that run threads.
    ProcessCpu,
}

impl Clock {
    /// The clock the environment variable `var` names: unset or `wall` gives [`Clock::Wall`],
    /// `cpu` gives `cpu` where this platform has that CPU-time clock; anything else is an error
    /// that names the variable and the choices (a benchmark never reports elapsed time under a
    /// CPU-time name).
    pub fn from_env(var: &str, cpu: Clock) -> Result<Clock, String> {
        match std::env::var(var).as_deref() {
            Err(_) | Ok("wall") => Ok(Clock::Wall),
            Ok("cpu") => {
                let available = match cpu {
                    Clock::Wall => true,
                    Clock::ThreadCpu => thread_cpu_time().is_some(),
                    Clock::ProcessCpu => process_cpu_time().is_some(),
                };
                if available {
                    Ok(cpu)
                } else {
                    Err(format!(
                        "{var}=cpu: this platform has no CPU-time clock (64-bit Linux only); \
                         use wall"
                    ))
                }
            }
            Ok(other) => Err(format!("{var}={other}: expected wall or cpu")),
        }
    }

    /// Suffix for benchmark group names: `""` for elapsed time, `"_cpu"` for CPU time.
    pub fn suffix(self) -> &'static str {
        match self {
            Clock::Wall => "",
            Clock::ThreadCpu | Clock::ProcessCpu => "_cpu",
        }
    }

    /// The clock's reading, from an arbitrary origin (elapsed time where a CPU clock is
    /// unavailable).
    pub fn now(self) -> Duration {
        let cpu = match self {
            Clock::Wall => None,
            Clock::ThreadCpu => thread_cpu_time(),
            Clock::ProcessCpu => process_cpu_time(),
        };
        cpu.unwrap_or_else(elapsed_since_start)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cpu_clocks_advance_with_work() {
        let (t0, p0) = (thread_cpu_time(), process_cpu_time());
        let mut x = 0u64;
        for i in 0..20_000_000u64 {
            x = std::hint::black_box(x.wrapping_mul(6364136223846793005).wrapping_add(i));
        }
        std::hint::black_box(x);
        if cfg!(all(target_os = "linux", target_pointer_width = "64")) {
            assert!(thread_cpu_time().unwrap() > t0.unwrap());
            assert!(process_cpu_time().unwrap() > p0.unwrap());
        }
        let w = Clock::Wall.now();
        assert!(Clock::Wall.now() >= w);
        std::env::set_var("OBLIQUE_CLOCK_TEST", "cpu");
        assert_eq!(
            Clock::from_env("OBLIQUE_CLOCK_TEST", Clock::ThreadCpu),
            Ok(Clock::ThreadCpu)
        );
        std::env::set_var("OBLIQUE_CLOCK_TEST", "gpu");
        let e = Clock::from_env("OBLIQUE_CLOCK_TEST", Clock::ThreadCpu).unwrap_err();
        assert!(
            e.contains("OBLIQUE_CLOCK_TEST=gpu") && e.contains("wall or cpu"),
            "{e}"
        );
        std::env::remove_var("OBLIQUE_CLOCK_TEST");
        assert_eq!(
            Clock::from_env("OBLIQUE_CLOCK_TEST", Clock::ThreadCpu),
            Ok(Clock::Wall)
        );
    }
}
