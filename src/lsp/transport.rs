//! The stdio transport: JSON-RPC messages framed by `Content-Length`
//! headers, read on one thread and written on another. Unlike
//! `lsp_server::Connection::stdio`, a malformed frame or payload does not
//! end the session: it becomes a [`MALFORMED`] notification for the main
//! loop to report, and reading goes on with the next frame. A frame may
//! claim at most [`MAX_MESSAGE_BYTES`], and its body is read as it comes,
//! never allocated from the claim alone.

use crossbeam_channel::{unbounded, Sender};
use lsp_server::{Connection, Message, Notification};
use std::io::{self, BufRead, Read, Write};
use std::thread;

/// The method of the notification standing for a message that could not
/// be read (its params: `{ "error": "…" }`).
pub const MALFORMED: &str = "$/ptsc/malformed";

/// The largest message accepted: a scene at the size limit
/// ([`crate::source::MAX_SCENE_BYTES`]) sent whole, with room for escapes.
pub const MAX_MESSAGE_BYTES: usize = (crate::source::MAX_SCENE_BYTES as usize) * 2;

/// The threads behind a [`Connection`] over stdio.
pub struct Threads {
    reader: thread::JoinHandle<()>,
    writer: thread::JoinHandle<()>,
}

impl Threads {
    /// Waits for the writer to flush what it was given (the reader is left
    /// to end with stdin).
    pub fn join(self) {
        let _ = self.writer.join();
        drop(self.reader);
    }
}

/// A connection over the process's stdin and stdout.
pub fn stdio() -> (Connection, Threads) {
    let (to_main, receiver) = unbounded::<Message>();
    let (sender, from_main) = unbounded::<Message>();
    let reader = thread::spawn(move || read_loop(&mut io::stdin().lock(), &to_main));
    let writer = thread::spawn(move || {
        let mut out = io::stdout().lock();
        for message in from_main {
            if message.write(&mut out).and_then(|()| out.flush()).is_err() {
                break;
            }
        }
    });
    (Connection { sender, receiver }, Threads { reader, writer })
}

/// Reads messages from `input` until it ends (or the main loop is gone).
pub fn read_loop(input: &mut impl BufRead, to_main: &Sender<Message>) {
    loop {
        let message = match read_frame(input) {
            Ok(None) => return,
            Ok(Some(body)) => parse(&body),
            Err(e) if e.kind() == io::ErrorKind::UnexpectedEof => return,
            Err(e) => malformed(e.to_string()),
        };
        let exit = matches!(&message, Message::Notification(n) if n.method == "exit");
        if to_main.send(message).is_err() || exit {
            return;
        }
    }
}

fn parse(body: &[u8]) -> Message {
    match serde_json::from_slice::<Message>(body) {
        Ok(m) => m,
        Err(e) => malformed(format!("not a JSON-RPC message: {e}")),
    }
}

fn malformed(error: String) -> Message {
    Message::Notification(Notification::new(
        MALFORMED.to_string(),
        serde_json::json!({ "error": error }),
    ))
}

/// One frame's body; `None` at the end of the input. A header block
/// without a usable `Content-Length` is an error after it is consumed.
fn read_frame(input: &mut impl BufRead) -> io::Result<Option<Vec<u8>>> {
    let mut length: Option<Result<usize, String>> = None;
    let mut line = Vec::new();
    let mut any = false;
    loop {
        line.clear();
        // A header line is short: a longer one is junk, read in bounded steps.
        let n = input.by_ref().take(4096).read_until(b'\n', &mut line)?;
        if n == 0 {
            return if any {
                Err(io::Error::new(
                    io::ErrorKind::UnexpectedEof,
                    "end inside a header",
                ))
            } else {
                Ok(None)
            };
        }
        let text = String::from_utf8_lossy(&line);
        let text = text.trim_end_matches(['\r', '\n']);
        if text.is_empty() {
            if any {
                break;
            }
            continue;
        }
        any = true;
        if let Some((name, value)) = text.split_once(':') {
            if name.trim().eq_ignore_ascii_case("content-length") {
                length = Some(value.trim().parse::<usize>().map_err(|e| e.to_string()));
            }
        }
    }
    let length = match length {
        Some(Ok(n)) if n <= MAX_MESSAGE_BYTES => n,
        Some(Ok(n)) => {
            // Skip the body without holding it.
            io::copy(&mut input.by_ref().take(n as u64), &mut io::sink())?;
            return Err(io::Error::other(format!(
                "a message of {n} bytes (the most is {MAX_MESSAGE_BYTES})"
            )));
        }
        Some(Err(e)) => return Err(io::Error::other(format!("bad Content-Length: {e}"))),
        None => return Err(io::Error::other("a header without Content-Length")),
    };
    let mut body = Vec::with_capacity(length.min(1 << 20));
    input.by_ref().take(length as u64).read_to_end(&mut body)?;
    if body.len() < length {
        return Err(io::Error::new(
            io::ErrorKind::UnexpectedEof,
            "end inside a message",
        ));
    }
    Ok(Some(body))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(body: &str) -> String {
        format!("Content-Length: {}\r\n\r\n{body}", body.len())
    }

    #[test]
    fn bad_frames_are_reported_and_reading_goes_on() {
        let ok = r#"{"jsonrpc":"2.0","method":"initialized","params":{}}"#;
        let input = [
            frame("{not json"),
            "X-Junk: 1\r\n\r\n".to_string(),
            frame(ok),
            "Content-Length: 99999999999\r\n\r\n".to_string(),
        ]
        .concat();
        let (tx, rx) = unbounded();
        read_loop(&mut io::Cursor::new(input.into_bytes()), &tx);
        let methods: Vec<String> = rx
            .try_iter()
            .map(|m| match m {
                Message::Notification(n) => n.method,
                other => format!("{other:?}"),
            })
            .collect();
        assert_eq!(methods, [MALFORMED, MALFORMED, "initialized", MALFORMED]);
    }
}
