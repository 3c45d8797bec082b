//! The render threads other than the calling one ([`crate::fbi::Fbi::set_threads`]):
//! a pool of their own, and a way to wake them before a triangle's bands are ready.
//!
//! A helper that has had no work for a few tens of microseconds sleeps (rayon's idle
//! loop), and waking it takes about as long again on the 2-vCPU machine of
//! docs/performance.md (20 to 100 µs for 696 of perf_gouraud_heavy's 700 banded
//! triangles, measured). A large triangle's walk, pieces and bands take the calling
//! thread about that long, so [`Helpers::wake`] starts the helpers when the walk starts
//! and [`Helpers::release`] lets them go once the bands are queued (or the triangle turns
//! out not to be banded): they spin in between, so they take the first bands as soon as
//! there are any.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The longest a woken helper spins waiting for [`Helpers::release`]: longer than the
/// walk of any triangle measured, short enough that a lost release costs little.
const WAKE_SPIN: Duration = Duration::from_micros(300);

/// A pool of helper threads and the count that releases the woken ones.
pub(crate) struct Helpers {
    pool: rayon::ThreadPool,
    /// Bumped by [`Helpers::release`]: a woken helper spins while it holds the value
    /// it was woken with.
    released: Arc<AtomicU64>,
}

impl Helpers {
    /// A pool of `helpers` threads, or `None` if the threads cannot be started.
    pub(crate) fn new(helpers: usize) -> Option<Helpers> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(helpers)
            .thread_name(|i| format!("voodoo-render-{i}"))
            .build()
            .ok()?;
        Some(Helpers {
            pool,
            released: Arc::new(AtomicU64::new(0)),
        })
    }

    /// The pool the bands run on.
    pub(crate) fn pool(&self) -> &rayon::ThreadPool {
        &self.pool
    }

    /// Wake every helper: each spins until the next [`Helpers::release`] (or for
    /// [`WAKE_SPIN`]) instead of sleeping, so that it is running when the bands come.
    pub(crate) fn wake(&self) {
        let woken_at = self.released.load(Ordering::Acquire);
        for _ in 0..self.pool.current_num_threads() {
            let released = Arc::clone(&self.released);
            self.pool.spawn(move || {
                let since = Instant::now();
                while released.load(Ordering::Acquire) == woken_at && since.elapsed() < WAKE_SPIN {
                    for _ in 0..64 {
                        std::hint::spin_loop();
                    }
                }
            });
        }
    }

    /// Let the helpers woken by [`Helpers::wake`] stop spinning: each returns to the pool
    /// and takes the bands queued there, or sleeps.
    pub(crate) fn release(&self) {
        self.released.fetch_add(1, Ordering::AcqRel);
    }
}
