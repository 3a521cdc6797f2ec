//! The demo report renders in headless Chromium: the browser's DOM holds every scene section,
//! every figure row and one `<svg>` per plot, and a screenshot of it is a real picture.
//!
//! Needs Chromium: `$HANDSTACK_CHROMIUM` (set by `cargo xtask test`) or `/usr/bin/chromium`.
//! Without it this test fails, saying what to install; it never passes silently.

use crate::common;

use common::run_scene;
use handstack::{Outcome, Plot};
use paper_scenes::report::browser::{Chromium, Image};
use paper_scenes::report::{TRADE_POINTS, TradeSection, write_html};
use std::path::{Path, PathBuf};

/// The committed scenes the report is built from: real runs, the cheap ones (≈ 1.3 s in all),
/// which between them draw every plot kind (lines, grids, confusion matrices, the surface).
const SCENES: [&str; 4] = [
    "weight-estimation",
    "contact-location",
    "softness",
    "grasp-table5",
];

fn workspace_root() -> PathBuf {
    common::root()
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
    let outcomes: Vec<Outcome> = SCENES.iter().map(|s| run_scene(s)).collect();
    let kinds: Vec<&str> = outcomes
        .iter()
        .flat_map(|o| &o.plots)
        .map(|p| match p {
            Plot::Lines { .. } => "lines",
            Plot::Confusion { .. } => "confusion",
            Plot::Grid { .. } => "grid",
            Plot::Surface { .. } => "surface",
        })
        .collect();
    for kind in ["lines", "confusion", "grid", "surface"] {
        assert!(kinds.contains(&kind), "no {kind} plot among {SCENES:?}");
    }
    let points = workspace_root().join(TRADE_POINTS);
    write_html(&outcomes, &[], Some(&points), &page).unwrap();

    // 1. The browser parsed what we wrote.
    let dom = chromium
        .dump_dom(&page, &dir)
        .unwrap_or_else(|e| panic!("{e}"));
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
        .screenshot(&page, &png, (1024, 1400), &dir)
        .unwrap_or_else(|e| panic!("{e}"));
    let image = Image::read(&png).unwrap();
    assert_eq!((image.width, image.height), (1024, 1400));
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
