//! A hand-written log-log SVG plot of relMSE against rendering time, one line per configuration,
//! its fitted convergence slope in the legend. Hand-written rather than drawn by a plotting
//! crate: a hundred lines of SVG need no font files (plotters needs one shipped and registered
//! even for SVG) and no dependency.

use super::report::SceneReport;
use std::fmt::Write as _;

/// Plot width in SVG user units (pixels).
const WIDTH: f64 = 520.0;
/// Plot height in SVG user units (pixels).
const HEIGHT: f64 = 320.0;
/// Margin around the plot area, room for the axes' labels (pixels).
const MARGIN: f64 = 48.0;
/// Width of the legend right of the plot area (pixels).
const LEGEND: f64 = 150.0;

/// Line colours, cycled per configuration.
const COLOURS: &[&str] = &[
    "#000000", "#e6194b", "#3cb44b", "#4363d8", "#f58231", "#911eb4", "#42d4f4", "#f032e6",
    "#9a6324", "#808000", "#000075", "#469990",
];

/// The plot of `report`'s measurements: log10 seconds across, log10 relMSE up, axis ranges
/// snapped to whole decades. Measurements with a non-positive relMSE or time are left out.
pub fn log_log_svg(report: &SceneReport) -> String {
    let points: Vec<(f64, f64)> = report
        .measurements
        .iter()
        .filter(|m| m.relmse > 0.0 && m.seconds > 0.0)
        .map(|m| (m.seconds.log10(), m.relmse.log10()))
        .collect();
    let range = |values: &mut dyn Iterator<Item = f64>| {
        let (lo, hi) = values.fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
        if lo > hi {
            (0.0, 1.0)
        } else {
            (lo.floor(), hi.ceil().max(lo.floor() + 1.0))
        }
    };
    let (x0, x1) = range(&mut points.iter().map(|p| p.0));
    let (y0, y1) = range(&mut points.iter().map(|p| p.1));
    let plot_w = WIDTH - 2.0 * MARGIN - LEGEND;
    let plot_h = HEIGHT - 2.0 * MARGIN;
    let sx = |x: f64| MARGIN + (x - x0) / (x1 - x0) * plot_w;
    let sy = |y: f64| HEIGHT - MARGIN - (y - y0) / (y1 - y0) * plot_h;
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{WIDTH}\" height=\"{HEIGHT}\" \
         font-family=\"sans-serif\" font-size=\"10\">\n<rect width=\"100%\" height=\"100%\" \
         fill=\"white\"/>\n<text x=\"{MARGIN}\" y=\"16\" font-size=\"12\">{}: relMSE against \
         seconds</text>\n",
        report.scene
    );
    for decade in (x0 as i32)..=(x1 as i32) {
        let x = sx(f64::from(decade));
        let _ = writeln!(
            svg,
            "<line x1=\"{x:.1}\" y1=\"{:.1}\" x2=\"{x:.1}\" y2=\"{:.1}\" stroke=\"#ddd\"/>\
             <text x=\"{x:.1}\" y=\"{:.1}\" text-anchor=\"middle\">1e{decade} s</text>",
            sy(y0),
            sy(y1),
            sy(y0) + 14.0
        );
    }
    for decade in (y0 as i32)..=(y1 as i32) {
        let y = sy(f64::from(decade));
        let _ = writeln!(
            svg,
            "<line x1=\"{:.1}\" y1=\"{y:.1}\" x2=\"{:.1}\" y2=\"{y:.1}\" stroke=\"#ddd\"/>\
             <text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\">1e{decade}</text>",
            sx(x0),
            sx(x1),
            sx(x0) - 4.0,
            y + 3.0
        );
    }
    for (index, name) in report.configurations.iter().enumerate() {
        let colour = COLOURS[index % COLOURS.len()];
        let line: Vec<String> = report
            .measurements
            .iter()
            .filter(|m| &m.configuration == name && m.relmse > 0.0 && m.seconds > 0.0)
            .map(|m| format!("{:.1},{:.1}", sx(m.seconds.log10()), sy(m.relmse.log10())))
            .collect();
        let legend_y = MARGIN + 14.0 * index as f64;
        let slope = report
            .slope(name)
            .map_or(String::new(), |s| format!(" ({s:+.2})"));
        let _ = writeln!(
            svg,
            "<polyline fill=\"none\" stroke=\"{colour}\" stroke-width=\"1.5\" points=\"{}\"/>\
             <text x=\"{:.1}\" y=\"{legend_y:.1}\" fill=\"{colour}\">{name}{slope}</text>",
            line.join(" "),
            WIDTH - MARGIN - LEGEND + 12.0
        );
    }
    svg.push_str("</svg>\n");
    svg
}
