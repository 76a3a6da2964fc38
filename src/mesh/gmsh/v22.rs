//! Format 2.2 ASCII, read here: `mshio` reads format 4.1 only (its header parser rejects any other
//! version), and 2.2 is still what many tools write (`gmsh -format msh22`, meshio, older
//! scripts). The format (Gmsh reference manual, "MSH file format version 2"):
//!
//! ```text
//! $Nodes            n, then n lines `tag x y z`
//! $Elements         n, then n lines `tag type ntags tag_1 … tag_ntags node_1 … node_k`
//! ```
//!
//! with tag_1 the physical group and tag_2 the elementary entity. Every count is checked against
//! [`MAX_COUNT`] and the bytes left in the section before anything is allocated for it.

use super::raw::{
    element_name, node_count, physical_names, syntax, Located, RawElement, RawMesh, RawNode,
    MAX_COUNT,
};
use crate::error::MeshProblem;

/// Reads a 2.2 ASCII file.
pub fn read(bytes: &[u8]) -> Result<RawMesh, Located> {
    let text = std::str::from_utf8(bytes).map_err(|e| {
        syntax(
            e.valid_up_to(),
            "not UTF-8 text (format 2.2 is read in ASCII only)".into(),
        )
    })?;
    let physical_names = physical_names(bytes)?;
    let (nodes_at, nodes_text) = section(text, "$Nodes", "$EndNodes")?;
    let mut lines = Lines::new(nodes_text, nodes_at);
    let n = lines.count("$Nodes", 8)?;
    let mut nodes = Vec::with_capacity(n);
    for _ in 0..n {
        let (at, words) = lines.next_words("a node line `tag x y z`")?;
        let tag = parse_u64(&words, 0, at, "node tag")?;
        let mut xyz = [0.0; 3];
        for (k, x) in xyz.iter_mut().enumerate() {
            *x = words
                .get(1 + k)
                .and_then(|w| w.parse::<f64>().ok())
                .ok_or_else(|| {
                    (
                        format!("node {tag}"),
                        MeshProblem::Syntax("expected three coordinates after the tag".into()),
                    )
                })?;
        }
        nodes.push(RawNode { tag, xyz });
    }
    let (elements_at, elements_text) = section(text, "$Elements", "$EndElements")?;
    let mut lines = Lines::new(elements_text, elements_at);
    let n = lines.count("$Elements", 6)?;
    let mut elements = Vec::with_capacity(n);
    for _ in 0..n {
        let (at, words) = lines.next_words("an element line `tag type ntags tags… nodes…`")?;
        let tag = parse_u64(&words, 0, at, "element tag")?;
        let here = format!("element {tag}");
        let bad = |m: &str| (here.clone(), MeshProblem::Syntax(m.to_string()));
        let code = parse_u64(&words, 1, at, "element type")?;
        let code = u32::try_from(code).map_err(|_| bad("element type out of range"))?;
        let ntags = parse_u64(&words, 2, at, "number of tags")?;
        if ntags > words.len() as u64 {
            return Err(bad(&format!(
                "{ntags} tags on a line of {} words",
                words.len()
            )));
        }
        let ntags = ntags as usize;
        let k = node_count(code).ok_or_else(|| {
            (
                here.clone(),
                MeshProblem::UnsupportedElement {
                    code,
                    name: element_name(code),
                },
            )
        })?;
        if words.len() != 3 + ntags + k {
            return Err(bad(&format!(
                "{} words for a {} with {ntags} tags (expected {})",
                words.len(),
                element_name(code),
                3 + ntags + k
            )));
        }
        let int = |w: &str| {
            w.parse::<i32>()
                .map_err(|_| bad("a tag that is not an integer"))
        };
        let physical = if ntags >= 1 { int(words[3])? } else { 0 };
        let entity = if ntags >= 2 { int(words[4])? } else { 0 };
        let dim = match code {
            15 => 0,
            1 | 8 | 26 | 27 | 28 => 1,
            2..=3 | 9 | 10 | 16 | 20..=25 => 2,
            _ => 3,
        };
        let mut node_tags = Vec::with_capacity(k);
        for i in 0..k {
            node_tags.push(parse_u64(&words, 3 + ntags + i, at, "node tag")?);
        }
        elements.push(RawElement {
            tag,
            code,
            entity: (dim, entity),
            physical: if physical != 0 {
                vec![physical]
            } else {
                Vec::new()
            },
            nodes: node_tags,
        });
    }
    Ok(RawMesh {
        nodes,
        elements,
        physical_names,
    })
}

/// The text between `start` and `end` (and its byte offset in the file).
fn section<'a>(text: &'a str, start: &str, end: &str) -> Result<(usize, &'a str), Located> {
    let Some(a) = super::raw::section_start(text.as_bytes(), start.as_bytes()) else {
        return Err((
            "file".into(),
            MeshProblem::Syntax(format!("no {start} section")),
        ));
    };
    let body = &text[a + start.len()..];
    let Some(b) = body.find(end) else {
        return Err(syntax(a, format!("{start} without {end}")));
    };
    Ok((a + start.len(), &body[..b]))
}

/// The non-empty lines of a section, with their byte offsets.
struct Lines<'a> {
    rest: &'a str,
    offset: usize,
}

impl<'a> Lines<'a> {
    fn new(text: &'a str, offset: usize) -> Self {
        Self { rest: text, offset }
    }

    fn next_words(&mut self, what: &str) -> Result<(usize, Vec<&'a str>), Located> {
        loop {
            if self.rest.is_empty() {
                return Err(syntax(
                    self.offset,
                    format!("section ends where {what} was expected"),
                ));
            }
            let (line, tail) = self.rest.split_once('\n').unwrap_or((self.rest, ""));
            let at = self.offset;
            self.offset += line.len() + 1;
            self.rest = tail;
            let words: Vec<&str> = line.split_ascii_whitespace().collect();
            if !words.is_empty() {
                return Ok((at, words));
            }
        }
    }

    /// The section's count: at most [`MAX_COUNT`], and `min_bytes` per item must fit in the
    /// section's bytes left.
    fn count(&mut self, section: &str, min_bytes: u64) -> Result<usize, Located> {
        let (at, words) = self.next_words("the count")?;
        let n = parse_u64(&words, 0, at, "count")?;
        let left = self.rest.len() as u64;
        if n > MAX_COUNT || n.saturating_mul(min_bytes) > left + 1 {
            return Err((
                format!("byte {at}"),
                MeshProblem::TooLarge {
                    what: format!("{section} count"),
                    count: n,
                    limit: format!(
                        "the hard maximum {MAX_COUNT} and what the section's {left} bytes can hold"
                    ),
                },
            ));
        }
        Ok(n as usize)
    }
}

fn parse_u64(words: &[&str], i: usize, at: usize, what: &str) -> Result<u64, Located> {
    words
        .get(i)
        .and_then(|w| w.parse::<u64>().ok())
        .ok_or_else(|| syntax(at, format!("expected a {what} (a non-negative integer)")))
}
