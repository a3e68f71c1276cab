//! Log-log plots as SVG (plotters), shared by every section of the report.

use plotters::prelude::*;
use std::path::Path;

/// One named series of (x, y) points, drawn as a line with markers.
pub struct Series {
    /// The legend entry.
    pub name: String,
    /// The points; non-positive or non-finite values are left out (log axes).
    pub points: Vec<(f64, f64)>,
    /// Points to mark specially (for instance where an integrator went unstable), drawn as crosses.
    pub marked: Vec<(f64, f64)>,
}

impl Series {
    /// A series without marked points.
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series { name: name.into(), points, marked: Vec::new() }
    }
}

fn usable(p: &(f64, f64)) -> bool {
    p.0.is_finite() && p.1.is_finite() && p.0 > 0.0 && p.1 > 0.0
}

/// The decade range that holds every usable value of `values`.
fn decades(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite() && *v > 0.0) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return (1e-1, 1e1);
    }
    (10f64.powf(lo.log10().floor()), 10f64.powf(hi.log10().ceil().max(lo.log10().floor() + 1.0)))
}

/// Draws `series` on log-log axes into the SVG file `path`.
pub fn loglog(path: &Path, title: &str, x_label: &str, y_label: &str, series: &[Series]) -> Result<(), String> {
    let all = || series.iter().flat_map(|s| s.points.iter().chain(s.marked.iter())).filter(|p| usable(p));
    let (x0, x1) = decades(all().map(|p| p.0));
    let (y0, y1) = decades(all().map(|p| p.1));
    let root = SVGBackend::new(path, (900, 600)).into_drawing_area();
    let err = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .x_label_formatter(&|v| format!("{v:.0e}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .draw()
        .map_err(|e| err(&e))?;
    for (i, s) in series.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        let pts: Vec<(f64, f64)> = s.points.iter().copied().filter(usable).collect();
        chart
            .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
            .map_err(|e| err(&e))?
            .label(s.name.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2)));
        chart.draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled()))).map_err(|e| err(&e))?;
        let marked: Vec<(f64, f64)> = s.marked.iter().copied().filter(usable).collect();
        chart.draw_series(marked.iter().map(|&p| Cross::new(p, 6, color.stroke_width(2)))).map_err(|e| err(&e))?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(|e| err(&e))?;
    root.present().map_err(|e| err(&e))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decades_round_out_to_powers_of_ten() {
        assert_eq!(decades([3e-7, 2e-3].into_iter()), (1e-7, 1e-2));
        assert_eq!(decades([f64::NAN, 0.0].into_iter()), (1e-1, 1e1));
    }

    #[test]
    fn writes_an_svg_with_the_legend() {
        let dir = std::env::temp_dir().join(format!("dynagen-plot-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("p.svg");
        let mut s = Series::new("generic f64", vec![(1e-7, 1e-15), (2e-7, 3e-16)]);
        s.marked.push((3e-7, 1.0));
        loglog(&path, "title", "time [s]", "error", &[s]).unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        assert!(svg.contains("<svg") && svg.contains("generic f64"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
