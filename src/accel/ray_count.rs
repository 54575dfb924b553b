//! Rays traced, counted per thread: closest-hit queries (the scene's
//! `intersect`) and shadow queries (`occluded`). The pixel loop reads its
//! thread's counts before and after each tile, so a render reports the rays
//! it traced (rays/s beside paths/s) without a shared counter in the hot
//! path.

use std::cell::Cell;
use std::ops::{Add, Sub};

/// Rays traced, by kind.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RayCounts {
    /// Closest-hit queries: camera rays and the rays that continue paths.
    pub closest: u64,
    /// Any-hit queries: shadow rays.
    pub shadow: u64,
}

impl RayCounts {
    /// Both kinds together.
    pub fn total(&self) -> u64 {
        self.closest + self.shadow
    }
}

impl Add for RayCounts {
    type Output = RayCounts;
    fn add(self, o: RayCounts) -> RayCounts {
        RayCounts {
            closest: self.closest + o.closest,
            shadow: self.shadow + o.shadow,
        }
    }
}

impl Sub for RayCounts {
    type Output = RayCounts;
    fn sub(self, o: RayCounts) -> RayCounts {
        RayCounts {
            closest: self.closest - o.closest,
            shadow: self.shadow - o.shadow,
        }
    }
}

thread_local! {
    static COUNTS: Cell<RayCounts> = const {
        Cell::new(RayCounts {
            closest: 0,
            shadow: 0,
        })
    };
}

/// Counts one closest-hit query on this thread.
#[inline(always)]
pub fn closest() {
    bump(|n| n.closest += 1);
}

/// Counts one shadow query on this thread.
#[inline(always)]
pub fn shadow() {
    bump(|n| n.shadow += 1);
}

#[inline(always)]
fn bump(count: impl FnOnce(&mut RayCounts)) {
    COUNTS.with(|c| {
        let mut n = c.get();
        count(&mut n);
        c.set(n);
    });
}

/// The rays this thread has traced since it started.
pub fn this_thread() -> RayCounts {
    COUNTS.with(Cell::get)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_are_per_thread_and_subtract() {
        let before = this_thread();
        closest();
        closest();
        shadow();
        let here = this_thread() - before;
        assert_eq!(
            here,
            RayCounts {
                closest: 2,
                shadow: 1
            }
        );
        assert_eq!(here.total(), 3);
        // Another thread starts from zero and does not see these.
        let other = std::thread::spawn(|| {
            shadow();
            this_thread()
        })
        .join()
        .unwrap();
        assert_eq!(
            other,
            RayCounts {
                closest: 0,
                shadow: 1
            }
        );
        assert_eq!(this_thread() - before, here);
    }
}
