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

/// Ten colours that stay apart from each other on white (Palette99's third,
/// a light yellow, does not).
const COLOURS: [(u8, u8, u8); 10] = [
    (31, 119, 180),
    (255, 127, 14),
    (44, 160, 44),
    (214, 39, 40),
    (148, 103, 189),
    (140, 86, 75),
    (227, 119, 194),
    (127, 127, 127),
    (188, 189, 34),
    (23, 190, 207),
];

fn colour(i: usize) -> RGBAColor {
    let (r, g, b) = COLOURS[i % COLOURS.len()];
    RGBColor(r, g, b).to_rgba()
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
    let labelled: Vec<(&Series, &[String])> = series.iter().map(|s| (s, &[][..])).collect();
    draw(path, title, x_label, y_label, &labelled, true)
}

/// Draws each series as points only (no line between them), each point
/// with the label of the same index (e.g. the function it measures), on
/// log-log axes into the SVG file `path`.
pub fn scatter_loglog(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[(Series, Vec<String>)],
) -> Result<(), String> {
    let labelled: Vec<(&Series, &[String])> = series.iter().map(|(s, l)| (s, &l[..])).collect();
    draw(path, title, x_label, y_label, &labelled, false)
}

fn draw(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[(&Series, &[String])],
    lines: bool,
) -> Result<(), String> {
    let all = || series.iter().flat_map(|(s, _)| s.points.iter().chain(s.marked.iter())).filter(|p| usable(p));
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
    for (i, (s, labels)) in series.iter().enumerate() {
        let color = colour(i);
        let kept: Vec<(usize, (f64, f64))> = s.points.iter().copied().enumerate().filter(|(_, p)| usable(p)).collect();
        let pts: Vec<(f64, f64)> = kept.iter().map(|&(_, p)| p).collect();
        let legend = move |(x, y): (i32, i32)| PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2));
        if lines {
            chart
                .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
                .map_err(|e| err(&e))?
                .label(s.name.clone())
                .legend(legend);
            chart.draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled()))).map_err(|e| err(&e))?;
        } else {
            chart
                .draw_series(pts.iter().map(|&p| Circle::new(p, 4, color.filled())))
                .map_err(|e| err(&e))?
                .label(s.name.clone())
                .legend(legend);
        }
        let texts = kept.iter().filter_map(|&(j, p)| {
            labels.get(j).map(|l| Text::new(l.clone(), p, ("sans-serif", 12).into_font().color(&color)))
        });
        chart.draw_series(texts).map_err(|e| err(&e))?;
        let marked: Vec<(f64, f64)> = s.marked.iter().copied().filter(usable).collect();
        chart.draw_series(marked.iter().map(|&p| Cross::new(p, 6, color.stroke_width(2)))).map_err(|e| err(&e))?;
    }
    chart
        .configure_series_labels()
        // Errors cluster at f32's and f64's precision: between them is room.
        .position(if lines { SeriesLabelPosition::UpperRight } else { SeriesLabelPosition::MiddleRight })
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

    #[test]
    fn scatter_writes_the_point_labels() {
        let dir = std::env::temp_dir().join(format!("dynagen-scatter-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("s.svg");
        let s = Series::new("generated f64", vec![(1e-7, 1e-15), (-1.0, 1.0), (2e-7, 3e-16)]);
        let labels = vec!["tau".to_string(), "skipped".to_string(), "mass".to_string()];
        scatter_loglog(&path, "title", "time [s]", "error", &[(s, labels)]).unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        assert!(svg.contains("generated f64") && svg.contains("tau") && svg.contains("mass"));
        assert!(!svg.contains("skipped"), "a point off the log axes has no label");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
