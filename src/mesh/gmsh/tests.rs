//! The Gmsh reader: the three formats of one unit-square mesh read into the same mesh and groups
//! (catches a mis-ordered node or element map of one reader); each check triggers on a small
//! crafted 2.2 file with a message naming the element or node; a corrupted file (truncated, bytes
//! flipped) gives an error and never a panic.

use proptest::prelude::*;

use super::*;
use crate::error::MeshProblem;

const ASCII_41: &[u8] = include_bytes!("../../../examples/meshes/unit_square_8.msh");
const BINARY_41: &[u8] = include_bytes!("../../../examples/meshes/unit_square_8_binary.msh");
const ASCII_22: &[u8] = include_bytes!("../../../examples/meshes/unit_square_8_v22.msh");

fn parse(bytes: &[u8]) -> Result<GmshMesh, MeshFileError> {
    GmshMesh::parse(bytes, "test.msh", Placement::default())
}

#[test]
fn three_formats_read_into_the_same_mesh_and_groups() {
    let a = parse(ASCII_41).unwrap();
    assert_eq!(a.mesh.nodes().len(), 81);
    assert_eq!(a.mesh.triangles().len(), 128);
    assert_eq!(a.mesh.boundary().len(), 32);
    assert_eq!(
        a.boundary_groups.keys().collect::<Vec<_>>(),
        ["bottom", "left", "right", "top"]
    );
    assert_eq!(a.regions["body"].len(), 128);
    let total: f64 = (0..128).map(|t| a.mesh.area(t)).sum();
    assert!((total - 1.0).abs() < 1e-12);
    // every edge of a side group lies on its side
    for (name, k, value) in [
        ("bottom", 1, 0.0),
        ("right", 0, 1.0),
        ("top", 1, 1.0),
        ("left", 0, 0.0),
    ] {
        assert_eq!(a.boundary_groups[name].len(), 8);
        for &e in &a.boundary_groups[name] {
            for v in a.mesh.boundary()[e].nodes {
                assert!((a.mesh.nodes()[v][k] - value).abs() < 1e-11, "{name}");
            }
        }
    }
    // The same topology and groups; coordinates to the 16 significant digits of the ASCII files
    // (the binary file holds the exact doubles).
    for other in [parse(BINARY_41).unwrap(), parse(ASCII_22).unwrap()] {
        assert!(other.mesh.triangles() == a.mesh.triangles());
        assert!(other.mesh.boundary() == a.mesh.boundary());
        assert!(other.boundary_groups == a.boundary_groups && other.regions == a.regions);
        assert!(other.node_tags == a.node_tags && other.triangle_tags == a.triangle_tags);
        for (p, q) in other.mesh.nodes().iter().zip(a.mesh.nodes()) {
            assert!((p[0] - q[0]).abs() <= 1e-15 && (p[1] - q[1]).abs() <= 1e-15);
        }
    }
}

#[test]
fn placement_scales_and_shifts() {
    let p = Placement {
        scale: 2.0,
        offset: [1.0, -1.0],
    };
    let m = GmshMesh::parse(ASCII_41, "x", p).unwrap();
    let a = parse(ASCII_41).unwrap();
    for (q, r) in m.mesh.nodes().iter().zip(a.mesh.nodes()) {
        assert_eq!(*q, [2.0 * r[0] + 1.0, 2.0 * r[1] - 1.0]);
    }
}

/// A 2.2 file of the given node and element lines, with names "base" (dim 1, tag 1), "body"
/// (dim 2, tag 2).
fn file22(nodes: &[&str], elements: &[&str]) -> Vec<u8> {
    format!(
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n1 1 \"base\"\n2 2 \"body\"\n\
         $EndPhysicalNames\n$Nodes\n{}\n{}\n$EndNodes\n$Elements\n{}\n{}\n$EndElements\n",
        nodes.len(),
        nodes.join("\n"),
        elements.len(),
        elements.join("\n")
    )
    .into_bytes()
}

const SQUARE: [&str; 4] = ["1 0 0 0", "2 1 0 0", "3 1 1 0", "4 0 1 0"];

fn err(nodes: &[&str], elements: &[&str]) -> MeshFileError {
    parse(&file22(nodes, elements)).unwrap_err()
}

#[test]
fn clockwise_triangles_are_reoriented_and_groups_named() {
    let m = parse(&file22(
        &SQUARE,
        &[
            "1 2 2 2 1 1 3 2",
            "2 2 2 2 1 1 4 3",
            "3 1 2 1 5 1 2",
            "4 15 2 9 9 1",
        ],
    ))
    .unwrap();
    assert!((0..2).all(|t| m.mesh.area(t) > 0.0));
    assert_eq!(m.boundary_groups["base"].len(), 1);
    assert_eq!(m.regions["body"], vec![0, 1]);
    let e = m.boundary_group("dirichlet[0].group", "lid").unwrap_err();
    assert!(e.to_string().contains("\"base\""), "{e}");
}

#[test]
fn each_check_names_the_element_or_node() {
    type Expected = fn(&MeshProblem) -> bool;
    let cases: Vec<(MeshFileError, &str, Expected)> = vec![
        (
            err(&SQUARE, &["1 9 2 2 1 1 2 3 4 5 6", "2 2 2 2 1 1 3 4"]),
            "element 1 (surface 1)",
            |p| matches!(p, MeshProblem::UnsupportedElement { code: 9, name } if name == "6-node second order triangle"),
        ),
        (
            err(
                &["1 0 0 0", "2 1 0 0", "3 1 1 0", "4 2 0 0"],
                &["1 2 2 2 1 1 2 3", "7 2 2 2 1 1 2 4"],
            ),
            "element 7 (surface 1)",
            |p| matches!(p, MeshProblem::DegenerateTriangle { .. }),
        ),
        (
            err(
                &["1 0 0 0", "2 1 0 0", "3 1 1 0", "4 0 1 0", "5 1 1 0"],
                &["1 2 2 2 1 1 2 3", "2 2 2 2 1 1 5 4"],
            ),
            "node 5",
            |p| {
                matches!(
                    p,
                    MeshProblem::DuplicateNode {
                        node: 5,
                        other: 3,
                        ..
                    }
                )
            },
        ),
        (
            err(
                &["1 0 0 0", "2 1 0 0", "3 1 1 0", "4 0 1 0", "6 5 5 0"],
                &["1 2 2 2 1 1 2 3", "2 2 2 2 1 1 3 4"],
            ),
            "node 6",
            |p| matches!(p, MeshProblem::UnusedNodes { count: 1, first } if first == &[6]),
        ),
        (
            err(
                &SQUARE,
                &["1 2 2 2 1 1 2 3", "2 2 2 2 1 1 3 4", "3 1 2 1 5 1 3"],
            ),
            "element 3 (curve 5)",
            |p| matches!(p, MeshProblem::NotOnBoundary { group, nodes: [1, 3] } if group == "base"),
        ),
        (
            err(
                &["1 0 0 0", "2 1 0 0", "3 1 1 0", "4 0 1 0", "5 2 0 0"],
                &["1 2 2 2 1 1 2 3", "2 2 2 2 1 1 3 4", "3 2 2 2 1 1 5 3"],
            ),
            "element 3 (surface 1)",
            |p| matches!(p, MeshProblem::NonManifoldEdge { triangles: 3, .. }),
        ),
        (
            // two triangles touching at node 3 only
            err(
                &["1 0 0 0", "2 1 0 0", "3 1 1 0", "4 2 1 0", "5 2 2 0"],
                &["1 2 2 2 1 1 2 3", "2 2 2 2 1 3 4 5"],
            ),
            "node 3",
            |p| matches!(p, MeshProblem::NonManifoldNode { edges: 4 }),
        ),
        (
            err(&["1 0 0 0", "2 1 0 0", "3 1 1 0.5"], &["1 2 2 2 1 1 2 3"]),
            "node 3",
            |p| matches!(p, MeshProblem::NotPlanar { .. }),
        ),
        (
            err(&SQUARE, &["1 2 2 2 1 1 2 8"]),
            "element 1 (surface 1)",
            |p| matches!(p, MeshProblem::UnknownNode(8)),
        ),
    ];
    for (e, location, problem) in cases {
        assert_eq!(e.file, "test.msh");
        assert_eq!(e.location, location, "{e}");
        assert!(problem(&e.problem), "{e}");
        assert!(e.to_string().starts_with("mesh file test.msh: "), "{e}");
    }
}

#[test]
fn unsupported_versions_and_huge_counts_are_errors() {
    let text = String::from_utf8(ASCII_22.to_vec()).unwrap();
    let e = parse(text.replace("2.2 0 8", "3.0 0 8").as_bytes()).unwrap_err();
    assert!(
        matches!(e.problem, MeshProblem::UnsupportedFormat(_)),
        "{e}"
    );
    let e = parse(text.replace("$Nodes\n81", "$Nodes\n99999999999").as_bytes()).unwrap_err();
    assert!(matches!(e.problem, MeshProblem::TooLarge { .. }), "{e}");
    let text = String::from_utf8(ASCII_41.to_vec()).unwrap();
    let e = parse(text.replace("9 81 1 81", "9 4000000 1 4000000").as_bytes()).unwrap_err();
    assert!(matches!(e.problem, MeshProblem::TooLarge { .. }), "{e}");
    let e = parse(text.replace("9 81 1 81", "9 0 1 81").as_bytes()).unwrap_err();
    assert!(matches!(e.problem, MeshProblem::Syntax(_)), "{e}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// A truncated file, or one with a few bytes replaced, is read without a panic: it gives an
    /// error, or (a flipped digit in a coordinate) a valid mesh.
    #[test]
    fn corrupted_files_give_errors_not_panics(
        which in 0usize..3,
        cut in 0.0f64..1.0,
        flips in prop::collection::vec((0.0f64..1.0, any::<u8>()), 0..4),
    ) {
        let source = [ASCII_41, BINARY_41, ASCII_22][which];
        let mut bytes = source.to_vec();
        for (at, b) in flips {
            let i = ((at * bytes.len() as f64) as usize).min(bytes.len() - 1);
            bytes[i] = b;
        }
        if cut < 0.5 {
            bytes.truncate((cut * 2.0 * bytes.len() as f64) as usize);
            prop_assert!(parse(&bytes).is_err());
        } else {
            let _ = parse(&bytes);
        }
    }
}

#[test]
fn a_duplicated_dense_node_tag_is_refused() {
    // tags 1, 2, 2, 4, … : still dense (max − min + 1 = count), so mshio drops them; ours read them
    let text = String::from_utf8(ASCII_41.to_vec()).unwrap();
    let doubled = text.replacen("0 3 0 1\n3\n", "0 3 0 1\n2\n", 1);
    assert_ne!(doubled, text);
    let e = parse(doubled.as_bytes()).unwrap_err();
    assert!(e.to_string().contains("defined twice"), "{e}");
}

#[test]
fn a_nodes_header_quoted_in_comments_is_not_read() {
    let text = String::from_utf8(ASCII_41.to_vec()).unwrap();
    let decoy = text.replacen(
        "$EndMeshFormat\n",
        "$EndMeshFormat\n$Comments\n$Nodes\n1 0 1 1\n$EndComments\n",
        1,
    );
    assert_ne!(decoy, text);
    let m = parse(decoy.as_bytes()).unwrap();
    assert_eq!(m.mesh.nodes().len(), 81);
    assert_eq!(
        raw::section_start(decoy.as_bytes(), b"$Nodes"),
        decoy.find("$Nodes\n9 81")
    );
}
