// Setting: whole figures written to unique files in the system temp folder.
// Goal: pin that the public API writes valid-looking SVG with titles, legends and labels,
// survives hostile data (NaN, ±inf, ≤ 0 on log axes, empty, constant), and is deterministic.
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

use super::*;

/// A unique path in the temp folder for this test process.
fn temp_svg(tag: &str) -> PathBuf {
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    std::env::temp_dir().join(format!(
        "contactlab_plot_{}_{}_{}.svg",
        std::process::id(),
        tag,
        n
    ))
}

/// Writes the figure, reads it back and removes the file.
fn write_and_read(figure: &Figure, tag: &str) -> String {
    let path = temp_svg(tag);
    write_svg(figure, &path).expect("write_svg");
    let svg = std::fs::read_to_string(&path).expect("read back");
    let _ = std::fs::remove_file(&path);
    svg
}

/// The trimmed contents of every `<text>` element.
fn texts(svg: &str) -> Vec<String> {
    svg.split("<text")
        .skip(1)
        .filter_map(|rest| {
            let start = rest.find('>')? + 1;
            let end = rest.find("</text>")?;
            rest.get(start..end).map(|t| t.trim().to_string())
        })
        .collect()
}

fn has_text(svg: &str, text: &str) -> bool {
    texts(svg).iter().any(|t| t == text)
}

fn assert_svg(svg: &str) {
    assert!(
        svg.trim_start().starts_with("<svg"),
        "{}",
        &svg[..svg.len().min(200)]
    );
    assert!(svg.trim_end().ends_with("</svg>"));
    assert!(
        !svg.contains("NaN") && !svg.contains("inf"),
        "non-finite coordinate in SVG"
    );
}

fn convergence_figure() -> Figure {
    let hs = [0.2, 0.1, 0.05, 0.025, 0.0125];
    Figure::new("Convergence in h")
        .x_label("h")
        .y_label("L2 error")
        .log_log()
        .series(Series::line_markers(
            "backward Euler",
            hs.iter().map(|&h| (h, 0.3 * h)),
        ))
        .series(Series::line_markers(
            "Crank–Nicolson",
            hs.iter().map(|&h| (h, 0.5 * h * h)),
        ))
        .reference_slope(1.0, "slope 1")
        .reference_slope(2.0, "slope 2")
}

#[test]
fn log_log_figure_contains_title_legend_names_and_slope_labels() {
    let svg = write_and_read(&convergence_figure(), "loglog");
    assert_svg(&svg);
    for text in [
        "Convergence in h",
        "backward Euler",
        "Crank–Nicolson",
        "slope 1",
        "slope 2",
        "h",
        "L2 error",
    ] {
        assert!(
            has_text(&svg, text),
            "missing {text:?} in {:?}",
            texts(&svg)
        );
    }
    assert!(
        has_text(&svg, "1e-4") || has_text(&svg, "1e-3"),
        "no scientific tick label"
    );
}

#[test]
fn non_finite_and_non_positive_points_on_log_axes_are_skipped() {
    let fig = Figure::new("Hostile data")
        .log_log()
        .series(Series::line_markers(
            "mixed",
            vec![
                (1.0, 1.0),
                (f64::NAN, 2.0),
                (2.0, f64::INFINITY),
                (0.0, 1.0),
                (-1.0, 3.0),
                (3.0, -2.0),
                (4.0, 0.5),
                (f64::NEG_INFINITY, f64::NAN),
            ],
        ))
        .series(Series::markers("all negative", vec![(-1.0, -1.0)]))
        .reference_slope(f64::NAN, "bad slope")
        .vertical_line(-1.0, "invalid bound")
        .x_range(-1.0, 0.0);
    let svg = write_and_read(&fig, "hostile");
    assert_svg(&svg);
    assert!(has_text(&svg, "mixed"));
    assert!(has_text(&svg, "all negative (no data)"));
    assert!(!has_text(&svg, "no data"), "the figure has drawable points");
}

#[test]
fn empty_figure_writes_a_no_data_svg() {
    let fig = Figure::new("Nothing here")
        .x_label("t")
        .y_label("energy")
        .log_log();
    let svg = write_and_read(&fig, "empty");
    assert_svg(&svg);
    assert!(has_text(&svg, "Nothing here"));
    assert!(has_text(&svg, "no data"));

    let only_bad = Figure::new("Only bad").series(Series::line("nan", vec![(f64::NAN, 1.0)]));
    let svg = write_and_read(&only_bad, "only_bad");
    assert_svg(&svg);
    assert!(has_text(&svg, "no data"));
}

#[test]
fn constant_and_single_point_data_are_padded_not_rejected() {
    let fig = Figure::new("Constant")
        .series(Series::line(
            "flat",
            vec![(0.0, 2.0), (1.0, 2.0), (2.0, 2.0)],
        ))
        .series(Series::markers("single", vec![(1.0, 2.0)]))
        .horizontal_line(2.0, "tolerance");
    let svg = write_and_read(&fig, "constant");
    assert_svg(&svg);
    assert!(has_text(&svg, "tolerance"));
    let fig = Figure::new("Single")
        .log_log()
        .series(Series::markers("one", vec![(1e-3, 1e-6)]))
        .reference_slope(2.0, "slope 2");
    assert_svg(&write_and_read(&fig, "single"));
}

#[test]
fn huge_and_tiny_values_stay_finite_in_the_svg() {
    let fig = Figure::new("Extremes")
        .series(Series::line(
            "huge",
            vec![(0.0, 1e299), (1.0, -1e299), (2.0, 1e308)],
        ))
        .series(Series::line("tiny", vec![(0.0, 5e-324), (1.0, 0.0)]))
        .y_range(0.0, 1e-300);
    assert_svg(&write_and_read(&fig, "extremes"));
    let fig = Figure::new("Steep slope")
        .log_log()
        .series(Series::line("a", vec![(1e-3, 1e-3), (1e-1, 1e-1)]))
        .reference_slope(1e12, "absurd");
    assert_svg(&write_and_read(&fig, "steep"));
}

#[test]
fn stability_plot_draws_the_labelled_vertical_bound() {
    let fig = Figure::new("Spectral radius")
        .x_label("k")
        .y_label("ρ")
        .semilog_x()
        .series(Series::line_markers(
            "explicit",
            (0..12).map(|i| {
                let k = 1e-4 * 2f64.powi(i);
                (k, (1.0 - 400.0 * k).abs())
            }),
        ))
        .vertical_line(5e-3, "predicted bound")
        .horizontal_line(1.0, "ρ = 1");
    let svg = write_and_read(&fig, "stability");
    assert_svg(&svg);
    assert!(has_text(&svg, "predicted bound") && has_text(&svg, "ρ = 1"));
}

#[test]
fn panels_hold_every_figure_and_grow_with_the_grid() {
    let field = Figure::new("(a) field").x_label("x").series(Series::line(
        "u(t=1)",
        (0..50).map(|i| (i as f64 / 49.0, (i as f64 / 7.0).sin())),
    ));
    let error = Figure::new("(b) error")
        .x_label("x")
        .semilog_y()
        .series(Series::line(
            "|u − u_h|",
            (0..50).map(|i| (i as f64 / 49.0, 1e-6 * (1.0 + i as f64))),
        ));
    let path = temp_svg("panels");
    write_panels_svg(
        &[field.clone(), error.clone(), convergence_figure()],
        2,
        &path,
    )
    .expect("panels");
    let svg = std::fs::read_to_string(&path).expect("read back");
    let _ = std::fs::remove_file(&path);
    assert_svg(&svg);
    for text in ["(a) field", "(b) error", "Convergence in h", "slope 2"] {
        assert!(has_text(&svg, text), "missing {text:?}");
    }
    let (w, h) = (PANEL_SIZE.0 * 2, PANEL_SIZE.1 * 2);
    assert!(svg.contains(&format!("width=\"{w}\"")) && svg.contains(&format!("height=\"{h}\"")));

    // Zero columns are clamped to one; no figure at all is an error.
    let path = temp_svg("panels_stacked");
    write_panels_svg(&[field, error], 0, &path).expect("stacked panels");
    let svg = std::fs::read_to_string(&path).expect("read back");
    let _ = std::fs::remove_file(&path);
    assert!(svg.contains(&format!("height=\"{}\"", PANEL_SIZE.1 * 2)));
    assert!(matches!(
        write_panels_svg(&[], 2, &temp_svg("none")),
        Err(PlotError::NoFigures { .. })
    ));
}

#[test]
fn writing_twice_gives_identical_bytes() {
    let fig = convergence_figure()
        .series(
            Series::line("dashed", vec![(0.1, 1e-3), (0.02, 1e-4)])
                .dashed()
                .color(5),
        )
        .vertical_line(0.05, "bound");
    let (a, b) = (temp_svg("det_a"), temp_svg("det_b"));
    write_svg(&fig, &a).expect("first write");
    write_svg(&fig, &b).expect("second write");
    let (ba, bb) = (std::fs::read(&a).expect("a"), std::fs::read(&b).expect("b"));
    let _ = (std::fs::remove_file(&a), std::fs::remove_file(&b));
    assert!(!ba.is_empty());
    assert_eq!(ba, bb);
}

#[test]
fn unwritable_path_is_an_io_error_naming_the_path() {
    let blocker = temp_svg("blocker");
    std::fs::write(&blocker, "not a folder").expect("blocker file");
    let target = blocker.join("inside.svg");
    let err = write_svg(&convergence_figure(), &target).expect_err("must fail");
    let _ = std::fs::remove_file(&blocker);
    assert!(matches!(err, PlotError::Io { .. }));
    assert!(err.to_string().contains("blocker"), "{err}");
}

/// Figures like those of the verification report, for looking at by eye.
fn demo_figures() -> (Figure, Vec<Figure>) {
    let hs: Vec<f64> = (0..6).map(|i| 0.2 / 2f64.powi(i)).collect();
    let convergence = Figure::new("Convergence of the contact pressure in h")
        .x_label("mesh size h")
        .y_label("L2 error")
        .log_log()
        .series(Series::line_markers(
            "P1, penalty",
            hs.iter().map(|&h| (h, 0.8 * h * (1.0 + 0.3 * h))),
        ))
        .series(Series::line_markers(
            "P2, Nitsche",
            hs.iter().map(|&h| (h, 0.6 * h * h)),
        ))
        .series(
            Series::line_markers("P2, Lagrange", hs.iter().map(|&h| (h, 0.25 * h * h))).dashed(),
        )
        .reference_slope(1.0, "slope 1")
        .reference_slope(2.0, "slope 2");

    let xs: Vec<f64> = (0..=100).map(|i| f64::from(i) / 100.0).collect();
    let field = Figure::new("(a) displacement u(x, t)")
        .x_label("x")
        .y_label("u")
        .extend_series([0.25, 0.5, 1.0].iter().map(|&t| {
            Series::line(
                format!("t = {t}"),
                xs.iter()
                    .map(move |&x| (x, (-t * 2.0f64).exp() * (std::f64::consts::PI * x).sin())),
            )
        }));
    let error = Figure::new("(b) pointwise error |u − u_h|")
        .x_label("x")
        .y_label("error")
        .semilog_y()
        .extend_series([0.25, 0.5, 1.0].iter().map(|&t| {
            Series::line(
                format!("t = {t}"),
                xs.iter()
                    .map(move |&x| (x, 1e-4 * t * (0.05 + (6.0 * x).sin().abs()))),
            )
        }));
    let work = Figure::new("(c) work–precision")
        .x_label("CPU time [s]")
        .y_label("error at t = 1")
        .log_log()
        .series(Series::line_markers(
            "backward Euler",
            (0..6).map(|i| {
                let n = 10.0 * 2f64.powi(i);
                (1e-3 * n, 0.5 / n)
            }),
        ))
        .series(Series::line_markers(
            "BDF2",
            (0..6).map(|i| {
                let n = 10.0 * 2f64.powi(i);
                (1.3e-3 * n, 2.0 / (n * n))
            }),
        ))
        .series(Series::line_markers(
            "Crank–Nicolson",
            (0..6).map(|i| {
                let n = 10.0 * 2f64.powi(i);
                (1.1e-3 * n, 0.8 / (n * n))
            }),
        ))
        .reference_slope(-1.0, "slope −1")
        .reference_slope(-2.0, "slope −2");
    let stability = Figure::new("(d) stability of the explicit scheme")
        .x_label("time step k")
        .y_label("spectral radius")
        .semilog_x()
        .series(Series::line_markers(
            "measured",
            (0..14).map(|i| {
                let k = 1e-4 * 1.5f64.powi(i);
                (k, (1.0 - 400.0 * k).abs().max(0.2))
            }),
        ))
        .vertical_line(5e-3, "predicted bound k = 5e-3")
        .horizontal_line(1.0, "ρ = 1");
    (convergence, vec![field, error, work, stability])
}

#[test]
#[ignore = "writes demo SVGs to the temp folder for looking at by eye"]
fn demo_writes_sample_svgs_to_the_temp_folder() {
    let (convergence, panels) = demo_figures();
    let dir = std::env::temp_dir();
    write_svg(&convergence, &dir.join("plot_demo.svg")).expect("demo");
    write_panels_svg(&panels, 2, &dir.join("plot_demo_panels.svg")).expect("demo panels");
    let edge = [
        Figure::new("empty, log–log")
            .x_label("h")
            .y_label("error")
            .log_log(),
        Figure::new("hostile points on log axes")
            .log_log()
            .series(Series::line_markers(
                "mixed",
                vec![
                    (1.0, 1.0),
                    (f64::NAN, 2.0),
                    (2.0, 0.0),
                    (4.0, 0.5),
                    (8.0, 0.3),
                ],
            ))
            .series(Series::markers("all negative", vec![(-1.0, -1.0)]))
            .reference_slope(-1.0, "slope −1"),
        Figure::new("constant data")
            .series(Series::line_markers(
                "flat",
                vec![(0.0, 2.0), (1.0, 2.0), (2.0, 2.0)],
            ))
            .horizontal_line(2.0, "tolerance"),
        Figure::new("single point, fixed ranges")
            .log_log()
            .series(Series::markers("one", vec![(1e-3, 1e-6)]))
            .reference_slope(2.0, "slope 2")
            .x_range(1e-4, 1e-1)
            .y_range(1e-8, 1e-2),
    ];
    write_panels_svg(&edge, 2, &dir.join("plot_demo_edge.svg")).expect("demo edge cases");
}
