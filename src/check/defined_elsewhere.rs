//! A name reported unknown that the scene does define, where its use
//! cannot see it: after the use, or in a loop's body or a function. The
//! error says where the definition is, instead of a did-you-mean to some
//! other name, and the definition is not reported unused as well.

use super::*;

impl Checker<'_> {
    /// Tells each name reported unknown that the scene defines where it
    /// could not be seen (after its use, or in a loop's or function's own
    /// scope) where its definition is, instead of a did-you-mean to another
    /// name; the definition is then not reported unused as well.
    pub(super) fn defined_elsewhere(&mut self) {
        for (name, at) in std::mem::take(&mut self.env.unknown_names) {
            let named = |d: &&Definition| {
                use SymbolKind::*;
                let kinds = [Constant, Function, Texture, Parameter, LoopVariable];
                d.name == name && d.name_span != at && kinds.contains(&d.kind)
            };
            let Some((id, def_span)) = (self.env.symbols.iter())
                .find(|(_, d)| named(d))
                .map(|(id, d)| (id, d.name_span))
            else {
                continue;
            };
            let source = self.sources.get(def_span.file);
            let line = source.line_of(def_span.start as usize) + 1;
            let later = def_span.file == at.file && def_span.start > at.start;
            let help = match later {
                true => format!("`{name}` is defined below, at line {line}: a name is seen only by what follows its definition; move the definition above this use"),
                false => {
                    let place = match def_span.file == at.file {
                        true => format!("line {line}"),
                        false => format!("line {line} of {}", source.path.display()),
                    };
                    format!("`{name}` is defined at {place}, where this use does not see it: a loop's variable and the names defined in its body, and a function's parameters, are seen only there")
                }
            };
            let unknown = (self.diags.items.iter_mut())
                .find(|d| d.code == codes::UNKNOWN_NAME && d.span == Some(at));
            if let Some(d) = unknown {
                d.help = Some(help);
                d.label = "not seen here".to_string();
                d.fix = None;
                d.secondary.push((def_span, "defined here".to_string()));
                self.env.symbols.excuse(id);
            }
        }
    }
}
