//! How a session is asked to stop: a token the caller sets (from a signal
//! handler, or when a newer render replaces this one) and the session
//! reads. It holds two flags: the request, which stays set, and the flag
//! the pixel loop polls, which the session also raises itself to pause
//! for a checkpoint and lowers again to go on; the request tells a stop
//! from a pause.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// A cancellation token: clones share their flags.
#[derive(Debug, Clone, Default)]
pub struct Cancel {
    /// Set when the render is asked to stop; never cleared.
    requested: Arc<AtomicBool>,
    /// What the pixel loop polls: set with `requested`, and while a
    /// checkpoint is due.
    poll: Arc<AtomicBool>,
}

impl Cancel {
    /// A token no one has cancelled.
    pub fn new() -> Cancel {
        Cancel::default()
    }

    /// Asks the render to stop: it stops within a few samples and
    /// finishes as a stopped render does (a batch render writes what it
    /// has and its state).
    pub fn cancel(&self) {
        // The request first: a loop that sees the poll flag must find it.
        self.requested.store(true, Ordering::SeqCst);
        self.poll.store(true, Ordering::SeqCst);
    }

    /// Whether the render was asked to stop.
    pub fn is_cancelled(&self) -> bool {
        self.requested.load(Ordering::Relaxed)
    }

    /// The flags [`Cancel::cancel`] sets, in the order it sets them, for a
    /// caller that can only set flags (a signal handler): setting both in
    /// this order is cancelling.
    pub fn flags(&self) -> [Arc<AtomicBool>; 2] {
        [self.requested.clone(), self.poll.clone()]
    }

    /// The flag the pixel loop polls.
    pub(super) fn polled(&self) -> &AtomicBool {
        &self.poll
    }

    /// Stops the pixel loop for a checkpoint (not a request to stop).
    pub(super) fn pause(&self) {
        self.poll.store(true, Ordering::Relaxed);
    }

    /// Lets the pixel loop go on after a checkpoint.
    pub(super) fn resume(&self) {
        self.poll.store(false, Ordering::Relaxed);
    }
}
