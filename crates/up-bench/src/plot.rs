//! The report's plot: ms per step against balloons, both axes logarithmic,
//! one line per engine and runtime. SVG only (text is left to the viewer's fonts).

use std::path::Path;

use anyhow::{anyhow, Result};
use plotters::prelude::*;

/// One line of the plot: its label and (balloons, ms per step) points.
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

const COLORS: [RGBColor; 4] = [
    RGBColor(214, 39, 40),
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
];

/// Widens `[lo, hi]` to whole decades.
fn decades(lo: f64, hi: f64) -> (f64, f64) {
    (
        10f64.powf(lo.log10().floor()),
        10f64.powf(hi.log10().ceil().max(lo.log10().floor() + 1.0)),
    )
}

/// Writes the plot of `series` to `path`.
pub fn plot_svg(path: &Path, series: &[Series]) -> Result<()> {
    let points = series.iter().flat_map(|s| s.points.iter().copied());
    let (mut x_lo, mut x_hi, mut y_lo, mut y_hi) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for (x, y) in points.filter(|(x, y)| *x > 0.0 && *y > 0.0) {
        x_lo = x_lo.min(x);
        x_hi = x_hi.max(x);
        y_lo = y_lo.min(y);
        y_hi = y_hi.max(y);
    }
    if x_lo > x_hi {
        return Err(anyhow!("nothing to plot"));
    }
    let (x_lo, x_hi) = decades(x_lo, x_hi);
    let (y_lo, y_hi) = decades(y_lo, y_hi);
    let draw = || -> Result<(), Box<dyn std::error::Error>> {
        let root = SVGBackend::new(path, (720, 480)).into_drawing_area();
        root.fill(&WHITE)?;
        let mut chart = ChartBuilder::on(&root)
            .caption("ms per step against balloons (log-log)", ("sans-serif", 20))
            .margin(16)
            .x_label_area_size(44)
            .y_label_area_size(60)
            .build_cartesian_2d((x_lo..x_hi).log_scale(), (y_lo..y_hi).log_scale())?;
        chart
            .configure_mesh()
            .x_desc("balloons")
            .y_desc("ms per step (median)")
            .x_label_formatter(&|x| format!("{x:.0}"))
            .y_label_formatter(&|y| format!("{y}"))
            .draw()?;
        for (i, s) in series.iter().enumerate() {
            let color = COLORS[i % COLORS.len()];
            chart
                .draw_series(LineSeries::new(
                    s.points.iter().copied(),
                    color.stroke_width(2),
                ))?
                .label(s.label.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
            chart.draw_series(s.points.iter().map(|&p| Circle::new(p, 4, color.filled())))?;
        }
        // 60 Hz budget.
        if (y_lo..y_hi).contains(&16.7) {
            chart
                .draw_series(LineSeries::new(
                    [(x_lo, 16.7), (x_hi, 16.7)],
                    BLACK.mix(0.4),
                ))?
                .label("16.7 ms (60 Hz)")
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.mix(0.4)));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()?;
        root.present()?;
        Ok(())
    };
    draw().map_err(|e| anyhow!("{}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_an_svg_with_both_lines() {
        let path = std::env::temp_dir().join(format!("up-bench-plot-{}.svg", std::process::id()));
        plot_svg(
            &path,
            &[
                Series {
                    label: "UP native".into(),
                    points: vec![(1000.0, 0.8), (10_000.0, 9.0), (100_000.0, 95.0)],
                },
                Series {
                    label: "Rapier native".into(),
                    points: vec![(1000.0, 3.0), (10_000.0, 35.0)],
                },
            ],
        )
        .unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        assert!(svg.starts_with("<svg"), "{}", &svg[..40.min(svg.len())]);
        assert!(svg.contains("UP native") && svg.contains("Rapier native"));
        assert!(svg.matches("<polyline").count() >= 2);
    }
}
