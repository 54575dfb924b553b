//! Ctrl-C (SIGINT) and SIGTERM as flags: the first asks the render to stop
//! and write what it has, a second one ends the process at once. The exit
//! code tells which signal it was (128 + its number: 130, 143), so that a
//! script can tell an interrupted render from a finished one.

use crate::render::session::Cancel;
use signal_hook::consts::{SIGINT, SIGTERM};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// Exit code after SIGINT (Ctrl-C).
pub const EXIT_SIGINT: u8 = 130;
/// Exit code after SIGTERM (a scheduler's or `kill`'s stop).
pub const EXIT_SIGTERM: u8 = 143;

/// The flags the signals set.
#[derive(Debug, Clone)]
pub struct Signals {
    /// Cancelled by either signal: what a render session stops on (it
    /// tells a stop from its own checkpoints' pauses).
    pub cancel: Cancel,
    /// Set by SIGTERM.
    term: Arc<AtomicBool>,
}

impl Signals {
    /// Installs the handlers. Where a platform refuses one, that signal
    /// keeps its default action (the process ends).
    pub fn install() -> Signals {
        let signals = Signals {
            cancel: Cancel::new(),
            term: Arc::new(AtomicBool::new(false)),
        };
        let [requested, polled] = signals.cancel.flags();
        for (signal, code) in [(SIGINT, EXIT_SIGINT), (SIGTERM, EXIT_SIGTERM)] {
            // A second signal while the first is being answered: quit now.
            // (The condition is checked before the flags below are set.)
            let _ = signal_hook::flag::register_conditional_shutdown(
                signal,
                code as i32,
                requested.clone(),
            );
            // In the token's order, which is cancelling it.
            let _ = signal_hook::flag::register(signal, requested.clone());
            let _ = signal_hook::flag::register(signal, polled.clone());
        }
        let _ = signal_hook::flag::register(SIGTERM, signals.term.clone());
        signals
    }

    /// Whether a signal asked to stop.
    pub fn stopped(&self) -> bool {
        self.cancel.is_cancelled()
    }

    /// The exit code for the signal that stopped the process.
    pub fn exit_code(&self) -> u8 {
        if self.term.load(Ordering::Relaxed) {
            EXIT_SIGTERM
        } else {
            EXIT_SIGINT
        }
    }
}
