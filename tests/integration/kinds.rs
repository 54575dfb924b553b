//! The kind table (`check::kinds`) against what users read: every kind of
//! block and each of its parameters is in docs/language.md's tables, and an
//! unknown kind is answered from the table.

use ptsc::check::kinds::KINDS;

/// The part of docs/language.md that documents `kind`: its row in a table
/// of kinds (`| \`sphere\` | … |`), or the section whose heading names it
/// (`## \`camera { }\``, `### Environment`).
fn documentation_of<'a>(doc: &'a str, kind: &str) -> Option<&'a str> {
    let row = format!("| `{kind}` |");
    if let Some(line) = doc.lines().find(|l| l.starts_with(&row)) {
        return Some(line);
    }
    let heading = doc.lines().find(|l| {
        l.starts_with('#') && {
            let l = l.to_lowercase();
            l.contains(&format!("`{kind} {{ }}`"))
                || l.trim_start_matches('#').trim() == kind
                || l.ends_with(&format!(" {kind}"))
        }
    })?;
    let start = doc.find(heading)? + heading.len();
    let end = doc[start..].find("\n#").map_or(doc.len(), |e| start + e);
    Some(&doc[start..end])
}

#[test]
fn docs_document_every_kind_and_parameter() {
    let doc = std::fs::read_to_string(crate::root().join("docs/language.md")).unwrap();
    for kind in KINDS {
        let text = documentation_of(&doc, kind.name)
            .unwrap_or_else(|| panic!("docs/language.md does not document `{}`", kind.name));
        for p in kind.params.iter().filter(|p| p.povray.is_none()) {
            assert!(
                text.contains(&format!("`{}`", p.name)),
                "docs/language.md's `{}` lacks its parameter `{}`",
                kind.name,
                p.name
            );
        }
    }
}

#[test]
fn an_unknown_kind_is_answered_from_the_table() {
    let check = |text: &str| {
        let mut files = ptsc::source::MemoryFiles::new();
        files.insert("/memory/scene.pts", text);
        let options = ptsc::compile::Options {
            files: &files,
            lower: false,
            ..Default::default()
        };
        let path = std::path::Path::new("/memory/scene.pts");
        let compiled = ptsc::compile::compile_file(path, options).unwrap();
        (compiled.diagnostics.items.iter())
            .map(|d| (d.message.clone(), d.help.clone().unwrap_or_default()))
            .collect::<Vec<_>>()
    };
    let d = check("shpere { center <0, 1, 0> radius 1 }\n");
    assert!(
        d.iter()
            .any(|(m, h)| m == "unknown statement `shpere`" && h == "did you mean `sphere`?"),
        "{d:?}"
    );
    let d = check("spot_lihgt { position <0, 5, 0> look_at <0, 0, 0> intensity rgb 10 }\n");
    assert!(
        d.iter().any(|(_, h)| h == "did you mean `spot_light`?"),
        "{d:?}"
    );
    let d = check("light_source { <0, 5, 0> color rgb 1 }\n");
    assert!(
        d.iter()
            .any(|(m, h)| m.contains("POV-Ray's `light_source") && h.contains("point_light")),
        "{d:?}"
    );
    // A kind's name is a name elsewhere: it is not reserved.
    let d = check("let sphere = 0.5;\nsphere { center <0, 1, 0> radius sphere }\n");
    assert!(d.iter().all(|(m, _)| !m.contains("reserved")), "{d:?}");
}

/// Every pair of parameters the table says do one job two ways
/// (`ParamSpec::excludes`, which completion reads to leave one out) is
/// refused together by the checker: in its own block, and for a
/// material's pairs in at least one `type`.
#[test]
fn every_pair_the_table_excludes_is_a_conflict_the_checker_reports() {
    use ptsc::check::schema::{ParamSpec, MATERIAL, MATERIAL_TYPES};
    let conflicts = |text: &str| {
        let c = ptsc::check::check_str(std::path::Path::new("pair.pts"), text);
        (c.diagnostics.items.iter()).any(|d| d.code == ptsc::diag::codes::CONFLICTING_PARAMS)
    };
    let both =
        |a: &ParamSpec, b: &ParamSpec| format!("{} {} {} {}", a.name, a.example, b.name, b.example);
    let find =
        |rows: &[&'static ParamSpec], name: &str| *rows.iter().find(|r| r.name == name).unwrap();
    let mut pairs = 0;
    for kind in KINDS {
        let rows: Vec<&ParamSpec> = kind.schemas().into_iter().flatten().collect();
        for a in &rows {
            for other in a.excludes {
                let text = format!("{} {{ {} }}\n", kind.name, both(a, find(&rows, other)));
                assert!(conflicts(&text), "{text}");
                pairs += 1;
            }
        }
    }
    let rows: Vec<&ParamSpec> = MATERIAL.iter().collect();
    for a in &rows {
        for other in a.excludes {
            let b = find(&rows, other);
            let refused = (MATERIAL_TYPES.iter())
                .any(|t| conflicts(&format!("material m {{ type {t} {} }}\n", both(a, b))));
            assert!(refused, "{} and {other} in no material type", a.name);
            pairs += 1;
        }
    }
    assert!(pairs >= 10, "{pairs}");
}
