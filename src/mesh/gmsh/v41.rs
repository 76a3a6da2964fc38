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

use super::raw::{
    physical_names, section_start, syntax, Located, RawElement, RawMesh, RawNode, MAX_COUNT,
};
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
        // mshio keeps a block's tags only when they are sparse and then in a map, so a
        // duplicated or out-of-order tag would vanish; the tags are read from the file instead.
        let tags = node_tags(bytes, binary)?;
        let coordinates = section.node_blocks.iter().flat_map(|b| b.nodes.iter());
        let count = section
            .node_blocks
            .iter()
            .map(|b| b.nodes.len())
            .sum::<usize>();
        if count != tags.len() {
            return Err(syntax(
                section_start(bytes, b"$Nodes").unwrap_or(0),
                format!("$Nodes: {} node tags for {count} coordinates", tags.len()),
            ));
        }
        for (n, tag) in coordinates.zip(tags) {
            nodes.push(RawNode {
                tag,
                xyz: [n.x, n.y, n.z],
            });
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

/// The node tags of `$Nodes` in file order (format 4.1: per entity block `dim tag parametric n`,
/// then the n tags, then the n coordinate records of 3 + parametric·dim values), read after
/// [`check_counts`] has bounded the counts.
fn node_tags(bytes: &[u8], binary: Option<bool>) -> Result<Vec<u64>, Located> {
    let at = section_start(bytes, b"$Nodes").unwrap_or(0);
    let mut rest = &bytes[at + b"$Nodes".len()..];
    rest = rest.strip_prefix(b"\r").unwrap_or(rest);
    rest = rest.strip_prefix(b"\n").unwrap_or(rest);
    let bad = |what: &str| syntax(at, format!("$Nodes: {what}"));
    let mut reader = Reader { rest, binary };
    let blocks = reader.size().ok_or_else(|| bad("truncated header"))?;
    let count = reader.size().ok_or_else(|| bad("truncated header"))?;
    reader.size();
    reader.size();
    let mut tags = Vec::with_capacity(count.min(MAX_COUNT) as usize);
    for _ in 0..blocks {
        let (dim, _, parametric) = (reader.int(), reader.int(), reader.int());
        let (Some(dim), Some(parametric), Some(n)) = (dim, parametric, reader.size()) else {
            return Err(bad("truncated entity block"));
        };
        if n > count.saturating_sub(tags.len() as u64) {
            return Err(bad(
                "entity blocks hold more nodes than the header announces",
            ));
        }
        for _ in 0..n {
            tags.push(reader.size().ok_or_else(|| bad("truncated node tags"))?);
        }
        let values = 3 + if parametric != 0 {
            dim.max(0) as u64
        } else {
            0
        };
        for _ in 0..n * values {
            reader.real().ok_or_else(|| bad("truncated coordinates"))?;
        }
    }
    Ok(tags)
}

/// Sequential reading of ASCII words or binary values.
struct Reader<'a> {
    rest: &'a [u8],
    binary: Option<bool>,
}

impl Reader<'_> {
    fn word(&mut self) -> Option<&str> {
        let start = self.rest.iter().position(|b| !b.is_ascii_whitespace())?;
        let len = self.rest[start..]
            .iter()
            .position(|b| b.is_ascii_whitespace())
            .unwrap_or(self.rest.len() - start);
        let word = std::str::from_utf8(&self.rest[start..start + len]).ok();
        self.rest = &self.rest[start + len..];
        word
    }

    fn bytes<const N: usize>(&mut self) -> Option<[u8; N]> {
        let (head, tail) = self.rest.split_first_chunk::<N>()?;
        self.rest = tail;
        Some(*head)
    }

    fn size(&mut self) -> Option<u64> {
        match self.binary {
            Some(true) => self.bytes::<8>().map(u64::from_le_bytes),
            Some(false) => self.bytes::<8>().map(u64::from_be_bytes),
            None => self.word()?.parse().ok(),
        }
    }

    fn int(&mut self) -> Option<i32> {
        match self.binary {
            Some(true) => self.bytes::<4>().map(i32::from_le_bytes),
            Some(false) => self.bytes::<4>().map(i32::from_be_bytes),
            None => self.word()?.parse().ok(),
        }
    }

    fn real(&mut self) -> Option<f64> {
        match self.binary {
            Some(_) => self.bytes::<8>().map(|_| 0.0),
            None => self.word()?.parse().ok(),
        }
    }
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
    let Some(at) = section_start(bytes, name.as_bytes()) else {
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
