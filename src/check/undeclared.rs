//! Names declared nowhere: whether the scene's text holds a name anywhere
//! but where it is used (a statement that did not parse, or code that did
//! not run, may declare it), and the error for a material declared
//! nowhere. Read by the end of the check and by the check of the code
//! that did not run.

use super::*;

impl Checker<'_> {
    /// The names of `uses` that the scene's text holds only at the places
    /// that use them (each place once, however many loop passes): no
    /// statement, parsed or not, declares them. One pass over the text.
    pub(super) fn written_only_at<'u>(
        &self,
        uses: &'u [crate::syntax::ast::Ident],
    ) -> HashSet<&'u str> {
        if uses.is_empty() {
            return HashSet::new();
        }
        let mut places: HashMap<&str, HashSet<Span>> = HashMap::new();
        for n in uses {
            places.entry(n.name.as_str()).or_default().insert(n.span);
        }
        let mut written: HashMap<&str, usize> = HashMap::new();
        for file in self.sources.files() {
            for word in words(&file.text).filter(|w| places.contains_key(w)) {
                *written.entry(word).or_default() += 1;
            }
        }
        (places.into_iter())
            .filter(|(name, at)| written.get(name).copied().unwrap_or(0) <= at.len())
            .map(|(name, _)| name)
            .collect()
    }

    /// The error for `name`, a material declared nowhere, with a
    /// did-you-mean (whose material then does not count as unused: the
    /// typo already explains it).
    pub(super) fn unknown_material(&mut self, name: &crate::syntax::ast::Ident) {
        let names = self.material_names.keys().map(String::as_str);
        let suggestion = (self.env)
            .suggest(&name.name, self.material_names.len(), names)
            .map(str::to_string);
        let help = match &suggestion {
            Some(s) => {
                // The typo already explains why it is not used.
                self.env.symbols.excuse(self.material_names[s].def);
                format!("did you mean `{s}`?")
            }
            None => format!(
                "declare it (anywhere in the scene): `material {} {{ diffuse rgb 0.8 }}`",
                name.name
            ),
        };
        let mut d = Diagnostic::error(
            codes::UNKNOWN_MATERIAL,
            format!("unknown material `{}`", name.name),
            name.span,
        )
        .with_label("no material with this name")
        .with_help(help);
        if let Some(s) = &suggestion {
            d = d.with_secondary(
                self.material_names[s].span,
                format!("`{s}` is declared here"),
            );
        }
        self.diags.push(d);
    }
}

/// The names written in `text`, in order (with empty pieces between
/// other characters): what a whole-name search compares.
pub(super) fn words(text: &str) -> impl Iterator<Item = &str> {
    text.split(|c: char| !(c.is_alphanumeric() || c == '_'))
}
