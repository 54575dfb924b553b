//! What the editor shows agrees with `ptsc check` (findings of a user
//! trial of the server): the files a diagnostic names, a document with no
//! folder, and JSON-RPC's answers to bodies that are not messages.

use super::*;

/// A started server whose workspace is `root` (a `file:` URI), or none.
fn start_in(root: Option<&str>) -> Client {
    let mut c = Client::spawn(&[]);
    let params = json!({ "processId": null, "rootUri": root, "capabilities": {} });
    c.ok("initialize", params);
    c.notify("initialized", json!({}));
    c
}

/// The messages of `diagnostics`.
fn messages(diagnostics: &[Value]) -> Vec<String> {
    (diagnostics.iter())
        .map(|d| d["message"].as_str().unwrap_or("").to_string())
        .collect()
}

#[test]
fn missing_files_are_named_as_written_as_check_names_them() {
    let text = format!(
        "{CAMERA_AND_LIGHT}plane {{ normal <0, 1, 0> material {{ diffuse image {{ file \"nothere.png\" }} }} }}\nmesh {{ file \"badidx.obj\" }}\n"
    );
    let files = [
        ("scene.pts", text.as_str()),
        ("badidx.obj", "v 0 0 0\nf 1 2 9\n"),
    ];
    let (dir, uris) = folder(&files);
    let mut c = start_in(None);
    let messages = messages(&c.open(&uris[0], &text));
    let folder = dir.path().to_string_lossy().into_owned();
    assert!(
        messages.iter().all(|m| !m.contains(&folder)),
        "{messages:?}"
    );
    let first = |m: &String| m.lines().next().unwrap_or("").to_string();
    let heads: Vec<String> = messages.iter().map(first).collect();
    assert!(
        heads
            .iter()
            .any(|m| m.starts_with("cannot load image `nothere.png`")),
        "{heads:?}"
    );
    assert!(
        heads
            .iter()
            .any(|m| m.starts_with("cannot load mesh `badidx.obj`")),
        "{heads:?}"
    );
}

const INCLUDING: &str = "include \"inc.ptsi\"\ncamera { position <0, 1, 5> look_at <0, 0, 0> }\npoint_light { position <0, 4, 2> intensity rgb 20 }\nsphere { center <0, 0, 0> radius k }\n";

#[test]
fn an_untitled_document_includes_from_the_workspace() {
    let (dir, _) = folder(&[("inc.ptsi", "let k = 2;\n")]);
    let mut c = start_in(Some(&uri(dir.path())));
    let diagnostics = c.open("untitled:Untitled-1", INCLUDING);
    assert_eq!(diagnostics, Vec::<Value>::new());
}

#[test]
fn an_untitled_document_without_a_workspace_says_it_cannot_include() {
    let mut c = start_in(None);
    let diagnostics = c.open("untitled:Untitled-1", INCLUDING);
    let includes: Vec<&Value> = (diagnostics.iter())
        .filter(|d| code(d) == "pts::check::include_not_found")
        .collect();
    assert_eq!(includes.len(), 1, "{diagnostics:?}");
    let message = includes[0]["message"].as_str().unwrap();
    assert!(message.contains("unsaved document"), "{message}");
    assert!(!message.contains("/untitled"), "{message}");
    let at = nth(INCLUDING, "\"inc.ptsi\"", 0);
    assert_eq!(includes[0]["range"]["start"], c.pos(INCLUDING, at));
}

#[test]
fn bodies_that_are_not_requests_get_json_rpc_errors_with_a_null_id() {
    let mut c = Client::start(false);
    let frame = |body: &str| format!("Content-Length: {}\r\n\r\n{body}", body.len());
    c.send_raw(frame("{not json").as_bytes());
    let parse = c.wait_for("a parse error", |m| m.get("error").is_some());
    assert_eq!(parse["id"], Value::Null);
    assert_eq!(parse["error"]["code"], -32700);
    c.send_raw(frame("[1, 2, 3]").as_bytes());
    let invalid = c.wait_for("an invalid request", |m| m.get("error").is_some());
    assert_eq!(invalid["id"], Value::Null);
    assert_eq!(invalid["error"]["code"], -32600);
    // The server goes on.
    let result = c.ok(
        "textDocument/hover",
        json!({ "textDocument": { "uri": "file:///nowhere/x.pts" },
                "position": { "line": 0, "character": 0 } }),
    );
    assert_eq!(result, Value::Null);
    assert_eq!(c.shutdown_and_exit(), 0);
}
