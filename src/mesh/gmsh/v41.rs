//! Format 4.1 (ASCII and binary) through the `mshio` crate, after our own checks of what `mshio`
//! trusts: the section headers' counts (at least one node and one element, at most
//! [`MAX_COUNT`], and no more than the bytes left can hold) are read and checked here before
//! `mshio` parses the sections, so a corrupted count can neither underflow its arithmetic nor
//! make it loop over a count the file cannot hold.
//!
//! `mshio` keeps a block's node tags only when the section's tags are sparse
//! (max − min + 1 > count); otherwise the k-th node of the section, in file order, has tag
//! min + k. Gmsh writes dense tags in that order.

use std::collections::HashMap;

use mshio::mshfile::MshFile;

use super::raw::{find, physical_names, syntax, Located, RawElement, RawMesh, RawNode, MAX_COUNT};
use crate::error::MeshProblem;

/// Reads a 4.1 file: ASCII when `binary` is `None`, else binary with `Some(little_endian)` as its
/// header says (its data size checked to be 8 by the caller).
pub fn read(bytes: &[u8], binary: Option<bool>) -> Result<RawMesh, Located> {
    let wide = binary.is_some();
    check_counts(bytes, "$Nodes", binary, if wide { 32 } else { 8 })?;
    check_counts(bytes, "$Elements", binary, if wide { 16 } else { 4 })?;
    let msh: MshFile<u64, i32, f64> = mshio::parse_msh_bytes(bytes).map_err(|e| {
        let offset = e
            .backtrace
            .first()
            .map_or(0, |(rest, _)| bytes.len().saturating_sub(rest.len()));
        let what: Vec<String> = e
            .backtrace
            .iter()
            .rev()
            .filter(|(_, k)| !k.is_nom_error())
            .map(|(_, k)| k.to_string())
            .collect();
        syntax(offset, what.join(": "))
    })?;
    let physical_names = physical_names(bytes)?;
    let mut physical_of: HashMap<(i32, i32), Vec<i32>> = HashMap::new();
    if let Some(entities) = &msh.data.entities {
        for c in &entities.curves {
            physical_of.insert((1, c.tag), c.physical_tags.clone());
        }
        for s in &entities.surfaces {
            physical_of.insert((2, s.tag), s.physical_tags.clone());
        }
    }
    let mut nodes = Vec::new();
    if let Some(section) = &msh.data.nodes {
        let mut k = 0u64;
        for block in &section.node_blocks {
            let mut tags = vec![0u64; block.nodes.len()];
            match &block.node_tags {
                Some(map) => {
                    for (&tag, &i) in map {
                        if let Some(t) = tags.get_mut(i) {
                            *t = tag;
                        }
                    }
                }
                None => {
                    for t in tags.iter_mut() {
                        *t = section.min_node_tag.saturating_add(k);
                        k += 1;
                    }
                }
            }
            for (n, tag) in block.nodes.iter().zip(tags) {
                nodes.push(RawNode {
                    tag,
                    xyz: [n.x, n.y, n.z],
                });
            }
        }
    }
    let mut elements = Vec::new();
    if let Some(section) = &msh.data.elements {
        for block in &section.element_blocks {
            let entity = (block.entity_dim, block.entity_tag);
            let physical = physical_of.get(&entity).cloned().unwrap_or_default();
            for e in &block.elements {
                elements.push(RawElement {
                    tag: e.element_tag,
                    code: block.element_type as u32,
                    entity,
                    physical: physical.clone(),
                    nodes: e.nodes.clone(),
                });
            }
        }
    }
    Ok(RawMesh {
        nodes,
        elements,
        physical_names,
    })
}

/// Checks the header of section `name` (`numEntityBlocks numItems minTag maxTag`): 1 ≤ numItems
/// ≤ [`MAX_COUNT`], numEntityBlocks ≤ numItems, minTag ≥ 1, and numItems × `min_bytes` (the
/// fewest bytes one item takes) no more than the bytes after the header.
fn check_counts(
    bytes: &[u8],
    name: &str,
    binary: Option<bool>,
    min_bytes: u64,
) -> Result<(), Located> {
    let Some(at) = find(bytes, name.as_bytes()) else {
        return Ok(());
    };
    let mut rest = &bytes[at + name.len()..];
    // The end of the section's name line: binary data may start with a byte that looks blank.
    rest = rest.strip_prefix(b"\r").unwrap_or(rest);
    rest = rest.strip_prefix(b"\n").unwrap_or(rest);
    let mut values = [0u64; 4];
    if let Some(little) = binary {
        for v in values.iter_mut() {
            let Some((head, tail)) = rest.split_first_chunk::<8>() else {
                return Err(syntax(at, format!("{name}: truncated section header")));
            };
            *v = if little {
                u64::from_le_bytes(*head)
            } else {
                u64::from_be_bytes(*head)
            };
            rest = tail;
        }
    } else {
        let text = std::str::from_utf8(&rest[..rest.len().min(200)]).unwrap_or("");
        let mut words = text.split_ascii_whitespace();
        for v in values.iter_mut() {
            *v = words.next().and_then(|w| w.parse().ok()).ok_or_else(|| {
                syntax(
                    at,
                    format!("{name}: expected four counts after the section name"),
                )
            })?;
        }
    }
    let [blocks, count, min_tag, _] = values;
    let what = format!("{name} count");
    if count == 0 {
        return Err(("file".into(), MeshProblem::Syntax(format!("{what} is 0"))));
    }
    if count > MAX_COUNT {
        return Err((
            "file".into(),
            MeshProblem::TooLarge {
                what,
                count,
                limit: format!("the hard maximum {MAX_COUNT}"),
            },
        ));
    }
    let left = rest.len() as u64;
    if count.saturating_mul(min_bytes) > left || blocks > count || min_tag == 0 {
        return Err((
            "file".into(),
            MeshProblem::TooLarge {
                what: format!("{what} (with {blocks} blocks, first tag {min_tag})"),
                count,
                limit: format!("what the {left} bytes left can hold ({min_bytes} bytes each)"),
            },
        ));
    }
    Ok(())
}
