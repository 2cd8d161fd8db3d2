//! Clocks shared by the criterion benchmarks of both crates (`benches/speedup.rs`,
//! `crates/lookup/benches/lookup.rs`): `LOOKUP_BENCH_CLOCK=cpu` selects the process CPU time.

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::BenchmarkGroup;

/// Which clock a benchmark reads: elapsed time, or the CPU time of the whole process
/// (`CLOCK_PROCESS_CPUTIME_ID`), which other processes on a shared machine do not inflate.
#[derive(Clone, Copy)]
pub enum Clock {
    Wall,
    ProcessCpu,
}

impl Clock {
    pub fn from_env() -> Clock {
        match std::env::var("LOOKUP_BENCH_CLOCK").as_deref() {
            Ok("cpu") => Clock::ProcessCpu,
            _ => Clock::Wall,
        }
    }

    pub fn suffix(self) -> &'static str {
        match self {
            Clock::Wall => "",
            Clock::ProcessCpu => "_cpu",
        }
    }

    pub fn now(self) -> Duration {
        match self {
            Clock::Wall => {
                thread_local!(static T0: Instant = Instant::now());
                T0.with(|t| t.elapsed())
            }
            Clock::ProcessCpu => process_cpu_time(),
        }
    }
}

#[cfg(all(target_os = "linux", target_pointer_width = "64"))]
fn process_cpu_time() -> Duration {
    #[repr(C)]
    struct Timespec {
        sec: i64,
        nsec: i64,
    }
    extern "C" {
        fn clock_gettime(clock: i32, tp: *mut Timespec) -> i32;
    }
    const CLOCK_PROCESS_CPUTIME_ID: i32 = 2;
    let mut ts = Timespec { sec: 0, nsec: 0 };
    // SAFETY: clock_gettime writes one timespec to a valid pointer.
    let rc = unsafe { clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
    assert_eq!(rc, 0, "clock_gettime(CLOCK_PROCESS_CPUTIME_ID) failed");
    Duration::new(ts.sec as u64, ts.nsec as u32)
}

#[cfg(not(all(target_os = "linux", target_pointer_width = "64")))]
fn process_cpu_time() -> Duration {
    panic!("LOOKUP_BENCH_CLOCK=cpu is only implemented for 64-bit Linux")
}

/// Time `f` per iteration with `clock`.
pub fn timed<M: criterion::measurement::Measurement<Value = Duration>, O>(
    g: &mut BenchmarkGroup<'_, M>,
    name: &str,
    clock: Clock,
    mut f: impl FnMut() -> O,
) {
    g.bench_function(name, |b| {
        b.iter_custom(|iters| {
            let start = clock.now();
            for _ in 0..iters {
                black_box(f());
            }
            clock.now() - start
        })
    });
}
