//! A mesh's `materials { "Name" material … }`: the file's materials it
//! replaces by name, each material resolved as an object's is (by name,
//! perhaps declared further on, or written inline). Whether the file has
//! such a material is known once it is read: lowering says.

use super::*;
use crate::syntax::ast::Block;

/// The replacements of a block, and those whose material is named before
/// its declaration (the index of the replacement, the name).
pub(super) type Swaps = (Vec<MaterialSwap>, Vec<(usize, Ident)>);

impl Checker<'_> {
    /// The replacements of the `materials` entry of `block` (`None`: it
    /// has none); `own` is where the block's own material is written,
    /// which replaces all the file's materials (a warning then).
    pub(super) fn swaps(&mut self, block: &Block, own: Option<Span>) -> Option<Swaps> {
        let (word, written) = block.entries.iter().find_map(|e| match e {
            Entry::Materials { word, swaps, .. } => Some((word, swaps)),
            _ => None,
        })?;
        if let Some(own) = own {
            self.diags.push(
                Diagnostic::warning(
                    codes::NO_EFFECT,
                    "`materials` has no effect beside the mesh's `material`",
                    word.span,
                )
                .with_label("the file's materials are all replaced")
                .with_secondary(own, "by this material")
                .with_help("remove the `material` to keep the file's other materials"),
            );
        }
        let mut out = Vec::with_capacity(written.len());
        let mut pending = Vec::new();
        let mut seen: HashMap<&str, Span> = HashMap::new();
        for swap in written {
            // Resolved first: an unknown material is reported even in a
            // pair that repeats a name (every mistake at once).
            let material = self.object_material(&[(&swap.material, swap.span)], swap.span)?;
            if let Some(first) = seen.get(swap.name.as_str()) {
                self.diags.push(
                    Diagnostic::error(
                        codes::DUPLICATE_PARAM,
                        format!("the material `{}` is replaced twice", swap.name),
                        swap.name_span,
                    )
                    .with_label("replaced again here")
                    .with_secondary(*first, "first replaced here")
                    .with_help("keep one of them"),
                );
                continue;
            }
            seen.insert(&swap.name, swap.name_span);
            if let (true, MaterialRef::Named(name)) = (material == PENDING_MATERIAL, &swap.material)
            {
                pending.push((out.len(), name.clone()));
            }
            out.push(MaterialSwap {
                name: swap.name.clone(),
                span: swap.name_span,
                material,
            });
        }
        Some((out, pending))
    }
}

/// Gives the `k`th replaced material of the mesh `object` the scene's
/// material `index` (named before its declaration).
pub(super) fn set(object: &mut Object, k: usize, index: usize) {
    if let Shape::Mesh { swaps, .. } = &mut object.shape {
        if let Some(swap) = swaps.get_mut(k) {
            swap.material = index;
        }
    }
}
