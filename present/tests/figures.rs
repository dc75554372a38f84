//! The drawing kit writes real figures: SVG with the chart's text, PNG with its signature.

#[test]
fn heat_map_and_chart_figures_are_written_and_non_empty() {
    use chronocooked_present::figures::{Chart, Series, write_chart, write_heatmap};
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("cc-figs-{}", std::process::id()));
    // A sequence: unit i active at step i (time × units, row-major).
    let avg: Vec<f64> = (0..12 * 12)
        .map(|k| if k / 12 == k % 12 { 1.0 } else { 0.0 })
        .collect();
    let files = write_heatmap(&dir.join("seq"), "sequence", &avg, 12).unwrap();
    let chart = Chart {
        title: "learning curve".into(),
        x_label: "env steps".into(),
        y_label: "success".into(),
        series: vec![Series {
            label: "seed 0".into(),
            points: (0..10)
                .map(|k| (k as f64, (k as f64 / 9.0).powi(2)))
                .collect(),
            line: true,
            color: 0,
        }],
        markers: vec![(5.0, "half".into())],
        y_range: Some((0.0, 1.0)),
    };
    let more = write_chart(&dir.join("curve"), &chart).unwrap();
    for f in files.iter().chain(&more) {
        let len = std::fs::metadata(f).unwrap().len();
        assert!(len > 2000, "{}: {len} bytes", f.display());
    }
    let svg = std::fs::read_to_string(dir.join("curve.svg")).unwrap();
    assert!(svg.contains("learning curve") && svg.contains("seed 0"));
    let png = std::fs::read(dir.join("seq.png")).unwrap();
    assert_eq!(&png[..4], b"\x89PNG");
    let _ = std::fs::remove_dir_all(&dir);
}
