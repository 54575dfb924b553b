//! The background checker: documents are checked on their own thread, so
//! that hover and completion answer at once while a large scene is being
//! read. A newer version of a document replaces its pending check and
//! cancels a running one (the checker stops at its next statement); a
//! change waits [`DEBOUNCE`] for the next keystroke before its check starts.

use crate::compile::{compile_bytes, Compiled, Options};
use crate::lower::cache::LowerCache;
use crate::source::MemoryFiles;
use crossbeam_channel::Sender;
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::time::{Duration, Instant};

/// How long a change waits for the next one before it is checked.
pub const DEBOUNCE: Duration = Duration::from_millis(30);

/// A check to run.
pub struct Job {
    /// The document (its URI).
    pub uri: String,
    /// Its path.
    pub path: PathBuf,
    /// Its version.
    pub version: i32,
    /// Its text.
    pub text: Arc<String>,
    /// Every open document, over the disk.
    pub files: MemoryFiles,
    /// When to start.
    pub due: Instant,
}

/// A finished check.
pub struct Done {
    /// The document (its URI).
    pub uri: String,
    /// The version checked.
    pub version: i32,
    /// The result.
    pub compiled: Arc<Compiled>,
}

#[derive(Default)]
struct Queue {
    pending: HashMap<String, Job>,
    /// The document being checked and how to cancel it.
    running: Option<(String, Arc<AtomicBool>)>,
    closed: bool,
}

/// The handle the main loop holds.
pub struct Checker {
    shared: Arc<(Mutex<Queue>, Condvar)>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Checker {
    /// Starts the thread; results are sent to `done`.
    pub fn start(done: Sender<Done>) -> Checker {
        let shared = Arc::new((Mutex::new(Queue::default()), Condvar::new()));
        let worker = shared.clone();
        let thread = std::thread::Builder::new()
            .name("ptsc-lsp-checker".to_string())
            .spawn(move || run(&worker, &done))
            .expect("the checker thread starts");
        Checker {
            shared,
            thread: Some(thread),
        }
    }

    /// Queues `job`, replacing a pending check of its document and
    /// cancelling a running one.
    pub fn schedule(&self, job: Job) {
        let (lock, wake) = &*self.shared;
        let mut q = lock.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((uri, cancel)) = &q.running {
            if *uri == job.uri {
                cancel.store(true, Ordering::Relaxed);
            }
        }
        q.pending.insert(job.uri.clone(), job);
        wake.notify_all();
    }

    /// Forgets the pending check of `uri` and cancels its running one.
    pub fn forget(&self, uri: &str) {
        let (lock, _) = &*self.shared;
        let mut q = lock.lock().unwrap_or_else(|e| e.into_inner());
        q.pending.remove(uri);
        if let Some((running, cancel)) = &q.running {
            if running == uri {
                cancel.store(true, Ordering::Relaxed);
            }
        }
    }
}

impl Drop for Checker {
    fn drop(&mut self) {
        {
            let (lock, wake) = &*self.shared;
            let mut q = lock.lock().unwrap_or_else(|e| e.into_inner());
            q.closed = true;
            if let Some((_, cancel)) = &q.running {
                cancel.store(true, Ordering::Relaxed);
            }
            wake.notify_all();
        }
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

fn run(shared: &(Mutex<Queue>, Condvar), done: &Sender<Done>) {
    let (lock, wake) = shared;
    let mut cache = LowerCache::one_off();
    loop {
        let (job, cancel) = {
            let mut q = lock.lock().unwrap_or_else(|e| e.into_inner());
            loop {
                if q.closed {
                    return;
                }
                let next = q.pending.values().map(|j| j.due).min();
                match next {
                    None => q = wake.wait(q).unwrap_or_else(|e| e.into_inner()),
                    Some(due) if due > Instant::now() => {
                        q = wake
                            .wait_timeout(q, due - Instant::now())
                            .unwrap_or_else(|e| e.into_inner())
                            .0;
                    }
                    Some(due) => {
                        let uri = q
                            .pending
                            .iter()
                            .find(|(_, j)| j.due == due)
                            .map(|(u, _)| u.clone());
                        let job = uri
                            .and_then(|u| q.pending.remove(&u))
                            .expect("the job found");
                        let cancel = Arc::new(AtomicBool::new(false));
                        q.running = Some((job.uri.clone(), cancel.clone()));
                        break (job, cancel);
                    }
                }
            }
        };
        let options = Options {
            lower: false,
            files: &job.files,
            cache: Some(&mut cache),
            cancel: Some(cancel.clone()),
            ..Options::default()
        };
        // A panic in a check (a bug) loses that check, not the server.
        let compiled = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            compile_bytes(&job.path, job.text.as_bytes().to_vec(), options)
        }));
        lock.lock().unwrap_or_else(|e| e.into_inner()).running = None;
        let Ok(compiled) = compiled else {
            cache = LowerCache::one_off();
            continue;
        };
        if cancel.load(Ordering::Relaxed) {
            continue;
        }
        let result = Done {
            uri: job.uri,
            version: job.version,
            compiled: Arc::new(compiled),
        };
        if done.send(result).is_err() {
            return;
        }
    }
}
