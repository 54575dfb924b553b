//! `ptsc lsp` driven as an editor drives it: the real binary spoken to
//! over stdio (Content-Length frames of JSON-RPC), and the same server in
//! process over `lsp_server`'s in-memory connection. Covered: the position
//! encoding negotiated and columns counted in it, diagnostics published
//! under each file's own URI and cleared by edits (incremental and whole),
//! hover, completion, definition and references across an include, rename,
//! outline, colours, quick fixes, formatting (as `ptsc fmt`), a server
//! that survives malformed input, panicking requests and huge documents,
//! the exit codes, and a fuzz of every request at random positions over
//! every example scene.

use serde_json::{json, Value};
use std::collections::VecDeque;
use std::io::{BufRead, BufReader, Read, Write};
use std::path::Path;
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc;
use std::time::Duration;

/// The agreement of what the editor shows with `ptsc check`.
mod verdict;

/// How long one wait for the server may take before the test fails.
const TIMEOUT: Duration = Duration::from_secs(20);

/// JSON-RPC's code for a request that failed inside the server (a panic).
const INTERNAL_ERROR: i64 = -32603;

// ---------------------------------------------------------------------------
// The client.

/// How the client reaches the server.
enum Link {
    /// `ptsc lsp` as a child process.
    Process { child: Child, stdin: ChildStdin },
    /// `ptsc::lsp::serve` on a thread of this process.
    Memory {
        sender: crossbeam_channel::Sender<lsp_server::Message>,
        thread: std::thread::JoinHandle<ptsc::lsp::Ending>,
    },
}

/// An editor's end of a session: requests answered in turn, the
/// notifications the server sends collected until asked for.
struct Client {
    link: Option<Link>,
    incoming: mpsc::Receiver<Value>,
    /// Messages read and not yet asked for.
    pending: VecDeque<Value>,
    /// Every `window/logMessage` text seen.
    log: Vec<String>,
    next_id: i64,
    /// Whether positions count UTF-8 bytes (else UTF-16 units).
    utf8: bool,
}

/// Reads Content-Length frames from `out` and sends their bodies on.
fn read_frames(out: impl Read, to_test: mpsc::Sender<Value>) {
    let mut out = BufReader::new(out);
    loop {
        let mut length = None;
        loop {
            let mut line = String::new();
            if out.read_line(&mut line).unwrap_or(0) == 0 {
                return;
            }
            let line = line.trim_end();
            if line.is_empty() {
                break;
            }
            if let Some(n) = line.strip_prefix("Content-Length:") {
                length = Some(n.trim().parse::<usize>().expect("a length"));
            }
        }
        let mut body = vec![0; length.expect("the server sends Content-Length")];
        if out.read_exact(&mut body).is_err() {
            return;
        }
        let message = serde_json::from_slice(&body).expect("the server sends JSON");
        if to_test.send(message).is_err() {
            return;
        }
    }
}

impl Client {
    /// Starts `ptsc lsp` with the environment variables `env`.
    fn spawn(env: &[(&str, &str)]) -> Client {
        let mut child = Command::new(env!("CARGO_BIN_EXE_ptsc"))
            .arg("lsp")
            .envs(env.iter().copied())
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("ptsc lsp starts");
        let stdin = child.stdin.take().unwrap();
        let stdout = child.stdout.take().unwrap();
        let (tx, incoming) = mpsc::channel();
        std::thread::spawn(move || read_frames(stdout, tx));
        Client::new(Link::Process { child, stdin }, incoming)
    }

    /// Starts `ptsc::lsp::serve` on a thread, over an in-memory connection.
    fn in_memory() -> Client {
        let (server, client) = lsp_server::Connection::memory();
        let thread = std::thread::spawn(move || ptsc::lsp::serve(&server));
        let (tx, incoming) = mpsc::channel();
        let receiver = client.receiver;
        std::thread::spawn(move || {
            for message in receiver {
                let value = serde_json::to_value(message).unwrap();
                if tx.send(value).is_err() {
                    return;
                }
            }
        });
        let link = Link::Memory {
            sender: client.sender,
            thread,
        };
        Client::new(link, incoming)
    }

    fn new(link: Link, incoming: mpsc::Receiver<Value>) -> Client {
        Client {
            link: Some(link),
            incoming,
            pending: VecDeque::new(),
            log: Vec::new(),
            next_id: 0,
            utf8: false,
        }
    }

    /// A started server, initialized (offering UTF-8 positions or not).
    fn start(utf8: bool) -> Client {
        let mut c = Client::spawn(&[]);
        c.initialize(utf8);
        c
    }

    /// `initialize` then `initialized`; the result of `initialize`.
    fn initialize(&mut self, utf8: bool) -> Value {
        let mut capabilities = json!({});
        if utf8 {
            capabilities = json!({ "general": { "positionEncodings": ["utf-8", "utf-16"] } });
        }
        let params = json!({ "processId": null, "rootUri": null, "capabilities": capabilities });
        let result = self.ok("initialize", params);
        self.utf8 = result["capabilities"]["positionEncoding"] == "utf-8";
        self.notify("initialized", json!({}));
        result
    }

    /// Sends one message.
    fn send(&mut self, message: Value) {
        match self.link.as_mut().expect("the session is open") {
            Link::Process { stdin, .. } => {
                let body = serde_json::to_vec(&message).unwrap();
                let mut frame = format!("Content-Length: {}\r\n\r\n", body.len()).into_bytes();
                frame.extend(body);
                Self::write(stdin, &frame);
            }
            Link::Memory { sender, .. } => {
                let message = serde_json::from_value(message).expect("a JSON-RPC message");
                sender.send(message).expect("the server is listening");
            }
        }
    }

    /// Writes raw bytes to the server's stdin (malformed frames).
    fn send_raw(&mut self, bytes: &[u8]) {
        match self.link.as_mut() {
            Some(Link::Process { stdin, .. }) => Self::write(stdin, bytes),
            _ => panic!("raw bytes need the process"),
        }
    }

    fn write(stdin: &mut ChildStdin, bytes: &[u8]) {
        stdin.write_all(bytes).expect("the server reads its stdin");
        stdin.flush().unwrap();
    }

    fn notify(&mut self, method: &str, params: Value) {
        self.send(json!({ "jsonrpc": "2.0", "method": method, "params": params }));
    }

    /// Sends a request without waiting; its id.
    fn send_request(&mut self, method: &str, params: Value) -> i64 {
        self.next_id += 1;
        let id = self.next_id;
        self.send(json!({ "jsonrpc": "2.0", "id": id, "method": method, "params": params }));
        id
    }

    /// Sends a request and waits for its response (the whole message).
    fn request(&mut self, method: &str, params: Value) -> Value {
        let id = self.send_request(method, params);
        self.response(id)
    }

    /// The response to request `id`.
    fn response(&mut self, id: i64) -> Value {
        self.wait_for(&format!("the response to request {id}"), |m| {
            m.get("method").is_none() && m["id"] == id
        })
    }

    /// The result of a request that must succeed.
    fn ok(&mut self, method: &str, params: Value) -> Value {
        let response = self.request(method, params);
        assert!(
            response.get("error").is_none(),
            "{method} failed: {response}"
        );
        response["result"].clone()
    }

    /// The next message from the server, within the timeout.
    fn next_message(&mut self, what: &str) -> Value {
        match self.incoming.recv_timeout(TIMEOUT) {
            Ok(m) => {
                if m["method"] == "window/logMessage" {
                    self.log
                        .push(m["params"]["message"].as_str().unwrap_or("").into());
                }
                m
            }
            Err(e) => panic!(
                "waiting for {what}: {e} (the server hung or ended); unread: {:?}; log: {:?}",
                self.pending, self.log
            ),
        }
    }

    /// The first message (already read or still to come) `wanted` accepts,
    /// taken out of the queue.
    fn wait_for(&mut self, what: &str, wanted: impl Fn(&Value) -> bool) -> Value {
        if let Some(i) = self.pending.iter().position(&wanted) {
            return self.pending.remove(i).unwrap();
        }
        loop {
            let m = self.next_message(what);
            if wanted(&m) {
                return m;
            }
            self.pending.push_back(m);
        }
    }

    /// The params of the next `publishDiagnostics` for `uri` that `wanted`
    /// accepts; earlier ones for `uri` are dropped.
    fn diagnostics(&mut self, uri: &str, wanted: impl Fn(&Value) -> bool) -> Value {
        let is_for = |m: &Value| {
            m["method"] == "textDocument/publishDiagnostics" && m["params"]["uri"] == uri
        };
        loop {
            let m = self.wait_for(&format!("diagnostics of {uri}"), is_for);
            if wanted(&m["params"]) {
                return m["params"].clone();
            }
        }
    }

    /// The diagnostics of version `version` of the open document `uri`.
    fn diagnostics_of_version(&mut self, uri: &str, version: i64) -> Vec<Value> {
        let p = self.diagnostics(uri, |p| p["version"] == version);
        p["diagnostics"].as_array().unwrap().clone()
    }

    /// Opens `text` as `uri` (version 1) and returns its diagnostics.
    fn open(&mut self, uri: &str, text: &str) -> Vec<Value> {
        self.notify(
            "textDocument/didOpen",
            json!({ "textDocument": { "uri": uri, "languageId": "pts", "version": 1, "text": text } }),
        );
        self.diagnostics_of_version(uri, 1)
    }

    /// A position in `text` in this session's encoding.
    fn pos(&self, text: &str, offset: usize) -> Value {
        position(text, offset, self.utf8)
    }

    /// A request about the position of byte `offset` of `uri`'s `text`.
    fn at(&mut self, method: &str, uri: &str, text: &str, offset: usize) -> Value {
        let position = self.pos(text, offset);
        self.ok(
            method,
            json!({ "textDocument": { "uri": uri }, "position": position }),
        )
    }

    /// `shutdown` then `exit`: the process's exit code.
    fn shutdown_and_exit(mut self) -> i32 {
        assert_eq!(self.ok("shutdown", Value::Null), Value::Null);
        self.notify("exit", Value::Null);
        self.wait_exit()
    }

    /// Waits for the process to end: its exit code.
    fn wait_exit(mut self) -> i32 {
        let Some(Link::Process { mut child, stdin }) = self.link.take() else {
            panic!("not a process");
        };
        drop(stdin);
        let t0 = std::time::Instant::now();
        loop {
            if let Some(status) = child.try_wait().unwrap() {
                return status.code().unwrap_or(-1);
            }
            if t0.elapsed() > TIMEOUT {
                let _ = child.kill();
                panic!("the server did not exit");
            }
            std::thread::sleep(Duration::from_millis(10));
        }
    }

    /// `shutdown` then `exit` in process: how `serve` ended.
    fn end_in_memory(mut self) -> ptsc::lsp::Ending {
        assert_eq!(self.ok("shutdown", Value::Null), Value::Null);
        self.notify("exit", Value::Null);
        let Some(Link::Memory { sender, thread }) = self.link.take() else {
            panic!("not in memory");
        };
        drop(sender);
        let t0 = std::time::Instant::now();
        while !thread.is_finished() {
            assert!(t0.elapsed() < TIMEOUT, "serve did not return");
            std::thread::sleep(Duration::from_millis(10));
        }
        thread.join().expect("serve does not panic")
    }
}

impl Drop for Client {
    fn drop(&mut self) {
        if let Some(Link::Process { mut child, .. }) = self.link.take() {
            let _ = child.kill();
            let _ = child.wait();
        }
    }
}

// ---------------------------------------------------------------------------
// Texts, positions and edits.

/// The protocol position of byte `offset` of `text`.
fn position(text: &str, offset: usize, utf8: bool) -> Value {
    let line_start = text[..offset].rfind('\n').map_or(0, |i| i + 1);
    let column = &text[line_start..offset];
    let character = if utf8 {
        column.len()
    } else {
        column.encode_utf16().count()
    };
    json!({ "line": text[..offset].matches('\n').count(), "character": character })
}

/// The byte offset of a protocol position in `text` (exact: a test's
/// positions name character boundaries).
fn offset(text: &str, p: &Value, utf8: bool) -> usize {
    let line = p["line"].as_u64().unwrap() as usize;
    let character = p["character"].as_u64().unwrap() as usize;
    let start: usize = text.split_inclusive('\n').take(line).map(str::len).sum();
    let mut counted = 0;
    for (i, c) in text[start..].char_indices() {
        if counted == character {
            return start + i;
        }
        counted += if utf8 { c.len_utf8() } else { c.len_utf16() };
    }
    assert_eq!(counted, character, "a position past the text");
    text.len()
}

/// `text` with the protocol edits `edits` applied.
fn apply_edits(text: &str, edits: &[Value], utf8: bool) -> String {
    let mut ranges: Vec<(usize, usize, &str)> = edits
        .iter()
        .map(|e| {
            let r = &e["range"];
            (
                offset(text, &r["start"], utf8),
                offset(text, &r["end"], utf8),
                e["newText"].as_str().unwrap(),
            )
        })
        .collect();
    ranges.sort_by_key(|r| std::cmp::Reverse(r.0));
    let mut out = text.to_string();
    for (start, end, new) in ranges {
        out.replace_range(start..end, new);
    }
    out
}

/// The byte offset of the `n`th (from 0) `needle` in `text`.
fn nth(text: &str, needle: &str, n: usize) -> usize {
    text.match_indices(needle)
        .nth(n)
        .unwrap_or_else(|| panic!("no {needle} #{n} in {text}"))
        .0
}

/// The `file:` URI of a path.
fn uri(path: &Path) -> String {
    url::Url::from_file_path(path).unwrap().to_string()
}

/// A scene's folder with `files`, and the URI of each file.
fn folder(files: &[(&str, &str)]) -> (tempfile::TempDir, Vec<String>) {
    let dir = crate::temp_dir_with(files);
    let uris = files
        .iter()
        .map(|(n, _)| uri(&dir.path().join(n)))
        .collect();
    (dir, uris)
}

/// The diagnostics that are errors.
fn errors(diagnostics: &[Value]) -> Vec<&Value> {
    diagnostics.iter().filter(|d| d["severity"] == 1).collect()
}

/// A diagnostic's code.
fn code(d: &Value) -> &str {
    d["code"].as_str().unwrap_or("")
}

/// The lines of a scene that is clean once its one mistake is fixed.
const CAMERA_AND_LIGHT: &str = "camera { position <0, 1, 5> look_at <0, 0, 0> }\n\
point_light { position <0, 4, 2> intensity rgb 20 }\n";

// ---------------------------------------------------------------------------
// Over stdio: the binary.

#[test]
fn initialize_picks_utf8_when_the_client_offers_it() {
    let mut c = Client::spawn(&[]);
    let result = c.initialize(true);
    assert_eq!(result["capabilities"]["positionEncoding"], "utf-8");
    assert_eq!(result["serverInfo"]["name"], "ptsc");
    assert_eq!(c.shutdown_and_exit(), 0);
}

#[test]
fn initialize_falls_back_on_utf16() {
    let mut c = Client::spawn(&[]);
    let result = c.initialize(false);
    assert_eq!(result["capabilities"]["positionEncoding"], "utf-16");
    assert_eq!(c.shutdown_and_exit(), 0);
}

/// A scene whose one mistake (`radus`) follows multi-byte characters on
/// its line.
fn scene_with_multibyte_mistake() -> String {
    format!("{CAMERA_AND_LIGHT}/* é𝄞 */ sphere {{ center <0, 0, 0> radus 1 }}\n")
}

/// Opens the scene above; checks the mistake's diagnostic is at the
/// columns the session's encoding counts. The URI and text.
fn open_multibyte_mistake(c: &mut Client, dir: &Path) -> (String, String) {
    let text = scene_with_multibyte_mistake();
    let uri = uri(&dir.join("scene.pts"));
    let diagnostics = c.open(&uri, &text);
    let errors = errors(&diagnostics);
    assert_eq!(errors.len(), 1, "{diagnostics:?}");
    let d = errors[0];
    assert_eq!(code(d), "pts::check::unknown_param");
    let at = nth(&text, "radus", 0);
    let line = &text[text[..at].rfind('\n').unwrap() + 1..];
    let before = &line[..line.find("radus").unwrap()];
    let column = if c.utf8 {
        before.len()
    } else {
        before.encode_utf16().count()
    };
    // é is 2 bytes, 1 unit; 𝄞 is 4 bytes, 2 units: the two counts differ.
    assert_eq!(
        d["range"],
        json!({ "start": { "line": 2, "character": column },
                "end": { "line": 2, "character": column + 5 } }),
        "in {}",
        if c.utf8 { "UTF-8" } else { "UTF-16" }
    );
    (uri, text)
}

#[test]
fn diagnostic_columns_count_the_negotiated_encoding_and_an_incremental_fix_clears_them() {
    for utf8 in [true, false] {
        let dir = tempfile::tempdir().unwrap();
        let mut c = Client::start(utf8);
        let (uri, text) = open_multibyte_mistake(&mut c, dir.path());
        let at = nth(&text, "radus", 0);
        let range = json!({ "start": c.pos(&text, at), "end": c.pos(&text, at + 5) });
        c.notify(
            "textDocument/didChange",
            json!({ "textDocument": { "uri": uri, "version": 2 },
                    "contentChanges": [{ "range": range, "text": "radius" }] }),
        );
        let after = c.diagnostics_of_version(&uri, 2);
        assert_eq!(after, Vec::<Value>::new(), "utf8 {utf8}");
        // The server's text is the one fixed here: a hover on `radius`
        // finds the parameter where this text has it.
        let fixed = text.replace("radus", "radius");
        let hover = c.at(
            "textDocument/hover",
            &uri,
            &fixed,
            nth(&fixed, "radius", 0) + 2,
        );
        assert!(hover["contents"]["value"]
            .as_str()
            .unwrap()
            .contains("**radius**"));
        assert_eq!(c.shutdown_and_exit(), 0);
    }
}

#[test]
fn a_whole_text_change_clears_the_diagnostics() {
    let dir = tempfile::tempdir().unwrap();
    let mut c = Client::start(false);
    let (uri, text) = open_multibyte_mistake(&mut c, dir.path());
    c.notify(
        "textDocument/didChange",
        json!({ "textDocument": { "uri": uri, "version": 2 },
                "contentChanges": [{ "text": text.replace("radus", "radius") }] }),
    );
    assert_eq!(c.diagnostics_of_version(&uri, 2), Vec::<Value>::new());
    // And back: the mistake again, the diagnostic again.
    c.notify(
        "textDocument/didChange",
        json!({ "textDocument": { "uri": uri, "version": 3 },
                "contentChanges": [{ "text": text }] }),
    );
    assert_eq!(errors(&c.diagnostics_of_version(&uri, 3)).len(), 1);
}

#[test]
fn an_included_files_mistake_is_published_under_its_own_uri() {
    let lib = "material red { diffuse rgb <1, 0, 0> }\nsphere { center <0, 0, 0> radus 2 }\n";
    let scene = format!("include \"lib.ptsi\"\n{CAMERA_AND_LIGHT}sphere {{ center <0, 1, 0> radius 1 material red }}\n");
    let (_dir, uris) = folder(&[("scene.pts", &scene), ("lib.ptsi", lib)]);
    let mut c = Client::start(true);
    c.notify(
        "textDocument/didOpen",
        json!({ "textDocument": { "uri": uris[0], "languageId": "pts", "version": 1, "text": scene } }),
    );
    let published = c.diagnostics(&uris[1], |p| {
        !p["diagnostics"].as_array().unwrap().is_empty()
    });
    let diagnostics = published["diagnostics"].as_array().unwrap();
    assert_eq!(diagnostics.len(), 1, "{diagnostics:?}");
    let d = &diagnostics[0];
    assert_eq!(code(d), "pts::check::unknown_param");
    let at = nth(lib, "radus", 0);
    assert_eq!(d["range"]["start"], position(lib, at, true));
    let related = d["relatedInformation"]
        .as_array()
        .expect("related information");
    let included = related
        .iter()
        .find(|r| r["message"] == "included from")
        .expect("an `included from`");
    assert_eq!(included["location"]["uri"], uris[0]);
    let line = included["location"]["range"]["start"]["line"].clone();
    assert_eq!(line, 0, "the include is the scene's first line");
    // The scene itself has nothing to say.
    assert_eq!(c.diagnostics_of_version(&uris[0], 1), Vec::<Value>::new());
}

#[test]
fn hover_explains_parameters_constants_and_functions() {
    let text = format!(
        "let r = 2 * 3;\n{CAMERA_AND_LIGHT}sphere {{ center <0, sqrt(4), 0> radius r }}\nsphere {{ center <0, 0, r> radius 0.5 }}\n"
    );
    let (_dir, uris) = folder(&[("scene.pts", &text)]);
    let mut c = Client::start(false);
    c.open(&uris[0], &text);
    let markdown = |h: &Value| h["contents"]["value"].as_str().unwrap().to_string();

    let radius = nth(&text, "radius", 0);
    let h = c.at("textDocument/hover", &uris[0], &text, radius + 1);
    assert_eq!(h["contents"]["kind"], "markdown");
    let m = markdown(&h);
    assert!(m.starts_with("**radius** — "), "{m}");
    assert!(m.contains("number") && m.contains("in `sphere`"), "{m}");
    assert_eq!(
        h["range"],
        json!({ "start": c.pos(&text, radius), "end": c.pos(&text, radius + 6) })
    );

    let r_use = nth(&text, "radius r", 0) + "radius ".len();
    let m = markdown(&c.at("textDocument/hover", &uris[0], &text, r_use));
    assert!(m.contains("**r** (constant) = `6`"), "{m}");
    assert!(m.contains("used 2 times"), "{m}");

    let sqrt = nth(&text, "sqrt", 0);
    let m = markdown(&c.at("textDocument/hover", &uris[0], &text, sqrt + 2));
    assert!(
        m.contains("sqrt(x)") && m.contains("built-in function"),
        "{m}"
    );

    // Between statements: nothing.
    let blank = text.find("\ncamera").unwrap();
    assert_eq!(
        c.at("textDocument/hover", &uris[0], &text, blank),
        Value::Null
    );
}

/// The items of a completion answer.
fn items(answer: &Value) -> Vec<Value> {
    let list = answer.get("items").unwrap_or(answer);
    list.as_array().expect("completion items").clone()
}

fn item<'a>(items: &'a [Value], label: &str) -> &'a Value {
    items
        .iter()
        .find(|i| i["label"] == label)
        .unwrap_or_else(|| panic!("no `{label}` in {items:?}"))
}

#[test]
fn completion_in_a_block_offers_its_missing_parameters() {
    let text = format!("{CAMERA_AND_LIGHT}sphere {{ radius 1  }}\n");
    let (_dir, uris) = folder(&[("scene.pts", &text)]);
    let mut c = Client::start(false);
    c.open(&uris[0], &text);
    let cursor = nth(&text, "radius 1 ", 0) + "radius 1 ".len();
    let items = items(&c.at("textDocument/completion", &uris[0], &text, cursor));
    let center = item(&items, "center");
    // A parameter given once may not be given again: not offered.
    assert!(!items.iter().any(|i| i["label"] == "radius"), "{items:?}");
    // A vector parameter is a snippet with placeholders.
    assert_eq!(center["insertTextFormat"], 2);
    let insert = center["textEdit"]["newText"].as_str().unwrap();
    assert!(insert.starts_with("center <${1:"), "{insert}");
    assert_eq!(center["kind"], 10, "a property");
}

#[test]
fn completion_of_a_material_offers_the_scenes_and_its_includes() {
    let lib = "material from_lib { diffuse rgb 0.5 }\n";
    let text = format!(
        "include \"lib.ptsi\"\nmaterial red {{ diffuse rgb <1, 0, 0> }}\n{CAMERA_AND_LIGHT}sphere {{ center <0, 0, 0> radius 1 material  }}\n"
    );
    let (_dir, uris) = folder(&[("scene.pts", &text), ("lib.ptsi", lib)]);
    let mut c = Client::start(false);
    c.open(&uris[0], &text);
    let cursor = nth(&text, "material  }", 0) + "material ".len();
    let items = items(&c.at("textDocument/completion", &uris[0], &text, cursor));
    let labels: Vec<&str> = items.iter().filter_map(|i| i["label"].as_str()).collect();
    assert!(labels.contains(&"red"), "{labels:?}");
    assert!(labels.contains(&"from_lib"), "{labels:?}");
    assert!(!labels.contains(&"sphere"), "not a statement: {labels:?}");
}

/// A scene using a material defined in `lib.ptsi`, twice.
fn scene_and_library() -> (String, String) {
    let lib = "// shared materials\nmaterial red { diffuse rgb <1, 0, 0> }\n".to_string();
    let scene = format!(
        "include \"lib.ptsi\"\n{CAMERA_AND_LIGHT}sphere {{ center <0, 0, 0> radius 1 material red }}\nsphere {{ center <2, 0, 0> radius 1 material red }}\n"
    );
    (scene, lib)
}

#[test]
fn definition_and_references_cross_an_include() {
    let (scene, lib) = scene_and_library();
    let (_dir, uris) = folder(&[("scene.pts", &scene), ("lib.ptsi", &lib)]);
    let mut c = Client::start(false);
    c.open(&uris[0], &scene);

    let use_ = nth(&scene, "material red", 1) + "material r".len();
    let def = c.at("textDocument/definition", &uris[0], &scene, use_);
    assert_eq!(def["uri"], uris[1]);
    let name = nth(&lib, "material red", 0) + "material ".len();
    assert_eq!(
        def["range"],
        json!({ "start": position(&lib, name, false), "end": position(&lib, name + 3, false) })
    );

    let p = c.pos(&scene, use_);
    let refs = c.ok(
        "textDocument/references",
        json!({ "textDocument": { "uri": uris[0] }, "position": p,
                "context": { "includeDeclaration": true } }),
    );
    let refs = refs.as_array().unwrap();
    let in_file = |u: &str| refs.iter().filter(|r| r["uri"] == u).count();
    assert_eq!((in_file(&uris[0]), in_file(&uris[1])), (2, 1), "{refs:?}");
    let refs = c.ok(
        "textDocument/references",
        json!({ "textDocument": { "uri": uris[0] }, "position": p,
                "context": { "includeDeclaration": false } }),
    );
    assert_eq!(refs.as_array().unwrap().len(), 2);

    let edit = c.ok(
        "textDocument/rename",
        json!({ "textDocument": { "uri": uris[0] }, "position": p, "newName": "crimson" }),
    );
    let changes = &edit["changes"];
    let scene_edits = changes[&uris[0]].as_array().expect("the scene's edits");
    let lib_edits = changes[&uris[1]].as_array().expect("the library's edits");
    assert_eq!(
        apply_edits(&scene, scene_edits, false),
        scene.replace("material red", "material crimson")
    );
    assert_eq!(
        apply_edits(&lib, lib_edits, false),
        lib.replace("material red", "material crimson")
    );

    let path = nth(&scene, "lib.ptsi", 0) + 2;
    let def = c.at("textDocument/definition", &uris[0], &scene, path);
    assert_eq!(def["uri"], uris[1]);
    assert_eq!(def["range"]["start"], json!({ "line": 0, "character": 0 }));
}

#[test]
fn rename_edits_the_definition_and_every_use() {
    let text = format!(
        "let size = 1;\n{CAMERA_AND_LIGHT}sphere {{ center <0, 0, 0> radius size }}\nsphere {{ center <0, size, 0> radius 0.5 }}\n"
    );
    let (_dir, uris) = folder(&[("scene.pts", &text)]);
    let mut c = Client::start(false);
    c.open(&uris[0], &text);
    let at = c.pos(&text, nth(&text, "size", 1) + 1);
    let doc = json!({ "uri": uris[0] });

    let range = c.ok(
        "textDocument/prepareRename",
        json!({ "textDocument": doc, "position": at }),
    );
    let start = nth(&text, "size", 1);
    assert_eq!(
        range,
        json!({ "start": c.pos(&text, start), "end": c.pos(&text, start + 4) })
    );

    let edit = c.ok(
        "textDocument/rename",
        json!({ "textDocument": doc, "position": at, "newName": "scale" }),
    );
    let edits = edit["changes"][&uris[0]]
        .as_array()
        .expect("edits of the scene");
    assert_eq!(edits.len(), 3, "{edit}");
    assert_eq!(
        apply_edits(&text, edits, false),
        text.replace("size", "scale")
    );

    let refused_keyword = c.request(
        "textDocument/rename",
        json!({ "textDocument": doc, "position": at, "newName": "let" }),
    );
    let e = &refused_keyword["error"];
    assert!(e["message"].as_str().unwrap().contains("keyword"), "{e}");
    assert!(refused_keyword.get("result").is_none());

    // A predefined name would be hidden where the scene uses it (`x.x`).
    for predefined in ["x", "pi", "frame"] {
        let refused = c.request(
            "textDocument/rename",
            json!({ "textDocument": doc, "position": at, "newName": predefined }),
        );
        let e = &refused["error"];
        assert!(e["message"].as_str().unwrap().contains("predefined"), "{e}");
    }
}

#[test]
fn document_symbols_outline_the_scene() {
    let text = format!(
        "{CAMERA_AND_LIGHT}material m {{ diffuse rgb 0.5 }}\nsphere {{ center <0, 0, 0> radius 1 material m }}\ngroup pair {{\n  sphere {{ center <1, 0, 0> radius 0.2 }}\n  box {{ min <0, 0, 0> max <1, 1, 1> }}\n}}\n"
    );
    let (_dir, uris) = folder(&[("scene.pts", &text)]);
    let mut c = Client::start(false);
    c.open(&uris[0], &text);
    let symbols = c.ok(
        "textDocument/documentSymbol",
        json!({ "textDocument": { "uri": uris[0] } }),
    );
    let symbols = symbols.as_array().unwrap();
    let names: Vec<&str> = symbols
        .iter()
        .map(|s| s["name"].as_str().unwrap())
        .collect();
    for wanted in ["camera", "point_light", "material m", "sphere"] {
        assert!(names.contains(&wanted), "no {wanted} in {names:?}");
    }
    let group = symbols
        .iter()
        .find(|s| s["name"] == "group pair")
        .unwrap_or_else(|| panic!("no group in {names:?}"));
    let children: Vec<&str> = group["children"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["name"].as_str().unwrap())
        .collect();
    assert_eq!(children, ["sphere", "box"]);
    // Each symbol's name is inside its range.
    let camera = &symbols[names.iter().position(|n| *n == "camera").unwrap()];
    assert_eq!(
        camera["range"]["start"],
        json!({ "line": 0, "character": 0 })
    );
}

#[test]
fn colours_are_swatches_and_picked_colours_are_written_back() {
    let text = format!(
        "{CAMERA_AND_LIGHT}sphere {{ center <0, 0, 0> radius 1 material {{ diffuse rgb <1, 0, 0> }} }}\n"
    );
    let (_dir, uris) = folder(&[("scene.pts", &text)]);
    let mut c = Client::start(false);
    c.open(&uris[0], &text);
    let colours = c.ok(
        "textDocument/documentColor",
        json!({ "textDocument": { "uri": uris[0] } }),
    );
    let colours = colours.as_array().unwrap();
    let start = nth(&text, "rgb <1", 0);
    let red = colours
        .iter()
        .find(|c| c["range"]["start"] == position(&text, start, false))
        .unwrap_or_else(|| panic!("no swatch at the red: {colours:?}"));
    let channel = |name: &str| red["color"][name].as_f64().unwrap();
    assert!((channel("red") - 1.0).abs() < 1e-3, "{red}");
    assert!(
        channel("green").abs() < 1e-3 && channel("blue").abs() < 1e-3,
        "{red}"
    );
    assert_eq!(
        red["range"]["end"],
        position(&text, start + "rgb <1, 0, 0>".len(), false)
    );

    let presented = c.ok(
        "textDocument/colorPresentation",
        json!({ "textDocument": { "uri": uris[0] },
                "color": { "red": 0.0, "green": 1.0, "blue": 0.0, "alpha": 1.0 },
                "range": red["range"] }),
    );
    let label = presented[0]["label"].as_str().unwrap();
    assert_eq!(label, "rgb <0, 1, 0>");
    assert_eq!(presented[0]["textEdit"]["range"], red["range"]);
}

/// Asks for the fixes at the first of `diagnostics` of `code` in `text`
/// (open as `uri`, version `version`), applies the first, and checks the
/// fixed text has no error of that code. The fixed text and its
/// diagnostics.
fn fix_and_recheck(
    c: &mut Client,
    (uri, text, version): (&str, &str, i64),
    diagnostics: &[Value],
    code_: &str,
) -> (String, Vec<Value>) {
    let d = diagnostics
        .iter()
        .find(|d| code(d) == code_)
        .unwrap_or_else(|| panic!("no {code_} in {diagnostics:?}"));
    let actions = c.ok(
        "textDocument/codeAction",
        json!({ "textDocument": { "uri": uri }, "range": d["range"],
                "context": { "diagnostics": [d] } }),
    );
    let actions = actions.as_array().expect("actions");
    assert_eq!(actions.len(), 1, "{actions:?}");
    let action = &actions[0];
    assert_eq!(action["kind"], "quickfix");
    assert_eq!(action["diagnostics"][0]["code"], code_);
    let edits = action["edit"]["changes"][uri].as_array().expect("an edit");
    let fixed = apply_edits(text, edits, c.utf8);
    c.notify(
        "textDocument/didChange",
        json!({ "textDocument": { "uri": uri, "version": version + 1 },
                "contentChanges": [{ "text": fixed }] }),
    );
    let after = c.diagnostics_of_version(uri, version + 1);
    assert!(
        !after.iter().any(|d| code(d) == code_),
        "{code_} still there after the fix: {fixed}\n{after:?}"
    );
    (fixed, after)
}

#[test]
fn quick_fixes_replace_misspelt_and_povray_words() {
    let text = format!(
        "{CAMERA_AND_LIGHT}/* é𝄞 */ sphere {{ center <0, 0, 0> radus 1 }}\nlight_source {{ position <2, 4, 2> intensity rgb 5 }}\n"
    );
    let (_dir, uris) = folder(&[("scene.pts", &text)]);
    let uri = uris[0].as_str();
    let mut c = Client::start(false);
    let diagnostics = c.open(uri, &text);
    let (once, diagnostics) = fix_and_recheck(
        &mut c,
        (uri, &text, 1),
        &diagnostics,
        "pts::check::unknown_param",
    );
    assert!(once.contains("/* é𝄞 */ sphere { center <0, 0, 0> radius 1 }"));
    let (twice, diagnostics) = fix_and_recheck(
        &mut c,
        (uri, &once, 2),
        &diagnostics,
        "pts::check::foreign_block",
    );
    assert!(
        twice.contains("\npoint_light { position <2, 4, 2>"),
        "{twice}"
    );
    assert_eq!(diagnostics, Vec::<Value>::new());
}

#[test]
fn formatting_gives_what_ptsc_fmt_gives() {
    let text = "camera{position <0,1,5>   look_at<0,0,0>}\n\n\n\npoint_light {position <0,4,2> intensity rgb 20}\nlet  k=2 ;\nsphere { center <0,0,0>\n radius k*0.5 material { diffuse rgb <1,0,0> } }\n";
    let (_dir, uris) = folder(&[("scene.pts", text)]);
    let mut c = Client::start(false);
    c.open(&uris[0], text);
    let edits = c.ok(
        "textDocument/formatting",
        json!({ "textDocument": { "uri": uris[0] },
                "options": { "tabSize": 4, "insertSpaces": true } }),
    );
    let formatted = apply_edits(text, edits.as_array().unwrap(), false);
    let mut fmt = Command::new(env!("CARGO_BIN_EXE_ptsc"))
        .args(["fmt", "-"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    fmt.stdin
        .take()
        .unwrap()
        .write_all(text.as_bytes())
        .unwrap();
    let out = fmt.wait_with_output().unwrap();
    assert!(out.status.success());
    let expected = String::from_utf8(out.stdout).unwrap();
    assert_ne!(expected, text, "the scene is messy");
    assert_eq!(formatted, expected);

    // Formatted already: nothing to do.
    c.notify(
        "textDocument/didChange",
        json!({ "textDocument": { "uri": uris[0], "version": 2 },
                "contentChanges": [{ "text": formatted }] }),
    );
    let again = c.ok(
        "textDocument/formatting",
        json!({ "textDocument": { "uri": uris[0] },
                "options": { "tabSize": 4, "insertSpaces": true } }),
    );
    assert_eq!(again, json!([]));
}

#[test]
fn typing_a_word_key_by_key_ends_on_the_last_versions_diagnostics() {
    let text = format!("{CAMERA_AND_LIGHT}sphere {{ center <0, 0, 0>  }}\n");
    let (_dir, uris) = folder(&[("scene.pts", &text)]);
    let mut c = Client::start(false);
    assert!(
        !errors(&c.open(&uris[0], &text)).is_empty(),
        "no radius yet"
    );
    let mut at = nth(&text, "0>  }", 0) + "0> ".len();
    let mut typed = text.clone();
    let mut version = 1;
    for key in "radius 2".chars() {
        version += 1;
        let p = position(&typed, at, false);
        c.notify(
            "textDocument/didChange",
            json!({ "textDocument": { "uri": uris[0], "version": version },
                    "contentChanges": [{ "range": { "start": p, "end": p }, "text": key.to_string() }] }),
        );
        typed.insert(at, key);
        at += key.len_utf8();
    }
    assert_eq!(
        c.diagnostics_of_version(&uris[0], version),
        Vec::<Value>::new()
    );
    // No older version is published after the newest.
    c.ok(
        "textDocument/hover",
        json!({ "textDocument": { "uri": uris[0] }, "position": { "line": 0, "character": 0 } }),
    );
    std::thread::sleep(Duration::from_millis(300));
    while let Ok(m) = c.incoming.try_recv() {
        if m["method"] == "textDocument/publishDiagnostics" && m["params"]["uri"] == uris[0] {
            assert_eq!(m["params"]["version"], version, "{m}");
        }
    }
    let hover = c.at(
        "textDocument/hover",
        &uris[0],
        &typed,
        nth(&typed, "radius", 0),
    );
    assert!(hover["contents"]["value"]
        .as_str()
        .unwrap()
        .contains("**radius**"));
}

#[test]
fn an_open_included_file_wins_over_the_disk() {
    let lib_on_disk =
        "material red { diffuse rgb <1, 0, 0> }\nsphere { center <0, 0, 0> radus 2 }\n";
    let (scene, _) = scene_and_library();
    let (dir, uris) = folder(&[("scene.pts", &scene), ("lib.ptsi", lib_on_disk)]);
    let mut c = Client::start(false);
    c.open(&uris[0], &scene);
    let on_disk = c.diagnostics(&uris[1], |p| {
        p["diagnostics"].as_array().unwrap().len() == 1
    });
    assert_eq!(on_disk["version"], Value::Null, "not open: no version");

    // The editor's text of the library, fixed and not saved.
    let fixed = lib_on_disk.replace("radus", "radius");
    c.notify(
        "textDocument/didOpen",
        json!({ "textDocument": { "uri": uris[1], "languageId": "pts", "version": 7, "text": fixed } }),
    );
    let p = c.diagnostics(&uris[1], |p| p["version"] == 7);
    assert_eq!(
        p["diagnostics"],
        json!([]),
        "the scene's check reads the editor's text"
    );

    // Broken again in the editor: the scene's check says so, under the library's URI.
    c.notify(
        "textDocument/didChange",
        json!({ "textDocument": { "uri": uris[1], "version": 8 },
                "contentChanges": [{ "text": lib_on_disk.replace("radus", "radiuss") }] }),
    );
    let p = c.diagnostics(&uris[1], |p| {
        p["version"] == 8 && p["diagnostics"] != json!([])
    });
    let d = &p["diagnostics"][0];
    assert_eq!(code(d), "pts::check::unknown_param");
    // A name only the scene defines is not an error in the library.
    assert!(p["diagnostics"].as_array().unwrap().len() == 1, "{p}");

    // Closed: the disk again.
    std::fs::write(dir.path().join("lib.ptsi"), &fixed).unwrap();
    c.notify(
        "textDocument/didClose",
        json!({ "textDocument": { "uri": uris[1] } }),
    );
    c.diagnostics(&uris[1], |p| p["diagnostics"] == json!([]));
    let p = c.diagnostics(&uris[0], |p| p["version"] == 1);
    assert_eq!(p["diagnostics"], json!([]));
}

#[test]
fn a_watched_file_changed_on_disk_rechecks_the_scenes_that_read_it() {
    let lib = "material red { diffuse rgb <1, 0, 0> }\n";
    let (scene, _) = scene_and_library();
    let (dir, uris) = folder(&[("scene.pts", &scene), ("lib.ptsi", lib)]);
    let mut c = Client::start(false);
    assert_eq!(c.open(&uris[0], &scene), Vec::<Value>::new());
    std::fs::write(
        dir.path().join("lib.ptsi"),
        "material blue { diffuse rgb <0, 0, 1> }\n",
    )
    .unwrap();
    c.notify(
        "workspace/didChangeWatchedFiles",
        json!({ "changes": [{ "uri": uris[1], "type": 2 }] }),
    );
    let p = c.diagnostics(&uris[0], |p| p["diagnostics"] != json!([]));
    let codes: Vec<&str> = p["diagnostics"]
        .as_array()
        .unwrap()
        .iter()
        .map(code)
        .collect();
    assert!(
        !codes.is_empty() && codes.iter().all(|c| c.contains("material")),
        "{codes:?}"
    );
}

#[test]
fn uris_of_folders_with_spaces_and_accents_round_trip() {
    let root = tempfile::tempdir().unwrap();
    let dir = root.path().join("my scènes #1");
    std::fs::create_dir(&dir).unwrap();
    let (scene, lib) = scene_and_library();
    std::fs::write(dir.join("lib.ptsi"), &lib).unwrap();
    let scene_uri = uri(&dir.join("scene.pts"));
    assert!(scene_uri.contains("%20"), "{scene_uri}");
    let mut c = Client::start(true);
    assert_eq!(
        c.open(&scene_uri, &scene),
        Vec::<Value>::new(),
        "the include is found"
    );
    let use_ = nth(&scene, "material red", 0) + "material r".len();
    let def = c.at("textDocument/definition", &scene_uri, &scene, use_);
    assert_eq!(def["uri"], uri(&dir.join("lib.ptsi")));
}

#[test]
fn inlay_hints_folding_and_include_paths() {
    let text = format!(
        "let half = 1 / 2;\nlet one = 1;\n{CAMERA_AND_LIGHT}group g {{\n  sphere {{ center <0, 0, 0> radius half }}\n}}\ninstance g {{ translate <one, 0, 0> }}\ninclude \"\"\n"
    );
    let (_dir, uris) = folder(&[("scene.pts", &text), ("lib.ptsi", ""), ("other.txt", "")]);
    let mut c = Client::start(false);
    c.open(&uris[0], &text);
    let whole = json!({ "start": { "line": 0, "character": 0 }, "end": position(&text, text.len(), false) });
    let hints = c.ok(
        "textDocument/inlayHint",
        json!({ "textDocument": { "uri": uris[0] }, "range": whole }),
    );
    let hints = hints.as_array().unwrap();
    assert_eq!(
        hints.len(),
        1,
        "only where the value is not written: {hints:?}"
    );
    assert_eq!(hints[0]["label"], " = 0.5");
    assert_eq!(
        hints[0]["position"],
        position(&text, text.find(';').unwrap() + 1, false)
    );

    let folds = c.ok(
        "textDocument/foldingRange",
        json!({ "textDocument": { "uri": uris[0] } }),
    );
    let group_line = text[..text.find("group").unwrap()].matches('\n').count();
    assert!(
        folds
            .as_array()
            .unwrap()
            .iter()
            .any(|f| f["startLine"] == group_line && f["endLine"] == group_line + 2),
        "{folds}"
    );

    let quote = nth(&text, "include \"", 0) + "include \"".len();
    let items = items(&c.at("textDocument/completion", &uris[0], &text, quote));
    let labels: Vec<&str> = items.iter().filter_map(|i| i["label"].as_str()).collect();
    assert!(labels.contains(&"lib.ptsi"), "{labels:?}");
    assert!(!labels.contains(&"other.txt"), "{labels:?}");
}

#[test]
fn malformed_messages_are_logged_and_the_server_goes_on() {
    let mut c = Client::start(false);
    c.send_raw(b"Content-Length: 9\r\n\r\n{not json");
    c.send_raw(b"X-Junk: 1\r\n\r\n");
    c.send_raw(b"Content-Length: 1x\r\n\r\n");
    let result = c.ok(
        "textDocument/hover",
        json!({
        "textDocument": { "uri": "file:///nowhere/x.pts" },
        "position": { "line": 0, "character": 0 } }),
    );
    assert_eq!(result, Value::Null);
    let malformed = c.log.iter().filter(|l| l.contains("malformed")).count();
    assert_eq!(malformed, 3, "{:?}", c.log);
    assert_eq!(c.shutdown_and_exit(), 0);
}

#[test]
fn a_panicking_request_is_answered_with_an_error_and_the_server_goes_on() {
    let mut c = Client::spawn(&[("PTSC_LSP_TEST_PANIC", "1")]);
    c.initialize(false);
    let text = format!("{CAMERA_AND_LIGHT}sphere {{ center <0, 0, 0> radius 1 }}\n");
    let dir = tempfile::tempdir().unwrap();
    let uri = uri(&dir.path().join("scene.pts"));
    c.open(&uri, &text);
    for _ in 0..2 {
        let answer = c.request("$/ptsc/panic", json!({}));
        assert_eq!(answer["error"]["code"], INTERNAL_ERROR, "{answer}");
        assert!(c.log.iter().any(|l| l.contains("test hook panicked")));
        let h = c.at("textDocument/hover", &uri, &text, nth(&text, "radius", 0));
        assert!(h["contents"]["value"].as_str().unwrap().contains("radius"));
    }
    assert_eq!(c.shutdown_and_exit(), 0);
}

#[test]
fn the_panic_hook_is_off_without_its_variable() {
    let mut c = Client::start(false);
    let answer = c.request("$/ptsc/panic", json!({}));
    assert_eq!(answer["error"]["code"], -32601, "{answer}");
}

#[test]
fn unknown_methods_unopened_documents_and_wild_positions_are_answered() {
    let mut c = Client::start(true);
    let answer = c.request("textDocument/noSuchThing", json!({}));
    assert_eq!(answer["error"]["code"], -32601, "MethodNotFound: {answer}");
    let bad = c.request("textDocument/hover", json!({ "nonsense": true }));
    assert_eq!(bad["error"]["code"], -32602, "InvalidParams: {bad}");

    let unopened = json!({ "uri": "file:///nowhere/unopened.pts" });
    let far = json!({ "line": 99999, "character": 99999 });
    for method in [
        "textDocument/hover",
        "textDocument/completion",
        "textDocument/definition",
    ] {
        let r = c.ok(method, json!({ "textDocument": unopened, "position": far }));
        assert_eq!(r, Value::Null, "{method}");
    }
    let symbols = c.ok(
        "textDocument/documentSymbol",
        json!({ "textDocument": unopened }),
    );
    assert_eq!(symbols, Value::Null);

    let text = format!("{CAMERA_AND_LIGHT}sphere {{ center <0, 0, 0> radius 1 }} // é𝄞\n");
    let dir = tempfile::tempdir().unwrap();
    let uri = uri(&dir.path().join("scene.pts"));
    c.open(&uri, &text);
    let doc = json!({ "uri": uri });
    for p in [
        far.clone(),
        json!({ "line": 2, "character": 99999 }),
        json!({ "line": 4294967295u32, "character": 4294967295u32 }),
    ] {
        for method in [
            "textDocument/hover",
            "textDocument/completion",
            "textDocument/definition",
            "textDocument/prepareRename",
        ] {
            let r = c.request(method, json!({ "textDocument": doc, "position": p }));
            assert_ne!(r["error"]["code"], INTERNAL_ERROR, "{method} {p}: {r}");
        }
        let range = json!({ "start": p, "end": p });
        for method in [
            "textDocument/codeAction",
            "textDocument/inlayHint",
            "textDocument/rangeFormatting",
        ] {
            let r = c.request(
                method,
                json!({ "textDocument": doc, "range": range, "context": { "diagnostics": [] },
                        "options": { "tabSize": 4, "insertSpaces": true } }),
            );
            assert_ne!(r["error"]["code"], INTERNAL_ERROR, "{method} {p}: {r}");
        }
    }
    // A change far out of range appends at the end.
    c.notify(
        "textDocument/didChange",
        json!({ "textDocument": { "uri": uri, "version": 2 },
                "contentChanges": [{ "range": { "start": far, "end": far }, "text": "sphere { center <0, 2, 0> radius 1 }\n" }] }),
    );
    assert_eq!(c.diagnostics_of_version(&uri, 2), Vec::<Value>::new());
    assert_eq!(c.shutdown_and_exit(), 0);
}

#[test]
fn a_ten_megabyte_document_is_checked_and_hovered() {
    let mut text = String::from(CAMERA_AND_LIGHT);
    let mut i = 0;
    while text.len() < 10 << 20 {
        text.push_str(&format!("sphere {{ center <{i}, 0, 0> radius 0.25 }}\n"));
        i += 1;
    }
    let dir = tempfile::tempdir().unwrap();
    let uri = uri(&dir.path().join("big.pts"));
    let mut c = Client::start(false);
    c.notify(
        "textDocument/didOpen",
        json!({ "textDocument": { "uri": uri, "languageId": "pts", "version": 1, "text": text } }),
    );
    // Answered before the check is done, and after.
    let last = text.rfind("radius").unwrap();
    let h = c.request(
        "textDocument/hover",
        json!({ "textDocument": { "uri": uri }, "position": position(&text, last, false) }),
    );
    assert!(h.get("error").is_none(), "{h}");
    let diagnostics = c.diagnostics_of_version(&uri, 1);
    assert_eq!(errors(&diagnostics), Vec::<&Value>::new());
    let h = c.at("textDocument/hover", &uri, &text, last + 1);
    assert!(h["contents"]["value"]
        .as_str()
        .unwrap()
        .contains("**radius**"));
    assert_eq!(c.shutdown_and_exit(), 0);
}

#[test]
fn exit_after_shutdown_is_a_clean_end() {
    assert_eq!(Client::start(false).shutdown_and_exit(), 0);
}

#[test]
fn exit_without_shutdown_is_not() {
    let mut c = Client::start(false);
    c.notify("exit", Value::Null);
    assert_ne!(c.wait_exit(), 0);
}

#[test]
fn the_end_of_the_input_ends_the_server_uncleanly() {
    assert_ne!(Client::start(false).wait_exit(), 0);
}

#[test]
fn requests_after_shutdown_are_refused() {
    let mut c = Client::start(false);
    assert_eq!(c.ok("shutdown", Value::Null), Value::Null);
    let r = c.request(
        "textDocument/hover",
        json!({
        "textDocument": { "uri": "file:///x.pts" }, "position": { "line": 0, "character": 0 } }),
    );
    assert_eq!(r["error"]["code"], -32600, "InvalidRequest: {r}");
    c.notify("exit", Value::Null);
    assert_eq!(c.wait_exit(), 0);
}

#[test]
fn requests_before_initialize_are_refused() {
    let mut c = Client::spawn(&[]);
    let r = c.request("textDocument/hover", json!({}));
    assert_eq!(r["error"]["code"], -32002, "ServerNotInitialized: {r}");
    c.initialize(false);
    assert_eq!(c.shutdown_and_exit(), 0);
}

// ---------------------------------------------------------------------------
// In process: `ptsc::lsp::serve` over an in-memory connection.

#[test]
fn in_memory_session_hovers_and_ends_cleanly() {
    let text = format!("{CAMERA_AND_LIGHT}sphere {{ center <0, 0, 0> radius 1 }}\n");
    let mut c = Client::in_memory();
    let result = c.initialize(true);
    assert_eq!(result["capabilities"]["positionEncoding"], "utf-8");
    let uri = "untitled:Untitled-1";
    assert_eq!(c.open(uri, &text), Vec::<Value>::new());
    let h = c.at("textDocument/hover", uri, &text, nth(&text, "radius", 0));
    assert!(h["contents"]["value"]
        .as_str()
        .unwrap()
        .contains("**radius**"));
    assert_eq!(c.end_in_memory(), ptsc::lsp::Ending::Clean);
}

#[test]
fn in_memory_exit_without_shutdown_is_abrupt() {
    let mut c = Client::in_memory();
    c.initialize(false);
    c.notify("exit", Value::Null);
    let Some(Link::Memory { thread, .. }) = c.link.take() else {
        unreachable!()
    };
    assert_eq!(thread.join().unwrap(), ptsc::lsp::Ending::Abrupt);
}

/// A deterministic xorshift generator.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// A random position in `text` (UTF-16 columns): mostly at characters,
/// some inside a surrogate pair, some past a line's end or the text's.
fn random_position(rng: &mut Rng, text: &str) -> Value {
    let lines: Vec<&str> = text.split('\n').collect();
    match rng.below(10) {
        0..=5 => {
            let mut at = rng.below(text.len() + 1);
            while !text.is_char_boundary(at) {
                at -= 1;
            }
            position(text, at, false)
        }
        6 => {
            // Inside a character outside the BMP, where there is one.
            let astral: Vec<usize> = (text.char_indices())
                .filter(|(_, c)| c.len_utf16() == 2)
                .map(|(i, _)| i)
                .collect();
            if astral.is_empty() {
                return json!({ "line": 0, "character": 1 });
            }
            let at = astral[rng.below(astral.len())];
            let mut p = position(text, at, false);
            p["character"] = json!(p["character"].as_u64().unwrap() + 1);
            p
        }
        7 => {
            let line = rng.below(lines.len());
            json!({ "line": line, "character": lines[line].len() + 1 + rng.below(1000) })
        }
        8 => json!({ "line": lines.len() + rng.below(100_000), "character": rng.below(100) }),
        _ => json!({ "line": u32::MAX, "character": u32::MAX }),
    }
}

/// A scene of the odd texts the examples lack: multi-byte characters in
/// comments and strings, CRLF line ends, an unfinished block.
const ODD_SCENE: &str = "// é𝄞 ünïcödé 😀\r\nlet k = 2; /* 𝄞𝄞 */ let s = \"é😀\";\r\ncamera { position <0, 1, 5> look_at <0, 0, 0> }\r\nsphere { center <0, 𝄞k, 0> radus 1 material { diffuse rgb <1, 0.5, 0> } }\r\nlight_source { }\r\ngroup g { sphere { center <0,0,0> radius 1 } }\r\ninstance g { translate <1, 0, 0> }\r\nsphere { center <";

/// The requests the fuzz sends.
const FUZZED_METHODS: [&str; 11] = [
    "textDocument/hover",
    "textDocument/completion",
    "textDocument/definition",
    "textDocument/references",
    "textDocument/prepareRename",
    "textDocument/documentSymbol",
    "textDocument/foldingRange",
    "textDocument/documentColor",
    "textDocument/codeAction",
    "textDocument/inlayHint",
    "textDocument/rangeFormatting",
];

/// Texts the fuzz inserts: pieces of scenes, multi-byte characters,
/// unbalanced braces and quotes.
const FUZZED_INSERTS: [&str; 12] = [
    "",
    "{",
    "}",
    "\"",
    "𝄞",
    "é",
    "\r\n",
    "sphere { ",
    "material ",
    "<1, 2",
    "/* ",
    "let x = ",
];

/// Sends `count` random requests about `uri` (whose text is `text`) at
/// once, then checks each answer is not a panic; how many answers had
/// something in them, by method.
fn fuzz_requests(
    c: &mut Client,
    rng: &mut Rng,
    (uri, text): (&str, &str),
    count: usize,
    found: &mut std::collections::HashMap<&'static str, usize>,
) {
    let mut sent = Vec::new();
    for _ in 0..count {
        let method = FUZZED_METHODS[rng.below(FUZZED_METHODS.len())];
        let (a, b) = (random_position(rng, text), random_position(rng, text));
        let params = json!({
            "textDocument": { "uri": uri },
            "position": a,
            "range": { "start": a, "end": b },
            "context": { "includeDeclaration": rng.below(2) == 0, "diagnostics": [], "triggerKind": 1 },
            "options": { "tabSize": 4, "insertSpaces": true },
        });
        let id = c.send_request(method, params.clone());
        sent.push((id, method, params));
    }
    for (id, method, params) in sent {
        let r = c.response(id);
        assert!(
            r.get("error").is_none() || method == "textDocument/prepareRename",
            "{method} on {uri} at {params}: {r}"
        );
        assert_ne!(
            r["error"]["code"], INTERNAL_ERROR,
            "{method} on {uri} at {params}: {r}"
        );
        let something = match &r["result"] {
            Value::Null => false,
            Value::Array(a) => !a.is_empty(),
            Value::Object(o) => o.get("items").is_none_or(|i| i != &json!([])),
            _ => true,
        };
        *found.entry(method).or_default() += something as usize;
    }
}

#[test]
fn fuzzed_requests_over_every_example_are_answered_without_panics() {
    let mut scenes: Vec<(String, String)> =
        crate::files_below(&crate::root().join("examples"), "pts")
            .into_iter()
            .map(|p| (uri(&p), std::fs::read_to_string(&p).unwrap()))
            .collect();
    scenes.sort();
    assert!(scenes.len() > 10, "the examples are found");
    scenes.push(("untitled:odd".to_string(), ODD_SCENE.to_string()));

    let mut c = Client::in_memory();
    c.initialize(false);
    let mut found = std::collections::HashMap::new();
    for (n, (uri, text)) in scenes.iter().enumerate() {
        c.open(uri, text);
        let seed = 0x9E37_79B9_7F4A_7C15 ^ (n as u64 + 1).wrapping_mul(0x2545_F491_4F6C_DD1D);
        let mut rng = Rng(seed);
        // The large benchmark scene gets fewer: whole-text requests on it
        // take a while, and the small ones find more.
        let big = text.len() > 100_000;
        fuzz_requests(
            &mut c,
            &mut rng,
            (uri, text),
            if big { 40 } else { 200 },
            &mut found,
        );
        // Then edits, each answered from a check that may be older than
        // the text (the checks are debounced) or of a broken scene.
        let mut text = text.clone();
        for version in 2..if big { 2 } else { 12 } {
            let (a, b) = (rng.below(text.len() + 1), rng.below(text.len() + 1));
            let (mut start, mut end) = (a.min(b), a.max(b).min(a.min(b) + 40));
            while !text.is_char_boundary(start) {
                start -= 1;
            }
            while !text.is_char_boundary(end) {
                end -= 1;
            }
            let insert = FUZZED_INSERTS[rng.below(FUZZED_INSERTS.len())];
            let range = json!({ "start": position(&text, start, false), "end": position(&text, end, false) });
            c.notify(
                "textDocument/didChange",
                json!({ "textDocument": { "uri": uri, "version": version },
                        "contentChanges": [{ "range": range, "text": insert }] }),
            );
            text.replace_range(start..end, insert);
            fuzz_requests(&mut c, &mut rng, (uri, &text), 20, &mut found);
        }
        c.notify(
            "textDocument/didClose",
            json!({ "textDocument": { "uri": uri } }),
        );
    }
    let bugs: Vec<&String> = c.log.iter().filter(|l| l.contains("bug")).collect();
    assert!(bugs.is_empty(), "{bugs:?}");
    // The positions found names, parameters and blocks, not only nothing.
    for method in FUZZED_METHODS {
        if method != "textDocument/inlayHint" && method != "textDocument/rangeFormatting" {
            assert!(
                found.get(method).copied().unwrap_or(0) > 0,
                "{method}: {found:?}"
            );
        }
    }
    assert_eq!(c.end_in_memory(), ptsc::lsp::Ending::Clean);
}

#[test]
fn closing_a_scene_leaves_an_open_fragment_reported_by_its_own_check() {
    let lib = "sphere { radus 1 }\n";
    let scene = "include \"lib.ptsi\"\ncamera { position <0, 0, 5> look_at <0, 0, 0> }\npoint_light { position <0, 5, 0> intensity rgb 10 }\n";
    let (_dir, uris) = folder(&[("scene.pts", scene), ("lib.ptsi", lib)]);
    let mut c = Client::start(false);
    c.notify(
        "textDocument/didOpen",
        json!({ "textDocument": { "uri": uris[1], "languageId": "pts", "version": 3, "text": lib } }),
    );
    c.diagnostics(&uris[1], |p| {
        p["version"] == 3 && p["diagnostics"] != json!([])
    });
    c.open(&uris[0], scene);
    // The scene's check reports the fragment too (after the scene's own file).
    c.diagnostics(&uris[1], |p| p["version"] == 3);
    c.notify(
        "textDocument/didClose",
        json!({ "textDocument": { "uri": uris[0] } }),
    );
    // The scene's publication is cleared, then the fragment's own check speaks again.
    let p = c.diagnostics(&uris[1], |p| {
        p["version"] == 3 && p["diagnostics"] != json!([])
    });
    let codes: Vec<&str> = p["diagnostics"]
        .as_array()
        .unwrap()
        .iter()
        .map(code)
        .collect();
    assert!(codes.contains(&"pts::check::unknown_param"), "{codes:?}");
}
