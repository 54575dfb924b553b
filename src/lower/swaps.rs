//! A mesh statement's `materials { "Name" material … }` applied to the
//! materials its file brings (an OBJ's libraries, a glTF's materials): a
//! material of that name is replaced by the scene's, and a name the file
//! does not have is a warning at the name.

use crate::check::MaterialSwap;
use crate::diag::{codes, did_you_mean, Diagnostic, Diagnostics};

/// The scene's material that replaces the file's material `name`, if the
/// statement replaces it.
pub fn replacing(swaps: &[MaterialSwap], name: &str) -> Option<usize> {
    swaps.iter().find(|s| s.name == name).map(|s| s.material)
}

/// Warns of each replaced name that none of the file's materials (`names`)
/// has, with the closest name it has; the file is called what the scene
/// calls it (`named`).
pub fn warn_unmatched<'a>(
    swaps: &[MaterialSwap],
    names: impl Iterator<Item = &'a str> + Clone,
    named: &str,
    warnings: &mut Diagnostics,
) {
    for swap in swaps {
        if names.clone().any(|n| n == swap.name) {
            continue;
        }
        let d = Diagnostic::warning(
            codes::NO_EFFECT,
            format!("`{named}` has no material `{}`", swap.name),
            swap.span,
        )
        .with_label("replaces nothing");
        let listed: Vec<&str> = names.clone().filter(|n| !n.is_empty()).take(8).collect();
        let d = match did_you_mean(&swap.name, names.clone()) {
            Some(near) => d.with_help(format!("did you mean `{near}`?")).with_fix(
                swap.span,
                format!("\"{}\"", near.replace('\\', "\\\\").replace('"', "\\\"")),
            ),
            None if listed.is_empty() => d.with_help("the file names none of its materials"),
            None => d.with_help(format!(
                "its materials are {}",
                listed
                    .iter()
                    .map(|n| format!("`{n}`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            )),
        };
        warnings.push(d);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::span::Span;

    fn swap(name: &str, material: usize) -> MaterialSwap {
        MaterialSwap {
            name: name.into(),
            span: Span::default(),
            material,
        }
    }

    #[test]
    fn a_name_is_replaced_only_where_it_is_written_exactly() {
        let swaps = [swap("Leaf", 3), swap("Bark", 5)];
        assert_eq!(replacing(&swaps, "Bark"), Some(5));
        assert_eq!(replacing(&swaps, "leaf"), None);
        let mut w = Diagnostics::new();
        warn_unmatched(&swaps, ["Leaves", "Bark"].into_iter(), "t.obj", &mut w);
        assert_eq!(w.items.len(), 1, "{:?}", w.items);
        let text = format!("{:?}", w.items[0]);
        assert!(
            text.contains("no material `Leaf`") && text.contains("Leaves"),
            "{text}"
        );
    }
}
