//! The README's numbers come from the reports: every generated block of README.md equals what
//! `verify readme` renders from the committed `reports/` (regenerate both at the commit that
//! changes a number).

use contactlab_verify::core::report::readme::{fill, render};

#[test]
fn readme_numbers_equal_the_reports() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("the repository")
        .to_path_buf();
    let text = std::fs::read_to_string(root.join("README.md")).expect("README.md");
    let blocks = render(&root.join("reports")).expect("the reports render");
    let filled = fill(&text, &blocks).expect("the blocks fill");
    assert!(
        filled == text,
        "README.md's generated blocks differ from reports/: run `cargo run --release --bin verify -- readme`"
    );
    assert!(text.contains("<!-- generated: evidence -->"));
}
