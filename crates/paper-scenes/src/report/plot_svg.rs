//! Each [`Plot`] as an inline SVG string, drawn with plotters' SVG backend (which escapes the
//! text it writes). Non-finite values are skipped or drawn grey, never panicked on.

use super::ReportError;
use handstack::{Line, Plot};
use paper_experiments::axis::{fmt_num, fmt_tick, padded, span, wants_log};
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

/// A drawn plot: the `<svg>` element and, for line plots, the legend (label, CSS colour) the
/// page prints beside it as text.
pub(super) struct Drawn {
    pub svg: String,
    pub legend: Vec<(String, String)>,
}

/// Line colours (Tableau 10): distinct, readable on white, in legend order.
const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];
const MISSING: RGBColor = RGBColor(200, 200, 200);
const FONT: &str = "sans-serif";

type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// The plot's title.
pub(super) fn title(plot: &Plot) -> &str {
    match plot {
        Plot::Lines { title, .. }
        | Plot::Confusion { title, .. }
        | Plot::Grid { title, .. }
        | Plot::Surface { title, .. } => title,
    }
}

/// Draws `plot` into an SVG string. A trade plot passes its Pareto `front`: drawn as a wide
/// translucent band under the lines (so points on the front stay visible on their own line),
/// with a log cost axis when the costs span two decades.
pub(super) fn draw(plot: &Plot, front: Option<&Line>) -> Result<Drawn, ReportError> {
    let err = |e: &dyn std::fmt::Display| ReportError::Plot {
        title: title(plot).to_owned(),
        message: e.to_string(),
    };
    let mut svg = String::new();
    let mut legend = Vec::new();
    {
        let (w, h) = size(plot);
        let area = SVGBackend::with_string(&mut svg, (w, h)).into_drawing_area();
        area.fill(&WHITE).map_err(|e| err(&e))?;
        let drawn = match plot {
            Plot::Lines {
                title,
                x_label,
                y_label,
                lines: ls,
            } => lines(&area, title, (x_label, y_label), ls, front).map(|l| legend = l),
            Plot::Confusion {
                title,
                labels,
                counts,
            } => confusion(&area, title, labels, counts),
            Plot::Grid {
                title,
                rows,
                cols,
                values,
                unit,
            } => grid(&area, title, *rows, *cols, values, unit),
            Plot::Surface {
                title,
                x_label,
                y_label,
                z_label,
                xs,
                ys,
                z,
            } => surface(&area, title, (x_label, y_label, z_label), xs, ys, z),
        };
        drawn.map_err(|e| err(&e))?;
        area.present().map_err(|e| err(&e))?;
    }
    Ok(Drawn { svg, legend })
}

/// Pixel size per plot kind: heat maps grow with their cell count, within bounds, and are
/// never narrower than their title.
fn size(plot: &Plot) -> (u32, u32) {
    let title_px = 10 * title(plot).chars().count().min(90) as u32 + 60;
    match plot {
        Plot::Lines { .. } => (620, 400),
        Plot::Confusion { labels, counts, .. } => {
            let n = labels.len().max(counts.len()).clamp(2, 24) as u32;
            let side = 140 + 44 * n;
            ((side + 112).max(title_px), side)
        }
        Plot::Grid { rows, cols, .. } => {
            let cell = 64;
            let (r, c) = ((*rows).clamp(1, 16) as u32, (*cols).clamp(1, 24) as u32);
            ((c * cell + 222).max(title_px), r * cell + 90)
        }
        Plot::Surface { .. } => (660, 520),
    }
}

/// A plotters error as text (its error types differ per call).
type DrawResult<T> = Result<T, String>;

fn e<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

/// How a chart's axes are drawn: descriptions, tick formatters, a light grid or none, and
/// how many ticks (plotters picks when `None`).
struct Axes<'a> {
    desc: (&'a str, &'a str),
    fmt: (Ticks<'a>, Ticks<'a>),
    grid: bool,
    labels: Option<(usize, usize)>,
}

/// A tick label formatter.
type Ticks<'a> = &'a dyn Fn(&f64) -> String;

type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Draws `chart`'s axes in the report's one style.
fn axes(chart: &mut Chart<'_, '_>, a: Axes<'_>) -> DrawResult<()> {
    let mut mesh = chart.configure_mesh();
    mesh.x_desc(a.desc.0)
        .y_desc(a.desc.1)
        .x_label_formatter(a.fmt.0)
        .y_label_formatter(a.fmt.1)
        .label_style((FONT, 12))
        .axis_desc_style((FONT, 13));
    if a.grid {
        mesh.light_line_style(RGBColor(235, 235, 235));
    } else {
        mesh.disable_mesh();
    }
    if let Some((x, y)) = a.labels {
        mesh.x_labels(x).y_labels(y);
    }
    mesh.draw().map_err(e)
}

/// The Pareto-front band: amber, translucent, under the lines.
const FRONT: RGBAColor = RGBAColor(255, 179, 0, 0.45);

fn lines(
    area: &Area<'_>,
    title: &str,
    (x_label, y_label): (&str, &str),
    lines: &[Line],
    front: Option<&Line>,
) -> DrawResult<Vec<(String, String)>> {
    let finite = |l: &Line| {
        l.points
            .iter()
            .copied()
            .filter(|(x, y)| x.is_finite() && y.is_finite())
            .collect::<Vec<_>>()
    };
    let all: Vec<(f64, f64)> = lines.iter().chain(front).flat_map(finite).collect();
    // Trade plots (those with a front) whose costs span two decades or more read better on a
    // log axis; time and weight axes stay linear.
    let (xlo, xhi) = span(all.iter().map(|p| p.0));
    let log_x = front.is_some() && wants_log((xlo, xhi));
    let tx = |x: f64| if log_x { x.log10() } else { x };
    let x_range = padded(span(all.iter().map(|p| tx(p.0))));
    let y_range = padded(span(all.iter().map(|p| p.1)));
    let (x_axis, y_axis) = (x_range.clone(), y_range.clone());
    let x_desc = if log_x {
        format!("{x_label} (log scale)")
    } else {
        x_label.to_owned()
    };
    let mut chart = ChartBuilder::on(area)
        .caption(title, (FONT, 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(72)
        .build_cartesian_2d(x_axis, y_axis)
        .map_err(e)?;
    let x_fmt = |v: &f64| {
        if log_x {
            // Label whole decades only (0.1, 1, 10 …), not plotters' half-decade steps.
            if (v - v.round()).abs() < 1e-6 {
                fmt_num(10f64.powf(v.round()))
            } else {
                String::new()
            }
        } else {
            fmt_tick(*v, &x_range)
        }
    };
    let y_fmt = |v: &f64| fmt_tick(*v, &y_range);
    axes(
        &mut chart,
        Axes {
            desc: (&x_desc, y_label),
            fmt: (&x_fmt, &y_fmt),
            grid: true,
            labels: None,
        },
    )?;
    let mut legend = Vec::new();
    if let Some(front) = front {
        let pts = finite(front).into_iter().map(|(x, y)| (tx(x), y));
        chart
            .draw_series(LineSeries::new(pts, FRONT.stroke_width(10)))
            .map_err(e)?;
        let RGBAColor(r, g, b, a) = FRONT;
        legend.push((front.label.clone(), format!("rgba({r},{g},{b},{a})")));
    }
    for (i, line) in lines.iter().enumerate() {
        let color = PALETTE[i % PALETTE.len()];
        let pts: Vec<(f64, f64)> = finite(line).into_iter().map(|(x, y)| (tx(x), y)).collect();
        chart
            .draw_series(LineSeries::new(pts.iter().copied(), color.stroke_width(2)))
            .map_err(e)?;
        // Few points (trade settings, per-object results): mark each one.
        if pts.len() <= 60 {
            chart
                .draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))
                .map_err(e)?;
        }
        let (r, g, b) = color.rgb();
        legend.push((line.label.clone(), format!("#{r:02x}{g:02x}{b:02x}")));
    }
    if all.is_empty() {
        draw_note(area, "no finite points")?;
    }
    Ok(legend)
}

fn draw_note(area: &Area<'_>, note: &str) -> DrawResult<()> {
    let (w, h) = area.dim_in_pixel();
    area.draw(&Text::new(
        note.to_owned(),
        (w as i32 / 2 - 50, h as i32 / 2),
        (FONT, 16).into_font().color(&RED),
    ))
    .map_err(e)
}

/// Viridis colour of `v` on `lo..hi`; grey when `v` is not finite.
fn heat(v: f64, lo: f64, hi: f64) -> RGBColor {
    if !v.is_finite() {
        return MISSING;
    }
    let t = ((v - lo) / (hi - lo)).clamp(0.0, 1.0);
    ViridisRGB::get_color(t)
}

/// Black or white, whichever reads on `bg`.
fn ink(bg: RGBColor) -> RGBColor {
    let (r, g, b) = bg.rgb();
    let luma = 0.299 * f64::from(r) + 0.587 * f64::from(g) + 0.114 * f64::from(b);
    if luma > 140.0 { BLACK } else { WHITE }
}

/// A vertical colour bar for `lo..hi` in `area`, labelled `label`.
fn colour_bar(
    area: &Area<'_>,
    lo: f64,
    hi: f64,
    label: &str,
    colour: &dyn Fn(f64) -> RGBColor,
) -> DrawResult<()> {
    let mut bar = ChartBuilder::on(area)
        .margin_top(40)
        .margin_bottom(45)
        .margin_right(8)
        .y_label_area_size(74)
        .build_cartesian_2d(0.0..1.0, lo..hi)
        .map_err(e)?;
    let y_fmt = |v: &f64| fmt_tick(*v, &(lo..hi));
    bar.configure_mesh()
        .disable_x_mesh()
        .disable_x_axis()
        .disable_y_mesh()
        .y_desc(label)
        .y_labels(6)
        .y_label_formatter(&y_fmt)
        .label_style((FONT, 12))
        .axis_desc_style((FONT, 13))
        .draw()
        .map_err(e)?;
    let steps = 48;
    let dz = (hi - lo) / f64::from(steps);
    bar.draw_series((0..steps).map(|k| {
        let z = lo + dz * f64::from(k);
        Rectangle::new([(0.0, z), (1.0, z + dz)], colour(z + dz / 2.0).filled())
    }))
    .map_err(e)?;
    Ok(())
}

/// Draws a `cols × rows` matrix of coloured, labelled cells on `area`: cell `(c, r)` (row 0 at
/// the top, as matrices and seed 000 Figure 11 are printed) centred on `(c, rows - 1 - r)`.
struct Cells<'a> {
    title: &'a str,
    cols: usize,
    rows: usize,
    x_desc: &'a str,
    y_desc: &'a str,
    col_name: &'a dyn Fn(usize) -> String,
    row_name: &'a dyn Fn(usize) -> String,
    label_px: (u32, u32),
}

impl Cells<'_> {
    /// `cell(c, r)` gives each cell's colour and text.
    fn draw(
        &self,
        area: &Area<'_>,
        cell: &dyn Fn(usize, usize) -> (RGBColor, String),
    ) -> DrawResult<()> {
        let (cols, rows) = (self.cols.max(1), self.rows.max(1));
        let mut chart = ChartBuilder::on(area)
            .caption(self.title, (FONT, 18))
            .margin(12)
            .x_label_area_size(self.label_px.0)
            .y_label_area_size(self.label_px.1)
            .build_cartesian_2d(-0.5..cols as f64 - 0.5, -0.5..rows as f64 - 0.5)
            .map_err(e)?;
        // Labels only at cell centres (whole numbers inside the matrix).
        let centre = |v: f64, n: usize| {
            let i = v.round();
            ((v - i).abs() < 1e-6 && i >= 0.0 && i < n as f64).then_some(i as usize)
        };
        let x_fmt = |v: &f64| centre(*v, cols).map(self.col_name).unwrap_or_default();
        let y_fmt = |v: &f64| {
            centre(*v, rows)
                .map(|i| (self.row_name)(rows - 1 - i))
                .unwrap_or_default()
        };
        axes(
            &mut chart,
            Axes {
                desc: (self.x_desc, self.y_desc),
                fmt: (&x_fmt, &y_fmt),
                grid: false,
                labels: Some((cols + 1, rows + 1)),
            },
        )?;
        for r in 0..rows {
            for c in 0..cols {
                let (bg, text) = cell(c, r);
                let (x, y) = (c as f64, (rows - 1 - r) as f64);
                chart
                    .draw_series(std::iter::once(Rectangle::new(
                        [(x - 0.5, y - 0.5), (x + 0.5, y + 0.5)],
                        bg.filled(),
                    )))
                    .map_err(e)?;
                chart
                    .draw_series(std::iter::once(Text::new(
                        text,
                        (x, y),
                        (FONT, 12).into_font().color(&ink(bg)).pos(text_centre()),
                    )))
                    .map_err(e)?;
            }
        }
        Ok(())
    }
}

fn confusion(
    area: &Area<'_>,
    title: &str,
    labels: &[String],
    counts: &[Vec<u32>],
) -> DrawResult<()> {
    let n = labels.len().max(counts.len()).max(1);
    let (main, bar) = area.split_horizontally(area.dim_in_pixel().0 - 112);
    let name = |i: usize| labels.get(i).cloned().unwrap_or_else(|| i.to_string());
    let longest = (0..n).map(|i| name(i).chars().count()).max().unwrap_or(1) as u32;
    // Colour = share of the true class's samples (so rare classes read as well as common ones).
    let share_colour = |s: f64| {
        let s = if s.is_finite() {
            s.clamp(0.0, 1.0)
        } else {
            0.0
        };
        RGBColor(
            (247.0 - 239.0 * s) as u8,
            (251.0 - 203.0 * s) as u8,
            (255.0 - 148.0 * s) as u8,
        )
    };
    let cells = Cells {
        title,
        cols: n,
        rows: n,
        x_desc: "predicted",
        y_desc: "true",
        col_name: &name,
        row_name: &name,
        // x labels run horizontally: one text line; y labels need the longest name.
        label_px: (40, (7 * longest + 40).min(160)),
    };
    cells.draw(&main, &|p, t| {
        let row = counts.get(t).map_or(&[][..], Vec::as_slice);
        let total: u64 = row.iter().map(|&c| u64::from(c)).sum();
        let count = row.get(p).copied().unwrap_or(0);
        let share = if total == 0 {
            0.0
        } else {
            f64::from(count) / total as f64
        };
        (share_colour(share), count.to_string())
    })?;
    colour_bar(&bar, 0.0, 1.0, "share of true class", &share_colour)
}

fn text_centre() -> plotters::style::text_anchor::Pos {
    use plotters::style::text_anchor::{HPos, Pos, VPos};
    Pos::new(HPos::Center, VPos::Center)
}

fn grid(
    area: &Area<'_>,
    title: &str,
    rows: usize,
    cols: usize,
    values: &[f64],
    unit: &str,
) -> DrawResult<()> {
    let (main, bar) = area.split_horizontally(area.dim_in_pixel().0 - 112);
    let (lo, hi) = span(values.iter().copied());
    let cells = Cells {
        title,
        cols,
        rows,
        x_desc: "column",
        y_desc: "row",
        col_name: &|c| c.to_string(),
        row_name: &|r| r.to_string(),
        label_px: (40, 50),
    };
    let cols = cols.max(1);
    cells.draw(&main, &|c, r| {
        let v = values.get(r * cols + c).copied().unwrap_or(f64::NAN);
        (heat(v, lo, hi), fmt_num(v))
    })?;
    colour_bar(&bar, lo, hi, unit, &|v| heat(v, lo, hi))
}

/// Cell edges around sample points: midpoints between neighbours, half a step past the ends.
fn edges(samples: &[f64]) -> Vec<f64> {
    let n = samples.len();
    if n == 1 {
        return vec![samples[0] - 0.5, samples[0] + 0.5];
    }
    let mut out = Vec::with_capacity(n + 1);
    out.push(samples[0] - (samples[1] - samples[0]) / 2.0);
    out.extend(samples.windows(2).map(|w| (w[0] + w[1]) / 2.0));
    out.push(samples[n - 1] + (samples[n - 1] - samples[n - 2]) / 2.0);
    out
}

fn surface(
    area: &Area<'_>,
    title: &str,
    (x_label, y_label, z_label): (&str, &str, &str),
    xs: &[f64],
    ys: &[f64],
    z: &[Vec<f64>],
) -> DrawResult<()> {
    let (main, bar) = area.split_horizontally(area.dim_in_pixel().0 - 112);
    let usable = !xs.is_empty()
        && !ys.is_empty()
        && xs.iter().chain(ys).all(|v| v.is_finite())
        && z.len() == ys.len()
        && z.iter().all(|row| row.len() == xs.len());
    if !usable {
        main.draw(&Text::new(
            format!("{title}: surface data malformed"),
            (20, 40),
            (FONT, 16).into_font().color(&RED),
        ))
        .map_err(e)?;
        return Ok(());
    }
    let (xe, ye) = (edges(xs), edges(ys));
    let (lo, hi) = span(z.iter().flatten().copied());
    let (xr, yr) = (span(xe.iter().copied()), span(ye.iter().copied()));
    let mut chart = ChartBuilder::on(&main)
        .caption(title, (FONT, 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(72)
        .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
        .map_err(e)?;
    let x_fmt = |v: &f64| fmt_tick(*v, &(xr.0..xr.1));
    let y_fmt = |v: &f64| fmt_tick(*v, &(yr.0..yr.1));
    axes(
        &mut chart,
        Axes {
            desc: (x_label, y_label),
            fmt: (&x_fmt, &y_fmt),
            grid: false,
            labels: None,
        },
    )?;
    for (iy, row) in z.iter().enumerate() {
        chart
            .draw_series(row.iter().enumerate().map(|(ix, &v)| {
                Rectangle::new(
                    [(xe[ix], ye[iy]), (xe[ix + 1], ye[iy + 1])],
                    heat(v, lo, hi).filled(),
                )
            }))
            .map_err(e)?;
    }
    // Contours at eight evenly spaced levels, by marching squares over the sample grid.
    for k in 1..8 {
        let level = lo + (hi - lo) * f64::from(k) / 8.0;
        let segments = contour(xs, ys, z, level);
        chart
            .draw_series(
                segments
                    .into_iter()
                    .map(|(a, b)| PathElement::new(vec![a, b], WHITE.mix(0.8).stroke_width(1))),
            )
            .map_err(e)?;
    }
    colour_bar(&bar, lo, hi, z_label, &|v| heat(v, lo, hi))
}

/// Marching squares: the segments where `z` crosses `level`, in data coordinates (linear
/// interpolation along cell edges; saddle cells take the two pairings in order).
fn contour(xs: &[f64], ys: &[f64], z: &[Vec<f64>], level: f64) -> Vec<((f64, f64), (f64, f64))> {
    let mut out = Vec::new();
    for iy in 0..ys.len().saturating_sub(1) {
        for ix in 0..xs.len().saturating_sub(1) {
            // Corners counter-clockwise from bottom-left.
            let c = [
                (xs[ix], ys[iy], z[iy][ix]),
                (xs[ix + 1], ys[iy], z[iy][ix + 1]),
                (xs[ix + 1], ys[iy + 1], z[iy + 1][ix + 1]),
                (xs[ix], ys[iy + 1], z[iy + 1][ix]),
            ];
            if c.iter().any(|p| !p.2.is_finite()) {
                continue;
            }
            let crossings: Vec<(f64, f64)> = (0..4)
                .filter_map(|k| {
                    let (a, b) = (c[k], c[(k + 1) % 4]);
                    if (a.2 < level) == (b.2 < level) {
                        return None;
                    }
                    let t = (level - a.2) / (b.2 - a.2);
                    Some((a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)))
                })
                .collect();
            for pair in crossings.chunks_exact(2) {
                out.push((pair[0], pair[1]));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contour_of_a_ramp_is_a_straight_line_at_the_level() {
        // z = x on a 3 × 3 grid: the 0.5 contour is x = 0.5 from y = 0 to y = 2.
        let (xs, ys) = ([0.0, 1.0, 2.0], [0.0, 1.0, 2.0]);
        let z = vec![xs.to_vec(); 3];
        let segs = contour(&xs, &ys, &z, 0.5);
        assert_eq!(segs.len(), 2);
        for (a, b) in segs {
            assert!((a.0 - 0.5).abs() < 1e-12 && (b.0 - 0.5).abs() < 1e-12);
        }
    }

    #[test]
    fn only_trade_plots_get_a_log_cost_axis() {
        let line = Line {
            label: "l".into(),
            points: vec![(0.03, 1.0), (30.0, 2.0)],
        };
        let plot = Plot::Lines {
            title: "t".into(),
            x_label: "time, s".into(),
            y_label: "y".into(),
            lines: vec![line.clone()],
        };
        assert!(!draw(&plot, None).unwrap().svg.contains("log scale"));
        assert!(draw(&plot, Some(&line)).unwrap().svg.contains("log scale"));
    }

    #[test]
    fn every_kind_draws_one_svg_even_from_degenerate_data() {
        let plots = [
            Plot::Lines {
                title: "empty".into(),
                x_label: "x".into(),
                y_label: "y".into(),
                lines: vec![Line {
                    label: "nan".into(),
                    points: vec![(f64::NAN, 1.0)],
                }],
            },
            Plot::Confusion {
                title: "ragged".into(),
                labels: vec!["a".into(), "b".into()],
                counts: vec![vec![3]],
            },
            Plot::Grid {
                title: "short".into(),
                rows: 2,
                cols: 2,
                values: vec![1.0, f64::INFINITY],
                unit: "hPa".into(),
            },
            Plot::Surface {
                title: "bad".into(),
                x_label: "x".into(),
                y_label: "y".into(),
                z_label: "z".into(),
                xs: vec![0.0, 1.0],
                ys: vec![0.0],
                z: vec![vec![1.0]],
            },
        ];
        for plot in &plots {
            let drawn = draw(plot, None).unwrap();
            assert_eq!(drawn.svg.matches("<svg").count(), 1, "{}", title(plot));
            assert!(drawn.svg.trim_end().ends_with("</svg>"));
        }
    }
}
