//! A glTF file's node hierarchy checked as a whole, before any walk of it:
//! glTF 2.0 (§3.5.3) asks that nodes form disjoint strict trees, "no node
//! may be a direct descendant of more than one node". A cycle (A holds B,
//! B holds A) that no scene reaches would otherwise leave a file whose
//! default scene places nothing, and a walk from the scene would only say
//! a node was reached twice; a second parent would place one node under
//! each, which is not what the file means. Both are refused here, naming
//! the nodes, as the Khronos validator does.

use super::mesh_data::FileNode;

/// The most nodes a message lists on a cycle.
const SHOWN: usize = 8;

/// Whether `nodes` form disjoint trees; the error names the nodes of the
/// first cycle, or a node with two parents.
pub(super) fn hierarchy(nodes: &[FileNode]) -> Result<(), String> {
    let named = |k: usize| match nodes.get(k) {
        // An unnamed node's name is `#k` (`gltf::node_name`).
        Some(n) if n.name == format!("#{k}") => format!("nodes[{k}]"),
        Some(n) => format!("`{}` (nodes[{k}])", n.name),
        None => format!("nodes[{k}]"),
    };
    let mut parent: Vec<Option<usize>> = vec![None; nodes.len()];
    for (p, node) in nodes.iter().enumerate() {
        for &c in &node.children {
            let Some(slot) = parent.get_mut(c as usize) else {
                return Err(format!("{} has child {c}, past the nodes", named(p)));
            };
            match *slot {
                // A child listed twice by the same parent is the same edge.
                Some(q) if q == p => {}
                Some(q) => {
                    return Err(format!(
                        "{} is a child of both {} and {}: a glTF node has one parent at most (a mesh placed twice needs a node under each parent)",
                        named(c as usize),
                        named(q),
                        named(p)
                    ))
                }
                None => *slot = Some(p),
            }
        }
    }
    // With one parent each, a cycle is a walk up the parents that comes
    // back; each node is walked from once (`state`: 0 new, 1 on the walk
    // from the current start, 2 done), so the check is linear.
    let mut state = vec![0u8; nodes.len()];
    for start in 0..nodes.len() {
        let mut k = start;
        while state[k] == 0 {
            state[k] = 1;
            match parent[k] {
                Some(p) => k = p,
                None => break,
            }
        }
        if state[k] == 1 && parent[k].is_some() {
            return Err(cycle(k, &parent, named));
        }
        let mut k = start;
        while state[k] == 1 {
            state[k] = 2;
            match parent[k] {
                Some(p) => k = p,
                None => break,
            }
        }
    }
    Ok(())
}

/// The message for the cycle through node `on`, written parent first:
/// `A` holds `B`, which holds `A`.
fn cycle(on: usize, parent: &[Option<usize>], named: impl Fn(usize) -> String) -> String {
    let mut members = vec![on];
    let mut k = parent[on].unwrap_or(on);
    // Bounded by the node count whatever the table holds.
    while k != on && members.len() <= parent.len() {
        members.push(k);
        k = parent[k].unwrap_or(on);
    }
    members.reverse();
    // Told from its lowest node, whichever node the walk met first.
    let first = (0..members.len()).min_by_key(|&i| members[i]).unwrap_or(0);
    members.rotate_left(first);
    let mut shown: Vec<String> = members.iter().take(SHOWN).map(|&k| named(k)).collect();
    if members.len() > SHOWN {
        shown.push(format!("… ({} nodes)", members.len()));
    }
    shown.push(named(members[0]));
    format!(
        "the node hierarchy has a cycle: {} (each holds the next as a child; glTF nodes form trees)",
        shown.join(" → ")
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DMat4;

    fn node(name: &str, children: &[u32]) -> FileNode {
        FileNode {
            name: name.into(),
            local: DMat4::IDENTITY,
            mesh: None,
            light: None,
            children: children.to_vec(),
        }
    }

    #[test]
    fn trees_pass_and_cycles_are_named() {
        let tree = [node("A", &[1, 2]), node("B", &[]), node("C", &[1])];
        let e = hierarchy(&tree).unwrap_err();
        assert!(
            e.starts_with("`B` (nodes[1]) is a child of both `A` (nodes[0]) and `C` (nodes[2])"),
            "{e}"
        );
        assert!(hierarchy(&[node("A", &[1, 1]), node("B", &[])]).is_ok());
        let e = hierarchy(&[node("A", &[1]), node("B", &[0])]).unwrap_err();
        assert!(
            e.starts_with(
                "the node hierarchy has a cycle: `A` (nodes[0]) → `B` (nodes[1]) → `A` (nodes[0])"
            ),
            "{e}"
        );
        let e = hierarchy(&[node("#0", &[]), node("#1", &[1])]).unwrap_err();
        assert!(e.contains("cycle: nodes[1] → nodes[1] ("), "{e}");
        // A loop of 11 nodes with 10,000 leaves under one of them: shown
        // in part, and found walking each node once.
        let mut nodes: Vec<FileNode> = (0..11).map(|k| node("n", &[(k + 1) % 11])).collect();
        nodes[5].children.extend(11..10_011);
        nodes.extend((11..10_011).map(|_| node("leaf", &[])));
        let e = hierarchy(&nodes).unwrap_err();
        assert!(
            e.contains("`n` (nodes[7]) → … (11 nodes) → `n` (nodes[0])"),
            "{e}"
        );
    }
}
