//! What the readers of both formats produce: the nodes, elements and physical names of a `.msh`
//! file as written (Gmsh tags, not yet indices), and the names Gmsh gives its element types.

use crate::error::MeshProblem;

/// The largest number of nodes or elements read: 2²⁴ (about 16.8 million), far above what a
/// plane body of this crate solves, far below what exhausts memory.
pub const MAX_COUNT: u64 = 1 << 24;

/// The longest file read (bytes): 1 GiB.
pub const MAX_FILE_BYTES: u64 = 1 << 30;

/// A problem with where it is (`element 3 (surface 1)`, `node 4`, `byte 120`).
pub type Located = (String, MeshProblem);

/// A node: its tag and coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RawNode {
    pub tag: u64,
    pub xyz: [f64; 3],
}

/// An element: its tag, Gmsh type code, entity (dimension, tag), physical tags and node tags.
#[derive(Debug, Clone, PartialEq)]
pub struct RawElement {
    pub tag: u64,
    pub code: u32,
    pub entity: (i32, i32),
    pub physical: Vec<i32>,
    pub nodes: Vec<u64>,
}

/// A file as read.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RawMesh {
    pub nodes: Vec<RawNode>,
    pub elements: Vec<RawElement>,
    /// (dimension, physical tag, name) from `$PhysicalNames`.
    pub physical_names: Vec<(i32, i32, String)>,
}

/// Gmsh's type code of a 2-node line, a 3-node triangle and a 1-node point.
pub const LINE: u32 = 1;
pub const TRIANGLE: u32 = 2;
pub const POINT: u32 = 15;

/// Gmsh's name of element type `code` (the names of the Gmsh reference manual, "MSH file
/// format"), or `element type {code}` for a code it does not list.
pub fn element_name(code: u32) -> String {
    let name = match code {
        1 => "2-node line",
        2 => "3-node triangle",
        3 => "4-node quadrangle",
        4 => "4-node tetrahedron",
        5 => "8-node hexahedron",
        6 => "6-node prism",
        7 => "5-node pyramid",
        8 => "3-node second order line",
        9 => "6-node second order triangle",
        10 => "9-node second order quadrangle",
        11 => "10-node second order tetrahedron",
        12 => "27-node second order hexahedron",
        13 => "18-node second order prism",
        14 => "14-node second order pyramid",
        15 => "1-node point",
        16 => "8-node second order quadrangle",
        17 => "20-node second order hexahedron",
        18 => "15-node second order prism",
        19 => "13-node second order pyramid",
        20 => "9-node third order incomplete triangle",
        21 => "10-node third order triangle",
        22 => "12-node fourth order incomplete triangle",
        23 => "15-node fourth order triangle",
        24 => "15-node fifth order incomplete triangle",
        25 => "21-node fifth order complete triangle",
        26 => "4-node third order edge",
        27 => "5-node fourth order edge",
        28 => "6-node fifth order edge",
        29 => "20-node third order tetrahedron",
        30 => "35-node fourth order tetrahedron",
        31 => "56-node fifth order tetrahedron",
        92 => "64-node third order hexahedron",
        93 => "125-node fourth order hexahedron",
        _ => return format!("element type {code}"),
    };
    name.to_string()
}

/// The number of nodes of element type `code`, for the types this crate reads or names in its
/// errors (the others are rejected before their nodes are read).
pub fn node_count(code: u32) -> Option<usize> {
    Some(match code {
        1 => 2,
        2 => 3,
        3 => 4,
        4 => 4,
        5 => 8,
        6 => 6,
        7 => 5,
        8 => 3,
        9 => 6,
        10 => 9,
        11 => 10,
        12 => 27,
        13 => 18,
        14 => 14,
        15 => 1,
        16 => 8,
        17 => 20,
        18 => 15,
        19 => 13,
        20 => 9,
        21 => 10,
        22 => 12,
        23 => 15,
        24 => 15,
        25 => 21,
        26 => 4,
        27 => 5,
        28 => 6,
        29 => 20,
        30 => 35,
        31 => 56,
        92 => 64,
        93 => 125,
        _ => return None,
    })
}

/// The `$PhysicalNames` section of `text` (ASCII in every format: `n`, then `dim tag "name"` per
/// line), or none when the file has no such section.
pub fn physical_names(text: &[u8]) -> Result<Vec<(i32, i32, String)>, Located> {
    let Some(start) = section_start(text, b"$PhysicalNames") else {
        return Ok(Vec::new());
    };
    let body = &text[start + b"$PhysicalNames".len()..];
    let end = find(body, b"$EndPhysicalNames").ok_or_else(|| {
        syntax(
            start,
            "$PhysicalNames without $EndPhysicalNames".to_string(),
        )
    })?;
    let section = std::str::from_utf8(&body[..end])
        .map_err(|_| syntax(start, "$PhysicalNames is not UTF-8 text".to_string()))?;
    let mut lines = section.lines().map(str::trim).filter(|l| !l.is_empty());
    let count: u64 = lines
        .next()
        .and_then(|l| l.parse().ok())
        .ok_or_else(|| syntax(start, "$PhysicalNames: expected the number of names".into()))?;
    let mut names = Vec::new();
    for line in lines {
        let (head, rest) = line.split_once('"').ok_or_else(|| {
            syntax(
                start,
                format!("$PhysicalNames: expected `dim tag \"name\"`, found `{line}`"),
            )
        })?;
        let name = rest.strip_suffix('"').ok_or_else(|| {
            syntax(
                start,
                format!("$PhysicalNames: unterminated name in `{line}`"),
            )
        })?;
        let mut it = head.split_whitespace().map(str::parse::<i32>);
        match (it.next(), it.next(), it.next()) {
            (Some(Ok(dim)), Some(Ok(tag)), None) => names.push((dim, tag, name.to_string())),
            _ => {
                return Err(syntax(
                    start,
                    format!("$PhysicalNames: expected `dim tag \"name\"`, found `{line}`"),
                ))
            }
        }
    }
    if names.len() as u64 != count {
        return Err(syntax(
            start,
            format!(
                "$PhysicalNames announces {count} names and lists {}",
                names.len()
            ),
        ));
    }
    Ok(names)
}

/// The position of the top-level section `name` (e.g. `$Nodes`): the sections are walked from
/// the start of the file, each skipped to its `$End…` line, so that text inside another section
/// (a `$Nodes` quoted in `$Comments`, bytes of binary data) is never taken for a header.
pub fn section_start(bytes: &[u8], name: &[u8]) -> Option<usize> {
    let mut at = 0;
    while at < bytes.len() {
        let line_end = bytes[at..]
            .iter()
            .position(|&b| b == b'\n')
            .map_or(bytes.len(), |n| at + n);
        let line = bytes[at..line_end].trim_ascii();
        if line.first() == Some(&b'$') {
            if line == name {
                return Some(at + bytes[at..].iter().position(|&b| b == b'$').unwrap_or(0));
            }
            let mut end = b"\n$End".to_vec();
            end.extend_from_slice(&line[1..]);
            let body = &bytes[line_end.min(bytes.len())..];
            let close = find(body, &end)?;
            at = line_end + close + end.len();
        } else {
            at = line_end + 1;
        }
    }
    None
}

/// The first position of `needle` in `hay`.
pub fn find(hay: &[u8], needle: &[u8]) -> Option<usize> {
    hay.windows(needle.len()).position(|w| w == needle)
}

/// A syntax error at byte `offset`.
pub fn syntax(offset: usize, message: String) -> Located {
    (format!("byte {offset}"), MeshProblem::Syntax(message))
}
