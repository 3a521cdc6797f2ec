//! The demo report renders in headless Chromium: the browser's DOM holds every scene section,
//! every figure row and one `<svg>` per plot, and a screenshot of it is a real picture.
//!
//! Needs Chromium: `$HANDSTACK_CHROMIUM` (set by `cargo xtask test`) or `/usr/bin/chromium`.
//! Without it this test fails, saying what to install; it never passes silently.

use handstack::report::browser::{Chromium, Image};
use handstack::report::{TradeSection, write_html};
use handstack::{Figure, Line, Outcome, Plot};
use std::path::{Path, PathBuf};

/// The outcomes the report is built from.
fn outcomes() -> Vec<Outcome> {
    let figure = |name: &str, met: Option<bool>| Figure {
        name: name.into(),
        label: name.into(),
        value: 1.0,
        unit: "%".into(),
        paper: Some(2.0),
        source: Some("seed".into()),
        target: met.map(|_| "≥ 1".into()),
        met,
    };
    vec![
        Outcome {
            scene: "synthetic".into(),
            title: "Synthetic".into(),
            figures: vec![
                figure("a", Some(true)),
                figure("b", Some(false)),
                figure("c", None),
            ],
            plots: vec![
                Plot::Lines {
                    title: "l".into(),
                    x_label: "x".into(),
                    y_label: "y".into(),
                    lines: vec![Line {
                        label: "q".into(),
                        points: vec![(0.0, 0.0), (1.0, 1.0)],
                    }],
                },
                Plot::Grid {
                    title: "g".into(),
                    rows: 4,
                    cols: 6,
                    values: (0..24).map(f64::from).collect(),
                    unit: "taps".into(),
                },
            ],
            wall_s: 0.1,
        },
        Outcome {
            scene: "synthetic2".into(),
            title: "Synthetic 2".into(),
            figures: vec![],
            plots: vec![
                Plot::Confusion {
                    title: "conf".into(),
                    labels: (0..9).map(|i| format!("R{i}")).collect(),
                    counts: (0..9)
                        .map(|t| {
                            (0..9)
                                .map(|p| if t == p { 20 } else { (t * p % 3) as u32 })
                                .collect()
                        })
                        .collect(),
                },
                Plot::Surface {
                    title: "surface".into(),
                    x_label: "e".into(),
                    y_label: "de".into(),
                    z_label: "torque".into(),
                    xs: (0..41).map(|i| -1.0 + i as f64 / 20.0).collect(),
                    ys: (0..41).map(|i| -1.0 + i as f64 / 20.0).collect(),
                    z: (0..41)
                        .map(|j| {
                            (0..41)
                                .map(|i| {
                                    let (x, y) = (-1.0 + i as f64 / 20.0, -1.0 + j as f64 / 20.0);
                                    511.5 + 400.0 * (2.0 * x + y).tanh()
                                })
                                .collect()
                        })
                        .collect(),
                },
            ],
            wall_s: 0.2,
        },
    ]
}

fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The slice of `dom` from the element with `id` to the end of its `<section>`.
fn section<'a>(dom: &'a str, id: &str) -> &'a str {
    let start = dom
        .find(&format!("id=\"{id}\""))
        .unwrap_or_else(|| panic!("the rendered DOM has no section {id}"));
    let rest = &dom[start..];
    &rest[..rest.find("</section>").expect("section is closed")]
}

#[test]
fn report_renders_in_headless_chromium() {
    let chromium = Chromium::find().unwrap_or_else(|e| {
        panic!("{e}\n(run `cargo xtask test`, which sets HANDSTACK_CHROMIUM, or install chromium)")
    });
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("report_render");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let page = dir.join("report.html");
    let outcomes = outcomes();
    let points = workspace_root().join("docs/trade/points.csv");
    write_html(&outcomes, &[], Some(&points), &page).unwrap();

    // 1. The browser parsed what we wrote.
    let dom = chromium.dump_dom(&page, &dir).unwrap();
    assert_eq!(
        dom.matches("<section class=\"scene\"").count(),
        outcomes.len()
    );
    for o in &outcomes {
        let s = section(&dom, &format!("scene-{}", o.scene));
        for f in &o.figures {
            assert!(
                s.contains(&format!("data-figure=\"{}\"", f.name)),
                "{}: figure row {} missing from the rendered DOM",
                o.scene,
                f.name
            );
        }
        assert_eq!(
            s.matches("<svg").count(),
            o.plots.len(),
            "{}: one svg per plot",
            o.scene
        );
    }
    let trade = section(&dom, "trade");
    match TradeSection::load(&points).unwrap() {
        TradeSection::Points { points, .. } => {
            let mut tasks: Vec<&str> = points.iter().map(|p| p.task.as_str()).collect();
            tasks.sort_unstable();
            tasks.dedup();
            assert_eq!(
                trade.matches("<svg").count(),
                tasks.len(),
                "one trade plot per task"
            );
        }
        _ => assert!(
            trade.contains("is absent"),
            "the trade section says the points are absent"
        ),
    }

    // 2. A screenshot of the window size that is a picture, not a blank page.
    let png = dir.join("report.png");
    chromium
        .screenshot(&page, &png, (1024, 2600), &dir)
        .unwrap();
    let image = Image::read(&png).unwrap();
    assert_eq!((image.width, image.height), (1024, 2600));
    let colours = image.distinct_colours();
    assert!(
        colours > 32,
        "screenshot has only {colours} colours: blank?"
    );
    println!(
        "rendered: {} bytes of DOM, screenshot with {colours} colours",
        dom.len()
    );
}
