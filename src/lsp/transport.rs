//! The stdio transport: JSON-RPC messages framed by `Content-Length`
//! headers, read on one thread and written on another. Unlike
//! `lsp_server::Connection::stdio`, a malformed frame or payload does not
//! end the session: it becomes a [`MALFORMED`] notification for the main
//! loop to report, and reading goes on with the next frame. A body that
//! is not JSON, or JSON that is not a message, is also answered as
//! JSON-RPC 2.0 requires: an error response (parse error, invalid request)
//! whose id is `null` when the body gives none, which `lsp_server`'s
//! `Response` cannot hold, so the reader hands it to the writer as JSON.
//! A frame may claim at most [`MAX_MESSAGE_BYTES`], and its body is read
//! as it comes, never allocated from the claim alone.

use crossbeam_channel::{never, select, unbounded, Receiver, Sender};
use lsp_server::{Connection, ErrorCode, Message, Notification};
use serde_json::{json, Value};
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
    let (errors, refused) = unbounded::<Value>();
    let reader = thread::spawn(move || read_loop(&mut io::stdin().lock(), &to_main, &errors));
    let writer = thread::spawn(move || write_loop(&mut io::stdout().lock(), &from_main, refused));
    (Connection { sender, receiver }, Threads { reader, writer })
}

/// Writes the main loop's messages and the reader's error responses to
/// `out` until the main loop is gone.
fn write_loop(out: &mut impl Write, from_main: &Receiver<Message>, mut refused: Receiver<Value>) {
    loop {
        let written = select! {
            recv(from_main) -> m => match m {
                Ok(m) => m.write(out),
                // The session is over: the errors already queued still go.
                Err(_) => {
                    for e in refused.try_iter() {
                        let _ = write_json(out, &e);
                    }
                    let _ = out.flush();
                    return;
                }
            },
            recv(refused) -> e => match e {
                Ok(e) => write_json(out, &e),
                // The reader has ended: only the main loop's messages remain.
                Err(_) => {
                    refused = never();
                    Ok(())
                }
            },
        };
        if written.and_then(|()| out.flush()).is_err() {
            return;
        }
    }
}

/// One JSON-RPC value as a frame.
fn write_json(out: &mut impl Write, value: &Value) -> io::Result<()> {
    let body = value.to_string();
    write!(out, "Content-Length: {}\r\n\r\n{body}", body.len())
}

/// Reads messages from `input` until it ends (or the main loop is gone);
/// a body that is not a message is answered on `errors`.
pub fn read_loop(input: &mut impl BufRead, to_main: &Sender<Message>, errors: &Sender<Value>) {
    loop {
        let message = match read_frame(input) {
            Ok(None) => return,
            Ok(Some(body)) => match parse(&body) {
                Ok(m) => m,
                Err((response, why)) => {
                    let _ = errors.send(response);
                    malformed(why)
                }
            },
            Err(e) if e.kind() == io::ErrorKind::UnexpectedEof => return,
            Err(e) => malformed(e.to_string()),
        };
        let exit = matches!(&message, Message::Notification(n) if n.method == "exit");
        if to_main.send(message).is_err() || exit {
            return;
        }
    }
}

/// The message in `body`, or the error response it gets and why.
fn parse(body: &[u8]) -> Result<Message, (Value, String)> {
    let value = serde_json::from_slice::<Value>(body).map_err(|e| {
        let why = format!("not JSON: {e}");
        (refusal(Value::Null, ErrorCode::ParseError, &why), why)
    })?;
    // The id is echoed where the body has a usable one (a request whose
    // method or params are wrong), else it is null, as JSON-RPC says.
    let id = match value.get("id") {
        Some(id @ (Value::Number(_) | Value::String(_))) => id.clone(),
        _ => Value::Null,
    };
    serde_json::from_value::<Message>(value).map_err(|e| {
        let why = format!("not a JSON-RPC message: {e}");
        (refusal(id, ErrorCode::InvalidRequest, &why), why)
    })
}

/// A JSON-RPC error response to the request `id`.
fn refusal(id: Value, code: ErrorCode, message: &str) -> Value {
    json!({ "jsonrpc": "2.0", "id": id, "error": { "code": code as i32, "message": message } })
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
        let (errors, _) = unbounded();
        read_loop(&mut io::Cursor::new(input.into_bytes()), &tx, &errors);
        let methods: Vec<String> = rx
            .try_iter()
            .map(|m| match m {
                Message::Notification(n) => n.method,
                other => format!("{other:?}"),
            })
            .collect();
        assert_eq!(methods, [MALFORMED, MALFORMED, "initialized", MALFORMED]);
    }

    #[test]
    fn a_body_that_is_not_a_message_is_answered_with_an_error_and_a_null_id() {
        let bodies = [
            "{not json",
            "[1, 2]",
            r#"{"jsonrpc":"2.0","id":7,"method":3}"#,
            r#"{"jsonrpc":"2.0","method":"initialized","params":{}}"#,
        ];
        let input: String = bodies.iter().map(|b| frame(b)).collect();
        let (tx, rx) = unbounded();
        let (errors, refused) = unbounded();
        read_loop(&mut io::Cursor::new(input.into_bytes()), &tx, &errors);
        let answers: Vec<(Value, i64)> = refused
            .try_iter()
            .map(|e| (e["id"].clone(), e["error"]["code"].as_i64().unwrap()))
            .collect();
        let expected = [
            (Value::Null, -32700),
            (Value::Null, -32600),
            (json!(7), -32600),
        ];
        assert_eq!(answers, expected);
        // Each is still reported to the main loop, and reading went on.
        assert_eq!(rx.try_iter().count(), 4);
    }

    #[test]
    fn the_writer_frames_the_readers_errors_beside_the_main_loops_messages() {
        let (sender, from_main) = unbounded::<Message>();
        let (errors, refused) = unbounded();
        errors
            .send(json!({ "jsonrpc": "2.0", "id": null }))
            .unwrap();
        drop(errors);
        sender
            .send(Notification::new("m".into(), json!({})).into())
            .unwrap();
        drop(sender);
        let mut out = Vec::new();
        write_loop(&mut out, &from_main, refused);
        let out = String::from_utf8(out).unwrap();
        let null = r#"{"id":null,"jsonrpc":"2.0"}"#;
        let framed = format!("Content-Length: {}\r\n\r\n{null}", null.len());
        assert!(out.contains(&framed), "{out}");
        assert!(out.contains(r#""method":"m""#), "{out}");
    }
}
