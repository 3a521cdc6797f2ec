//! The page: header, summary, one section per scene, the trade section. Every text that comes
//! from data goes through [`escape`]; plots come from [`plot_svg`] (plotters escapes its text).

use super::plot_svg::{self, Drawn};
use super::trade_points::{self, TradePoint};
use super::{Failed, Provenance, ReportError, TradeSection, escape, fmt_num};
use handstack::{Figure, Line, Outcome, Plot};
use std::fmt::Write as _;

const STYLE: &str = "
body { font: 15px/1.45 system-ui, -apple-system, 'Segoe UI', 'DejaVu Sans', sans-serif;
       color: #1d2330; background: #f4f5f7; margin: 0; }
main { max-width: 1400px; margin: 0 auto; padding: 0 24px 40px; }
header { background: #1d2a44; color: #fff; padding: 18px 24px; }
header h1 { margin: 0 0 4px; font-size: 24px; }
header .meta { margin: 0; color: #c9d3e6; font-size: 13px; }
header code { color: #fff; }
h2 { margin: 0 0 2px; font-size: 20px; }
h3 { margin: 18px 0 6px; font-size: 16px; }
section { background: #fff; border: 1px solid #dde1e8; border-radius: 6px; padding: 16px 20px;
          margin: 18px 0; }
.sub { color: #5b6475; margin: 0 0 10px; font-size: 13px; }
table { border-collapse: collapse; margin: 6px 0 10px; font-size: 14px; }
th, td { border-bottom: 1px solid #e4e7ec; padding: 4px 10px; text-align: left;
         vertical-align: top; }
th { background: #f0f2f5; font-weight: 600; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
td.met { font-weight: 600; white-space: nowrap; }
td.target { white-space: nowrap; }
td.met.yes { color: #11602a; background: #e3f5e8; }
td.met.no { color: #9c1c1c; background: #fbe4e4; }
td.met.none { color: #8a8f99; }
td.met.finding { color: #7a4b00; background: #fff6e0; white-space: normal; max-width: 360px; }
.why { font-weight: 400; font-size: 12px; }
.src { color: #5b6475; font-size: 12px; }
.plots { display: flex; flex-wrap: wrap; gap: 14px; }
figure.plot { margin: 0; border: 1px solid #e4e7ec; border-radius: 4px; padding: 6px;
              background: #fff; }
figure.plot svg { display: block; max-width: 100%; height: auto; }
figcaption { font-size: 13px; padding: 4px 4px 0; max-width: 640px; }
.entry { white-space: nowrap; margin-right: 12px; }
.swatch { display: inline-block; width: 14px; height: 5px; margin: 0 4px 3px 0;
          vertical-align: middle; }
.note { color: #7a4b00; background: #fff6e0; border-left: 4px solid #e0a800;
        padding: 6px 10px; }
a { color: #1d4f91; }
";

/// The whole page for `outcomes`, the `failed` scenes, the `trade` section and the `header`.
pub fn render(
    outcomes: &[Outcome],
    failed: &[Failed],
    trade: &TradeSection,
    header: &Provenance,
) -> Result<String, ReportError> {
    let mut page = String::new();
    let w = &mut page;
    let _ = write!(
        w,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>handstack demo report</title>\n<style>{STYLE}</style>\n</head>\n<body>\n\
         <header><h1>handstack — demo report</h1>\n\
         <p class=\"meta\">commit <code>{}</code> · {} · {} cores, {}</p></header>\n<main>\n",
        escape(&header.commit),
        escape(&header.date_utc),
        header.cores,
        escape(&header.machine),
    );
    lead(w, outcomes, failed);
    summary(w, outcomes, failed);
    for outcome in outcomes {
        scene(w, outcome)?;
    }
    for f in failed {
        let _ = writeln!(
            w,
            "<section class=\"scene-failed\" id=\"failed-{0}\"><h2>{0}: failed</h2>\
             <pre class=\"note\">{1}</pre></section>",
            escape(&f.scene),
            escape(&f.error),
        );
    }
    trade_section(w, trade)?;
    w.push_str("</main>\n</body>\n</html>\n");
    Ok(page)
}

fn scene_id(outcome: &Outcome) -> String {
    format!("scene-{}", escape(&outcome.scene))
}

/// How an outcome's targets went.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
struct Tally {
    /// Figures with a target.
    targets: usize,
    /// Of those, met.
    met: usize,
    /// Missed, for a reason of the method measured (a paper's formula as written).
    findings: usize,
}

impl Tally {
    fn of(outcome: &Outcome) -> Tally {
        let mut t = Tally::default();
        for f in outcome.figures.iter().filter(|f| f.target.is_some()) {
            t.targets += 1;
            match (f.met, &f.finding) {
                (Some(true), _) => t.met += 1,
                (Some(false), Some(_)) => t.findings += 1,
                _ => {}
            }
        }
        t
    }

    fn add(self, o: Tally) -> Tally {
        Tally {
            targets: self.targets + o.targets,
            met: self.met + o.met,
            findings: self.findings + o.findings,
        }
    }

    /// Missed, and not findings.
    fn misses(self) -> usize {
        self.targets - self.met - self.findings
    }

    /// `met / targets`, with the findings named.
    fn text(self) -> String {
        match self.findings {
            0 => format!("{} / {}", self.met, self.targets),
            1 => format!("{} / {} · 1 finding", self.met, self.targets),
            n => format!("{} / {} · {n} findings", self.met, self.targets),
        }
    }

    /// The summary cell's class: all met, the rest findings, or a miss of ours.
    fn class(self) -> &'static str {
        match (self.targets, self.misses()) {
            (0, _) => "none",
            (_, 0) if self.findings == 0 => "yes",
            (_, 0) => "finding",
            _ => "no",
        }
    }
}

/// What the simulated stack achieves over every scene, first: targets met, findings, and our
/// own misses by name.
fn lead(w: &mut String, outcomes: &[Outcome], failed: &[Failed]) {
    let total = outcomes
        .iter()
        .map(Tally::of)
        .fold(Tally::default(), Tally::add);
    let _ = write!(
        w,
        "<section class=\"lead\" id=\"lead\"><h2>What the stack achieves</h2>\n<p>Over {} \
         scene{}, the simulated stack meets <strong>{} of {} targets</strong>.",
        outcomes.len(),
        if outcomes.len() == 1 { "" } else { "s" },
        total.met,
        total.targets,
    );
    if total.findings > 0 {
        let _ = write!(
            w,
            " {} {} the papers' own methods as written, which miss their targets for the \
             reason given beside each (amber).",
            total.findings,
            if total.findings == 1 {
                "is a finding about"
            } else {
                "are findings about"
            },
        );
    }
    let ours: Vec<String> = outcomes
        .iter()
        .flat_map(|o| {
            o.figures
                .iter()
                .filter(|f| f.met == Some(false) && f.finding.is_none())
                .map(move |f| {
                    format!(
                        "{} ({}: {}{}, target {})",
                        escape(&f.label),
                        escape(&o.scene),
                        fmt_num(f.value),
                        if f.unit.is_empty() {
                            String::new()
                        } else {
                            format!(" {}", escape(&f.unit))
                        },
                        f.target.as_deref().map_or("—".into(), escape)
                    )
                })
        })
        .collect();
    match ours.len() {
        0 => w.push_str(" Every other target is met."),
        _ => {
            let _ = write!(w, " Missed by this software: {}.", ours.join("; "));
        }
    }
    if !failed.is_empty() {
        let _ = write!(
            w,
            " {} scene(s) failed to run (listed below).",
            failed.len()
        );
    }
    w.push_str("</p></section>\n");
}

fn summary(w: &mut String, outcomes: &[Outcome], failed: &[Failed]) {
    w.push_str(
        "<section class=\"summary\" id=\"summary\"><h2>Scenes</h2>\n\
         <table><thead><tr><th>scene</th><th>what it reproduces</th><th>targets met</th>\
         <th>figures</th><th>plots</th><th>wall time</th></tr></thead><tbody>\n",
    );
    for o in outcomes {
        let t = Tally::of(o);
        let verdict = match t.targets {
            0 => "<td class=\"met none\">no targets</td>".to_owned(),
            _ => format!("<td class=\"met {}\">{}</td>", t.class(), t.text()),
        };
        let _ = writeln!(
            w,
            "<tr><td><a href=\"#{}\">{}</a></td><td>{}</td>\
             {verdict}<td class=\"num\">{}</td>\
             <td class=\"num\">{}</td><td class=\"num\">{} s</td></tr>",
            scene_id(o),
            escape(&o.scene),
            escape(&o.title),
            o.figures.len(),
            o.plots.len(),
            fmt_num(o.wall_s),
        );
    }
    for f in failed {
        let _ = writeln!(
            w,
            "<tr><td><a href=\"#failed-{0}\">{0}</a></td><td>—</td>\
             <td class=\"met no\">run failed</td><td></td><td></td><td></td></tr>",
            escape(&f.scene)
        );
    }
    if outcomes.is_empty() && failed.is_empty() {
        w.push_str("<tr><td colspan=\"6\">no scenes were run</td></tr>\n");
    }
    w.push_str("</tbody></table></section>\n");
}

fn scene(w: &mut String, o: &Outcome) -> Result<(), ReportError> {
    let t = Tally::of(o);
    let findings = match t.findings {
        0 => String::new(),
        1 => " (1 finding)".to_owned(),
        n => format!(" ({n} findings)"),
    };
    let _ = write!(
        w,
        "<section class=\"scene\" id=\"{}\" data-scene=\"{}\">\n<h2>{}</h2>\n\
         <p class=\"sub\">scene <code>{}</code> · {} of {} targets met{findings} · {} s</p>\n",
        scene_id(o),
        escape(&o.scene),
        escape(&o.title),
        escape(&o.scene),
        t.met,
        t.targets,
        fmt_num(o.wall_s),
    );
    figures_table(w, &o.figures);
    plots(w, &o.plots)?;
    w.push_str("</section>\n");
    Ok(())
}

fn figures_table(w: &mut String, figures: &[Figure]) {
    if figures.is_empty() {
        w.push_str("<p class=\"note\">This run measured no figures.</p>\n");
        return;
    }
    w.push_str(
        "<table class=\"figures\"><thead><tr><th>figure</th><th>value</th><th>paper</th>\
         <th>target</th><th>met</th></tr></thead><tbody>\n",
    );
    for f in figures {
        let unit = if f.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", escape(&f.unit))
        };
        let paper = match (&f.paper, &f.source) {
            (Some(p), Some(s)) => format!(
                "{}{unit} <span class=\"src\">({})</span>",
                fmt_num(*p),
                escape(s)
            ),
            (Some(p), None) => format!("{}{unit}", fmt_num(*p)),
            (None, _) => "—".into(),
        };
        // Honest marking: only `Some(true)` is met; a target without a verdict says so.
        let met = match (&f.target, f.met, &f.finding) {
            (_, Some(true), _) => "<td class=\"met yes\">✔ met</td>".to_owned(),
            (_, Some(false), Some(why)) => format!(
                "<td class=\"met finding\">✘ not met: a finding<br><span class=\"why\">{}</span></td>",
                escape(why)
            ),
            (_, Some(false), None) => "<td class=\"met no\">✘ not met</td>".to_owned(),
            (Some(_), None, _) => "<td class=\"met none\">not assessed</td>".to_owned(),
            (None, None, _) => "<td class=\"met none\">no target</td>".to_owned(),
        };
        let _ = writeln!(
            w,
            "<tr class=\"figure\" data-figure=\"{}\"><td>{}</td><td class=\"num\">{}{unit}</td>\
             <td class=\"num\">{paper}</td><td class=\"target\">{}</td>{met}</tr>",
            escape(&f.name),
            escape(&f.label),
            fmt_num(f.value),
            f.target.as_deref().map_or("—".into(), escape),
        );
    }
    w.push_str("</tbody></table>\n");
}

fn plots(w: &mut String, plots: &[Plot]) -> Result<(), ReportError> {
    let with_no_front: Vec<(&Plot, Option<&Line>)> = plots.iter().map(|p| (p, None)).collect();
    plots_with_fronts(w, &with_no_front)
}

fn plots_with_fronts(w: &mut String, plots: &[(&Plot, Option<&Line>)]) -> Result<(), ReportError> {
    if plots.is_empty() {
        return Ok(());
    }
    w.push_str("<div class=\"plots\">\n");
    for (i, (plot, front)) in plots.iter().enumerate() {
        let Drawn { svg, legend } = plot_svg::draw(plot, *front)?;
        let _ = write!(w, "<figure class=\"plot\" data-plot=\"{i}\">\n{svg}\n");
        if !legend.is_empty() {
            w.push_str("<figcaption>");
            for (label, colour) in legend {
                let _ = write!(
                    w,
                    "<span class=\"entry\"><span class=\"swatch\" \
                     style=\"background:{colour}\"></span>{}</span> ",
                    escape(&label)
                );
            }
            w.push_str("</figcaption>\n");
        }
        w.push_str("</figure>\n");
    }
    w.push_str("</div>\n");
    Ok(())
}

fn trade_section(w: &mut String, trade: &TradeSection) -> Result<(), ReportError> {
    w.push_str("<section class=\"trade\" id=\"trade\">\n<h2>Speed / accuracy trade</h2>\n");
    match trade {
        TradeSection::NotRequested => {
            w.push_str("<p class=\"note\">No trade points were given to this report.</p>\n")
        }
        TradeSection::Absent(path) => {
            let _ = writeln!(
                w,
                "<p class=\"note\">The trade points file <code>{}</code> is absent: \
                 run <code>cargo xtask trade</code> to measure them.</p>",
                escape(&shown(path))
            );
        }
        TradeSection::Points { path, points } => {
            let _ = writeln!(
                w,
                "<p class=\"sub\">{} points from <code>{}</code>: one plot per task, a line \
                 per knob through its settings by cost, the task's Pareto front as the amber \
                 band (higher is better for accuracies, lower for errors and noise).</p>",
                points.len(),
                escape(&shown(path))
            );
            let tasks = trade_points::tasks(points);
            let task_plots: Vec<(Plot, Line)> = tasks
                .iter()
                .map(|t| trade_points::task_plot(points, t))
                .collect();
            let refs: Vec<(&Plot, Option<&Line>)> =
                task_plots.iter().map(|(p, f)| (p, Some(f))).collect();
            plots_with_fronts(w, &refs)?;
            pareto_table(w, points, &tasks);
        }
    }
    w.push_str("</section>\n");
    Ok(())
}

/// `path` for people: `..` folded away, and relative to the working directory when inside it.
fn shown(path: &std::path::Path) -> String {
    use std::path::Component;
    let mut full = std::path::PathBuf::new();
    for c in path.components() {
        match c {
            Component::ParentDir if full.file_name().is_some() => {
                full.pop();
            }
            c => full.push(c),
        }
    }
    let cwd = std::env::current_dir().ok();
    cwd.and_then(|d| full.strip_prefix(d).ok().map(|p| p.display().to_string()))
        .unwrap_or_else(|| full.display().to_string())
}

fn pareto_table(w: &mut String, points: &[TradePoint], tasks: &[&str]) {
    w.push_str(
        "<h3>Pareto front per task</h3>\n<table class=\"pareto\"><thead><tr><th>task</th>\
         <th>knob</th><th>setting</th><th>cost per cycle</th><th>quality figure</th></tr>\
         </thead><tbody>\n",
    );
    for task in tasks {
        let mut front: Vec<&TradePoint> = points
            .iter()
            .filter(|p| p.task == *task && p.pareto)
            .collect();
        front.sort_by(|a, b| a.cost_us.total_cmp(&b.cost_us));
        for p in front {
            let _ = writeln!(
                w,
                "<tr><td>{}</td><td>{}</td><td>{}</td><td class=\"num\">{} µs</td>\
                 <td class=\"num\">{} {}</td></tr>",
                escape(&p.task),
                escape(&p.knob),
                escape(&p.setting),
                fmt_num(p.cost_us),
                fmt_num(p.accuracy),
                escape(&p.unit),
            );
        }
    }
    w.push_str("</tbody></table>\n");
}

#[cfg(test)]
mod tests {
    use super::*;

    fn figure(name: &str, target: Option<&str>, met: Option<bool>) -> Figure {
        Figure {
            name: name.into(),
            label: format!("{name} <label>"),
            value: 1.25,
            unit: "%".into(),
            paper: Some(2.0),
            source: Some("seed 000 Table 1".into()),
            target: target.map(Into::into),
            met,
            finding: None,
        }
    }

    fn outcome() -> Outcome {
        Outcome {
            scene: "s&t".into(),
            title: "Title <script>alert(1)</script>".into(),
            figures: vec![
                figure("a", Some("≥ 1"), Some(true)),
                figure("b", Some("≥ 9"), Some(false)),
                figure("c", None, None),
            ],
            notes: vec![],
            plots: vec![Plot::Lines {
                title: "trace <1>".into(),
                x_label: "t, s".into(),
                y_label: "F, N".into(),
                lines: vec![Line {
                    label: "finger & thumb".into(),
                    points: vec![(0.0, 1.0), (1.0, 2.0)],
                }],
            }],
            wall_s: 0.5,
        }
    }

    #[test]
    fn data_text_is_escaped_everywhere() {
        let html = render(
            &[outcome()],
            &[],
            &TradeSection::NotRequested,
            &Provenance::fixed("<c>"),
        )
        .unwrap();
        assert!(!html.contains("<script>"));
        assert!(html.contains("Title &lt;script&gt;alert(1)&lt;/script&gt;"));
        assert!(html.contains("a &lt;label&gt;"));
        assert!(html.contains("finger &amp; thumb"));
        assert!(html.contains("id=\"scene-s&amp;t\""));
        assert!(html.contains("<code>&lt;c&gt;</code>"));
        assert!(html.contains("trace &lt;1&gt;")); // plotters' own escaping
    }

    #[test]
    fn findings_are_told_apart_from_our_misses_and_the_page_opens_with_the_totals() {
        let mut o = outcome();
        let mut eq3 = figure("eq3", Some("≥ 90 %"), Some(false));
        eq3.finding = Some("the formula as written <names> three areas".into());
        o.figures.push(eq3);
        let html = render(
            &[o],
            &[],
            &TradeSection::NotRequested,
            &Provenance::fixed("x"),
        )
        .unwrap();
        // The finding: amber, its reason beside it (escaped); our miss stays red.
        assert!(html.contains(
            "<td class=\"met finding\">✘ not met: a finding<br><span class=\"why\">the \
             formula as written &lt;names&gt; three areas</span></td>"
        ));
        assert_eq!(html.matches("class=\"met no\">✘ not met").count(), 1);
        // The totals first, then the scenes: 1 of 3 met, one finding, our miss by name.
        let lead = html.find("What the stack achieves").expect("the lead");
        assert!(lead < html.find("<h2>Scenes</h2>").expect("the scene table"));
        assert!(html.contains("meets <strong>1 of 3 targets</strong>. 1 is a finding about"));
        assert!(
            html.contains(
                "Missed by this software: b &lt;label&gt; (s&amp;t: 1.25 %, target ≥ 9)."
            )
        );
        assert!(html.contains("<td class=\"met no\">1 / 3 · 1 finding</td>"));
        assert!(html.contains("1 of 3 targets met (1 finding)"));
    }

    #[test]
    fn met_and_unmet_targets_are_marked_as_they_are() {
        let html = render(
            &[outcome()],
            &[],
            &TradeSection::NotRequested,
            &Provenance::fixed("x"),
        )
        .unwrap();
        assert_eq!(html.matches("class=\"met yes\">✔ met").count(), 1);
        assert_eq!(html.matches("class=\"met no\">✘ not met").count(), 1);
        assert_eq!(html.matches("no target").count(), 1);
        // The summary shows 1 of 2 targets met, in the "no" colour.
        assert!(html.contains("<td class=\"met no\">1 / 2</td>"));
        assert!(html.contains("Missed by this software: b"));
        assert_eq!(html.matches("<svg").count(), 1);
    }

    #[test]
    fn failed_scenes_are_listed_with_their_error() {
        let failed = [Failed {
            scene: "tap-to-ur3".into(),
            error: "ur_rtde: <no venv>".into(),
        }];
        let html = render(
            &[outcome()],
            &failed,
            &TradeSection::NotRequested,
            &Provenance::fixed("x"),
        )
        .unwrap();
        assert!(html.contains("<td class=\"met no\">run failed</td>"));
        assert!(html.contains("<h2>tap-to-ur3: failed</h2>"));
        assert!(html.contains("ur_rtde: &lt;no venv&gt;"));
    }

    #[test]
    fn trade_section_says_why_it_is_empty() {
        let absent = TradeSection::Absent("docs/trade/points.csv".into());
        let html = render(&[], &[], &absent, &Provenance::fixed("x")).unwrap();
        assert!(html.contains("<code>docs/trade/points.csv</code> is absent"));
        assert!(html.contains("no scenes were run"));
    }

    #[test]
    fn trade_points_give_a_plot_per_task_and_the_front_table() {
        let points = trade_points::parse(
            "task,knob,setting,cost_us,accuracy,accuracy_unit,pareto\n\
             force,osr,256,1.5,80,%,true\nforce,osr,4096,9.0,97,%,true\n\
             location,method,aot,0.4,60,%,true\nlocation,method,cnn,300,93,%,false\n",
            "points.csv".as_ref(),
        )
        .unwrap();
        let section = TradeSection::Points {
            path: "points.csv".into(),
            points,
        };
        let html = render(&[], &[], &section, &Provenance::fixed("x")).unwrap();
        assert_eq!(html.matches("<svg").count(), 2);
        let table = &html[html.find("class=\"pareto\"").unwrap()..];
        assert_eq!(table.matches("<tr><td>").count(), 3); // the three Pareto points
        assert!(html.contains("(log scale)")); // location spans 0.4–300 µs
        assert_eq!(shown("a/b/../../docs/x.csv".as_ref()), "docs/x.csv");
    }
}
