//! `include "file"`: another file's statements, read through the
//! compile's `Files`, cycle-checked and bounded.

use super::*;

impl Checker<'_> {
    /// Adds to every diagnostic in an included file the chain of includes
    /// that led to it ("included from"), nearest first.
    pub(super) fn show_include_chains(&mut self) {
        for d in &mut self.diags.items {
            let Some(span) = d.span else { continue };
            let mut file = span.file;
            let mut depth = 0;
            while let Some(&site) = self.included_from.get(&file) {
                if !d.secondary.iter().any(|(s, _)| *s == site) {
                    d.secondary.push((site, "included from".to_string()));
                }
                file = site.file;
                depth += 1;
                if depth > MAX_INCLUDE_DEPTH {
                    break;
                }
            }
        }
    }

    pub(super) fn include(&mut self, path: &str, path_span: Span, file: FileId) {
        let target = folder_of(&self.sources, file).join(path);
        let canonical = self.files.canonical(&target);
        if let Some(pos) = self.include_stack.iter().position(|(p, _)| *p == canonical) {
            let mut d = Diagnostic::error(
                codes::INCLUDE_CYCLE,
                format!("`{path}` includes itself"),
                path_span,
            )
            .with_label("this include closes a cycle")
            .with_help("remove one of the includes in the cycle");
            for (_, s) in self.include_stack[pos + 1..].iter() {
                d = d.with_secondary(*s, "included from");
            }
            self.diags.push(d);
            return;
        }
        if self.include_stack.len() >= MAX_INCLUDE_DEPTH {
            self.diags.push(
                Diagnostic::error(
                    codes::INCLUDE_CYCLE,
                    "includes nested too deeply",
                    path_span,
                )
                .with_label(format!("more than {MAX_INCLUDE_DEPTH} levels"))
                .with_help("flatten the chain of includes"),
            );
            return;
        }
        // A file already read (an include in a loop, or included twice) is
        // not read again; but it is parsed again, which costs as many
        // statements as a parse's set-up plus one per 64 bytes (a typical
        // statement's size).
        if let Some(id) = self.sources.find(&target) {
            let bytes = self.sources.get(id).text.len() as u64;
            self.enter_loop(path_span);
            if self.charge_loop(INCLUDE_RUN_COST + bytes / STATEMENT_BYTES) {
                self.include_stack.push((canonical, path_span));
                self.run_file(id);
                self.include_stack.pop();
            }
            self.leave_loop();
            return;
        }
        let room = MAX_SCENE_BYTES.saturating_sub(self.sources.total_bytes() as u64);
        let bytes = match self.files.read(&target, room) {
            Ok(b) => b,
            Err(e) => {
                self.diags.push(not_included(path, &target, &e, path_span));
                return;
            }
        };
        if let Some(kind) = super::foreign_file::not_a_scene(&target, &bytes) {
            let d = super::foreign_file::not_a_scene_error(&target, kind, path_span);
            self.diags.push(d);
            // What the scene meant to include is missing: as after a
            // syntax error, the whole-scene checks would be noise.
            self.syntax_failed = true;
            return;
        }
        let (text, bad) = decode(bytes);
        let id = self.sources.add(target.clone(), text);
        self.included_from.insert(id, path_span);
        if let Some(at) = bad {
            self.diags.push(invalid_utf8(id, at));
        }
        self.include_stack.push((canonical, path_span));
        self.run_file(id);
        self.include_stack.pop();
    }
}

/// The error for an include of `path` (resolved to `target`) that could
/// not be read (`e`).
fn not_included(path: &str, target: &Path, e: &ReadError, path_span: Span) -> Diagnostic {
    let (reason, help) = match &e {
            // `colors.inc`, `textures.inc`: a POV-Ray scene's first lines.
            ReadError::NotFound if path.to_ascii_lowercase().ends_with(".inc") => (
                "not found".to_string(),
                "POV-Ray's own include files (colors.inc, textures.inc, …) have no ptsc version: write colours as `rgb <r, g, b>`"
                    .to_string(),
            ),
            ReadError::Unsaved => {
            // No folder, so no "looked for" path: one made up would name
            // a place that holds nothing.
            return Diagnostic::error(
                codes::INCLUDE_NOT_FOUND,
                format!("cannot include `{path}`: an unsaved document cannot include relative files"),
                path_span,
            )
            .with_label("the document has no folder yet")
            .with_help("save the document, or open the folder it belongs to as the workspace, and its includes are read from there");
        }
        ReadError::NotFound => (
                "not found".to_string(),
                "include paths are relative to the file that contains the `include`"
                    .to_string(),
            ),
            ReadError::NotRegular(FileKind::Folder) => (
                "it is a folder, not a file".to_string(),
                "include a `.pts` or `.ptsi` file".to_string(),
            ),
            ReadError::NotRegular(kind) => (
                format!("not a regular file: it is {kind}"),
                "devices, pipes and sockets are never read: include a file".to_string(),
            ),
            ReadError::TooLarge { size, .. } if *size <= MAX_SCENE_BYTES => (
                format!(
                    "the scene's files would hold more than {} of text together",
                    crate::source::human_bytes(MAX_SCENE_BYTES)
                ),
                "large generated geometry belongs in a mesh file (`mesh { file \"…\" }`)"
                    .to_string(),
            ),
            other => (
                other.to_string(),
                "large generated geometry belongs in a mesh file (`mesh { file \"…\" }`)"
                    .to_string(),
            ),
        };
    Diagnostic::error(
        codes::INCLUDE_NOT_FOUND,
        format!("cannot include `{path}`: {reason}"),
        path_span,
    )
    .with_label(format!("looked for {}", target.display()))
    .with_help(help)
}
