//! Formatting through `ptsc fmt`'s library (`crate::format`): the whole
//! document, or the statements a range touches. A document with a syntax
//! error is left as it is (its diagnostics say why), as `ptsc fmt` does.

use super::convert::Lines;
use super::state::{Answer, Server};
use crate::format::{format_range, format_text, FormatError};
use lsp_types as lsp;
use serde_json::Value;

fn refused(server: &Server, e: FormatError) -> Answer {
    if let FormatError::Bug(why) = &e {
        server.log(
            lsp::MessageType::ERROR,
            format!("not formatted (a bug in ptsc fmt, please report): {why}"),
        );
    }
    Ok(serde_json::json!([]))
}

/// `textDocument/formatting`.
pub fn whole(server: &Server, p: lsp::DocumentFormattingParams) -> Answer {
    edit(server, &p.text_document.uri, |text, _| {
        format_text(text).map(|f| (0..text.len(), f))
    })
}

/// `textDocument/rangeFormatting`: the top-level statements the range touches.
pub fn range(server: &Server, p: lsp::DocumentRangeFormattingParams) -> Answer {
    edit(server, &p.text_document.uri, |text, lines| {
        format_range(text, lines.offset(p.range.start), lines.offset(p.range.end))
    })
}

/// The one edit `format` gives for the open document `uri` (the bytes it
/// replaces and their new text): none when it changes nothing.
fn edit(
    server: &Server,
    uri: &lsp::Uri,
    format: impl FnOnce(&str, &Lines) -> Result<(std::ops::Range<usize>, String), FormatError>,
) -> Answer {
    let Some(doc) = server.documents.get(uri.as_str()) else {
        return Ok(Value::Null);
    };
    let lines = Lines {
        text: &doc.text,
        index: &doc.index,
        encoding: server.encoding,
    };
    let (replaced, text) = match format(&doc.text, &lines) {
        Ok(r) => r,
        Err(e) => return refused(server, e),
    };
    if replaced.is_empty() && text.is_empty()
        || doc.text.get(replaced.clone()) == Some(text.as_str())
    {
        return Ok(serde_json::json!([]));
    }
    let edit = lsp::TextEdit {
        range: lines.range(replaced.start, replaced.end),
        new_text: text,
    };
    serde_json::to_value(vec![edit]).map_err(|e| (-32603, e.to_string()))
}
