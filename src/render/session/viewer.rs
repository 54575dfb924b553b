//! When a batch render shows its passes in the tev viewer (`--tev`): at
//! most four times a second, and always its last image; a viewer that goes
//! away is let go with a note, and the render goes on.

use super::observer::Observer;
use crate::output::tev::Tev;
use crate::render::film::Film;
use std::time::{Duration, Instant};

/// Least time between two images sent, but for the last: an 8192² image
/// is 800 MB over the socket.
const INTERVAL: Duration = Duration::from_millis(250);

/// The viewer a render shows its passes in, if any.
pub(super) struct Viewer {
    tev: Option<Tev>,
    /// When an image was last sent.
    last_shown: Option<Instant>,
    /// Whether the film has a pass the viewer has not been sent (a time
    /// budget's last pass is not known to be the last).
    unshown: bool,
}

impl Viewer {
    /// Shows the passes in `tev`, or nowhere.
    pub(super) fn new(tev: Option<Tev>) -> Viewer {
        Viewer {
            tev,
            last_shown: None,
            unshown: false,
        }
    }

    /// A pass ended with `film`: sent if it is the `last` or its time has
    /// come.
    pub(super) fn pass(&mut self, film: &Film, last: bool, observer: &dyn Observer) {
        let due = last || self.last_shown.is_none_or(|t| t.elapsed() >= INTERVAL);
        self.unshown = !due;
        if due {
            self.last_shown = Some(Instant::now());
            self.show(film, observer);
        }
    }

    /// The passes are over: the film is sent if its last pass was not.
    pub(super) fn finish(&mut self, film: &Film, observer: &dyn Observer) {
        if std::mem::take(&mut self.unshown) {
            self.show(film, observer);
        }
    }

    fn show(&mut self, film: &Film, observer: &dyn Observer) {
        if let Some(Err(e)) = self.tev.as_mut().map(|t| t.show(|i| film.pixel(i))) {
            observer.note(&format!(
                "tev stopped taking the image ({e}); the render goes on"
            ));
            self.tev = None;
        }
    }
}
