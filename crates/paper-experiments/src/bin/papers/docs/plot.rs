//! What every plot of the docs shares: legend marks and boxes, and plotters' errors as anyhow's.

use anyhow::Result;
use plotters::prelude::*;

/// A series' legend mark: a short line in its colour.
pub(crate) fn legend_mark(color: RGBColor) -> impl Fn((i32, i32)) -> PathElement<(i32, i32)> {
    move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], color)
}

/// Draws the chart's series legend in a translucent white box at `position`.
pub(crate) fn draw_legend<'a, DB: DrawingBackend + 'a, X: Ranged, Y: Ranged>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    position: SeriesLabelPosition,
) -> Result<()> {
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .position(position)
        .draw()
        .map_err(plot_err)?;
    Ok(())
}

/// A plotters error as an anyhow one, prefixed `plot:`.
pub(crate) fn plot_err<E: std::fmt::Display>(e: E) -> anyhow::Error {
    anyhow::anyhow!("plot: {e}")
}
