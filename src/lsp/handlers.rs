//! The requests the server answers, each from the document held and its
//! last check through `ide`: the protocol's types in and out.

use super::convert::Lines;
use super::position::Encoding;
use super::state::{Answer, Document, Server};
use crate::ide::{self, View};
use lsp_server::{ErrorCode, Request};
use lsp_types as lsp;
use serde_json::Value;
use std::collections::HashMap;

/// What the server can do.
pub fn capabilities(encoding: Encoding) -> lsp::ServerCapabilities {
    let sync = lsp::TextDocumentSyncOptions {
        open_close: Some(true),
        change: Some(lsp::TextDocumentSyncKind::INCREMENTAL),
        ..Default::default()
    };
    lsp::ServerCapabilities {
        position_encoding: Some(match encoding {
            Encoding::Utf8 => lsp::PositionEncodingKind::UTF8,
            Encoding::Utf16 => lsp::PositionEncodingKind::UTF16,
        }),
        text_document_sync: Some(lsp::TextDocumentSyncCapability::Options(sync)),
        hover_provider: Some(lsp::HoverProviderCapability::Simple(true)),
        completion_provider: Some(lsp::CompletionOptions {
            trigger_characters: Some(vec!["\"".into(), "/".into()]),
            ..Default::default()
        }),
        definition_provider: Some(lsp::OneOf::Left(true)),
        references_provider: Some(lsp::OneOf::Left(true)),
        rename_provider: Some(lsp::OneOf::Right(lsp::RenameOptions {
            prepare_provider: Some(true),
            work_done_progress_options: Default::default(),
        })),
        document_symbol_provider: Some(lsp::OneOf::Left(true)),
        color_provider: Some(lsp::ColorProviderCapability::Simple(true)),
        folding_range_provider: Some(lsp::FoldingRangeProviderCapability::Simple(true)),
        code_action_provider: Some(lsp::CodeActionProviderCapability::Simple(true)),
        document_formatting_provider: Some(lsp::OneOf::Left(true)),
        document_range_formatting_provider: Some(lsp::OneOf::Left(true)),
        inlay_hint_provider: Some(lsp::OneOf::Left(true)),
        ..Default::default()
    }
}

fn params<P: serde::de::DeserializeOwned>(req: Request) -> Result<P, (i32, String)> {
    serde_json::from_value(req.params).map_err(|e| {
        (
            ErrorCode::InvalidParams as i32,
            format!("bad parameters: {e}"),
        )
    })
}

fn json(v: impl serde::Serialize) -> Answer {
    serde_json::to_value(v).map_err(|e| (ErrorCode::InternalError as i32, e.to_string()))
}

/// Answers `req`.
pub fn handle(server: &Server, req: Request) -> Answer {
    match req.method.as_str() {
        "textDocument/hover" => hover(server, params(req)?),
        "textDocument/completion" => completion(server, params(req)?),
        "textDocument/definition" => definition(server, params(req)?),
        "textDocument/references" => references(server, params(req)?),
        "textDocument/prepareRename" => prepare_rename(server, params(req)?),
        "textDocument/rename" => rename(server, params(req)?),
        "textDocument/documentSymbol" => symbols(server, params(req)?),
        "textDocument/documentColor" => colors(server, params(req)?),
        "textDocument/colorPresentation" => presentation(params(req)?),
        "textDocument/foldingRange" => folding(server, params(req)?),
        "textDocument/codeAction" => actions(server, params(req)?),
        "textDocument/formatting" => super::format::whole(server, params(req)?),
        "textDocument/rangeFormatting" => super::format::range(server, params(req)?),
        "textDocument/inlayHint" => inlay_hints(server, params(req)?),
        // A test hook (tests/integration/lsp.rs): proves a panicking
        // request is answered and the server goes on.
        "$/ptsc/panic" if std::env::var_os("PTSC_LSP_TEST_PANIC").is_some() => {
            panic!("the test hook panicked")
        }
        other => Err((
            ErrorCode::MethodNotFound as i32,
            format!("ptsc does not answer `{other}`"),
        )),
    }
}

/// The document at a URI, its view and its lines; `None` for a document
/// not open (answered with nothing).
fn open<'a>(server: &'a Server, uri: &lsp::Uri) -> Option<(View<'a>, &'a Document, Lines<'a>)> {
    let (view, doc) = server.view(uri.as_str())?;
    let lines = Lines {
        text: &doc.text,
        index: &doc.index,
        encoding: server.encoding,
    };
    Some((view, doc, lines))
}

fn hover(server: &Server, p: lsp::HoverParams) -> Answer {
    let at = p.text_document_position_params;
    let Some((view, _, lines)) = open(server, &at.text_document.uri) else {
        return Ok(Value::Null);
    };
    let Some(h) = ide::hover::hover(view, lines.offset(at.position)) else {
        return Ok(Value::Null);
    };
    json(lsp::Hover {
        contents: lsp::HoverContents::Markup(lsp::MarkupContent {
            kind: lsp::MarkupKind::Markdown,
            value: h.markdown,
        }),
        range: Some(lines.range(h.range.start, h.range.end)),
    })
}

fn completion(server: &Server, p: lsp::CompletionParams) -> Answer {
    let at = p.text_document_position;
    let Some((view, _, lines)) = open(server, &at.text_document.uri) else {
        return Ok(Value::Null);
    };
    let list = |dir: &std::path::Path| -> Vec<(String, bool)> {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return Vec::new();
        };
        (entries.flatten().take(2000))
            .map(|e| {
                (
                    e.file_name().to_string_lossy().into_owned(),
                    e.file_type().is_ok_and(|t| t.is_dir()),
                )
            })
            .collect()
    };
    let items = ide::completion::complete(view, lines.offset(at.position), &list);
    use ide::completion::ItemKind as K;
    let items: Vec<lsp::CompletionItem> = (items.into_iter())
        .map(|i| lsp::CompletionItem {
            label: i.label.clone(),
            kind: Some(match i.kind {
                K::Keyword => lsp::CompletionItemKind::KEYWORD,
                K::Kind => lsp::CompletionItemKind::CLASS,
                K::Parameter => lsp::CompletionItemKind::PROPERTY,
                K::Value => lsp::CompletionItemKind::ENUM_MEMBER,
                K::Constant => lsp::CompletionItemKind::CONSTANT,
                K::Function => lsp::CompletionItemKind::FUNCTION,
                K::Material | K::Texture => lsp::CompletionItemKind::COLOR,
                K::Group => lsp::CompletionItemKind::MODULE,
                K::File => lsp::CompletionItemKind::FILE,
                K::Folder => lsp::CompletionItemKind::FOLDER,
            }),
            detail: i.detail,
            documentation: i.documentation.map(|d| {
                lsp::Documentation::MarkupContent(lsp::MarkupContent {
                    kind: lsp::MarkupKind::Markdown,
                    value: d,
                })
            }),
            sort_text: Some(format!("{}{}", i.sort, i.label)),
            insert_text_format: Some(if i.snippet {
                lsp::InsertTextFormat::SNIPPET
            } else {
                lsp::InsertTextFormat::PLAIN_TEXT
            }),
            text_edit: Some(lsp::CompletionTextEdit::Edit(lsp::TextEdit {
                range: lines.range(i.replace.start, i.replace.end),
                new_text: i.insert,
            })),
            ..Default::default()
        })
        .collect();
    json(lsp::CompletionResponse::List(lsp::CompletionList {
        is_incomplete: false,
        items,
    }))
}

/// A location of `ide` in the protocol's terms.
fn location(server: &Server, l: &ide::navigation::Location) -> Option<lsp::Location> {
    let uri = server.uri_of(&l.path)?;
    // An open document's text is the one its check read when it is fresh.
    let index = super::position::LineIndex::new(&l.text);
    let lines = Lines {
        text: &l.text,
        index: &index,
        encoding: server.encoding,
    };
    Some(lsp::Location {
        uri,
        range: lines.range(l.range.start, l.range.end),
    })
}

fn definition(server: &Server, p: lsp::GotoDefinitionParams) -> Answer {
    let at = p.text_document_position_params;
    let Some((view, _, lines)) = open(server, &at.text_document.uri) else {
        return Ok(Value::Null);
    };
    let found = ide::navigation::definition(view, lines.offset(at.position));
    match found.and_then(|l| location(server, &l)) {
        Some(l) => json(lsp::GotoDefinitionResponse::Scalar(l)),
        None => Ok(Value::Null),
    }
}

fn references(server: &Server, p: lsp::ReferenceParams) -> Answer {
    let at = p.text_document_position;
    let Some((view, _, lines)) = open(server, &at.text_document.uri) else {
        return Ok(Value::Null);
    };
    let found = ide::navigation::references(
        view,
        lines.offset(at.position),
        p.context.include_declaration,
    );
    json(
        found
            .iter()
            .filter_map(|l| location(server, l))
            .collect::<Vec<_>>(),
    )
}

fn prepare_rename(server: &Server, p: lsp::TextDocumentPositionParams) -> Answer {
    let Some((view, _, lines)) = open(server, &p.text_document.uri) else {
        return Ok(Value::Null);
    };
    match ide::navigation::prepare_rename(view, lines.offset(p.position)) {
        Ok(r) => json(lsp::PrepareRenameResponse::Range(
            lines.range(r.start, r.end),
        )),
        Err(e) => Err((ErrorCode::RequestFailed as i32, e)),
    }
}

// `WorkspaceEdit::changes` is keyed by `Uri` (lsp-types' choice); its
// interior cells cache its parsed parts, not part of its hash.
#[allow(clippy::mutable_key_type)]
fn rename(server: &Server, p: lsp::RenameParams) -> Answer {
    let at = p.text_document_position;
    let Some((view, _, lines)) = open(server, &at.text_document.uri) else {
        return Ok(Value::Null);
    };
    let edits = ide::navigation::rename(view, lines.offset(at.position), &p.new_name)
        .map_err(|e| (ErrorCode::RequestFailed as i32, e))?;
    let mut changes: HashMap<lsp::Uri, Vec<lsp::TextEdit>> = HashMap::new();
    for (l, new_text) in edits {
        if let Some(loc) = location(server, &l) {
            changes.entry(loc.uri).or_default().push(lsp::TextEdit {
                range: loc.range,
                new_text,
            });
        }
    }
    json(lsp::WorkspaceEdit {
        changes: Some(changes),
        ..Default::default()
    })
}

fn symbols(server: &Server, p: lsp::DocumentSymbolParams) -> Answer {
    let Some((_, doc, lines)) = open(server, &p.text_document.uri) else {
        return Ok(Value::Null);
    };
    fn convert(item: ide::outline::OutlineItem, lines: &Lines) -> lsp::DocumentSymbol {
        use ide::outline::SymbolClass as C;
        #[allow(deprecated)]
        lsp::DocumentSymbol {
            name: item.name,
            detail: None,
            kind: match item.class {
                C::Setting => lsp::SymbolKind::PROPERTY,
                C::Light => lsp::SymbolKind::EVENT,
                C::Object => lsp::SymbolKind::OBJECT,
                C::Material => lsp::SymbolKind::STRUCT,
                C::Texture => lsp::SymbolKind::STRUCT,
                C::Group => lsp::SymbolKind::NAMESPACE,
                C::Constant => lsp::SymbolKind::CONSTANT,
                C::Function => lsp::SymbolKind::FUNCTION,
                C::Other => lsp::SymbolKind::KEY,
            },
            tags: None,
            deprecated: None,
            range: lines.range(item.range.start, item.range.end),
            selection_range: lines.range(item.selection.start, item.selection.end),
            children: Some(
                item.children
                    .into_iter()
                    .map(|c| convert(c, lines))
                    .collect(),
            ),
        }
    }
    let items: Vec<_> = ide::outline::outline(&doc.text)
        .into_iter()
        .map(|i| convert(i, &lines))
        .collect();
    json(lsp::DocumentSymbolResponse::Nested(items))
}

fn colors(server: &Server, p: lsp::DocumentColorParams) -> Answer {
    let Some((_, doc, lines)) = open(server, &p.text_document.uri) else {
        return Ok(Value::Null);
    };
    let found: Vec<lsp::ColorInformation> = (ide::colors::colors(&doc.text).into_iter())
        .map(|c| {
            let [r, g, b] = c.linear.map(|v| ide::colors::to_srgb(v) as f32);
            lsp::ColorInformation {
                range: lines.range(c.range.start, c.range.end),
                color: lsp::Color {
                    red: r,
                    green: g,
                    blue: b,
                    alpha: 1.0,
                },
            }
        })
        .collect();
    json(found)
}

fn presentation(p: lsp::ColorPresentationParams) -> Answer {
    let c = p.color;
    let label = ide::colors::presentation([c.red as f64, c.green as f64, c.blue as f64]);
    json(vec![lsp::ColorPresentation {
        label: label.clone(),
        text_edit: Some(lsp::TextEdit {
            range: p.range,
            new_text: label,
        }),
        additional_text_edits: None,
    }])
}

fn folding(server: &Server, p: lsp::FoldingRangeParams) -> Answer {
    let Some((_, doc, lines)) = open(server, &p.text_document.uri) else {
        return Ok(Value::Null);
    };
    let folds: Vec<lsp::FoldingRange> = (ide::outline::folds(&doc.text).into_iter())
        .map(|f| {
            let (start, end) = (lines.position(f.range.start), lines.position(f.range.end));
            lsp::FoldingRange {
                start_line: start.line,
                end_line: end.line,
                kind: Some(if f.comment {
                    lsp::FoldingRangeKind::Comment
                } else {
                    lsp::FoldingRangeKind::Region
                }),
                ..Default::default()
            }
        })
        .collect();
    json(folds)
}

fn actions(server: &Server, p: lsp::CodeActionParams) -> Answer {
    let uri = p.text_document.uri;
    let Some((view, _, lines)) = open(server, &uri) else {
        return Ok(Value::Null);
    };
    let range = lines.offset(p.range.start)..lines.offset(p.range.end);
    let actions: Vec<lsp::CodeActionOrCommand> = (ide::actions::fixes(view, range).into_iter())
        .map(|fix| {
            let edit = lsp::TextEdit {
                range: lines.range(fix.range.start, fix.range.end),
                new_text: fix.replacement,
            };
            let diagnostic = super::convert::diagnostic(&fix.diagnostic, &lines, &mut |_| None);
            lsp::CodeActionOrCommand::CodeAction(lsp::CodeAction {
                title: fix.title,
                kind: Some(lsp::CodeActionKind::QUICKFIX),
                diagnostics: Some(vec![diagnostic]),
                edit: Some(lsp::WorkspaceEdit {
                    changes: Some(HashMap::from([(uri.clone(), vec![edit])])),
                    ..Default::default()
                }),
                is_preferred: Some(true),
                ..Default::default()
            })
        })
        .collect();
    json(actions)
}

fn inlay_hints(server: &Server, p: lsp::InlayHintParams) -> Answer {
    let Some((view, _, lines)) = open(server, &p.text_document.uri) else {
        return Ok(Value::Null);
    };
    let (Some(file), Some(compiled)) = (view.fresh_file(), view.compiled) else {
        return json(Vec::<lsp::InlayHint>::new());
    };
    let range = lines.offset(p.range.start)..lines.offset(p.range.end);
    let mut hints = Vec::new();
    for (_, def) in compiled.symbols.iter() {
        let (Some(value), true) = (&def.value, def.name_span.file == file) else {
            continue;
        };
        let end = def.span.end as usize;
        if !range.contains(&end) {
            continue;
        }
        // Only where the value is not written as it is (`let r = 2 * a;`).
        let statement = view.text.get(def.span.start as usize..end).unwrap_or("");
        let written = statement
            .split_once('=')
            .map_or("", |(_, v)| v)
            .trim()
            .trim_end_matches(';')
            .trim();
        if written == value || value.len() > 60 {
            continue;
        }
        hints.push(lsp::InlayHint {
            position: lines.position(end),
            label: lsp::InlayHintLabel::String(format!(" = {value}")),
            kind: None,
            text_edits: None,
            tooltip: None,
            padding_left: Some(true),
            padding_right: None,
            data: None,
        });
    }
    json(hints)
}
