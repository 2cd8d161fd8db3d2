//! Criterion timing with a [`Clock`] (elapsed time, or the CPU time of the thread or the
//! process), shared by the benchmarks of the workspace. Only benchmarks depend on this crate:
//! the clocks themselves (`oblique-clock`) carry no criterion code, so a release build of the
//! binary and the test build compile them with the same features.

use std::time::Duration;

use criterion::measurement::Measurement;
use oblique_clock::Clock;

/// Criterion's iteration with a [`Clock`].
pub trait ClockIter {
    /// `b.iter` for elapsed time, else the CPU time of the iterations.
    fn iter<M, R>(self, b: &mut criterion::Bencher<'_, M>, f: impl FnMut() -> R)
    where
        M: Measurement<Value = Duration>;
}

impl ClockIter for Clock {
    fn iter<M, R>(self, b: &mut criterion::Bencher<'_, M>, mut f: impl FnMut() -> R)
    where
        M: Measurement<Value = Duration>,
    {
        match self {
            Clock::Wall => b.iter(f),
            _ => b.iter_custom(|iters| {
                let start = self.now();
                for _ in 0..iters {
                    std::hint::black_box(f());
                }
                self.now() - start
            }),
        }
    }
}

/// Time `f` per iteration with `clock`, as the benchmark `name` of the group `g`.
///
/// The loop calls `f` directly (not through `&mut f`), so a nanosecond-scale `f` is inlined
/// into it: through a reference it was called out of line and its result copied through the
/// stack, which tripled the time of a 3 ns query.
pub fn timed<M: Measurement<Value = Duration>, O>(
    g: &mut criterion::BenchmarkGroup<'_, M>,
    name: &str,
    clock: Clock,
    mut f: impl FnMut() -> O,
) {
    g.bench_function(name, |b| {
        b.iter_custom(|iters| {
            let start = clock.now();
            for _ in 0..iters {
                std::hint::black_box(f());
            }
            clock.now() - start
        })
    });
}
