//! A hand-written log-log SVG plot of relMSE against rendering time: per configuration, the
//! median over seeds at each budget joined by a line, with a marker and an error bar from the
//! smallest to the largest relMSE over the seeds; its fitted convergence slope in the legend.
//! Lines differ in colour, marker shape and dash pattern, so that coinciding ones can still be
//! told apart. Hand-written rather than drawn by a plotting crate: two hundred lines of SVG need
//! no font files (plotters needs one shipped and registered even for SVG) and no dependency.

use super::report::SceneReport;
use super::summary::Spread;
use std::fmt::Write as _;

/// Plot width in SVG user units (pixels).
const WIDTH: f64 = 760.0;
/// Plot height in SVG user units (pixels).
const HEIGHT: f64 = 420.0;
/// Left margin: the y axis' tick labels and title (pixels).
const LEFT: f64 = 70.0;
/// Top margin: the plot's title (pixels).
const TOP: f64 = 30.0;
/// Bottom margin: the x axis' tick labels and title (pixels).
const BOTTOM: f64 = 50.0;
/// Width of the legend right of the plot area (pixels).
const LEGEND: f64 = 210.0;
/// Share of the data's log range added on each side, so that markers are not cut by the frame.
const PAD: f64 = 0.06;

/// Line colours, cycled per configuration (Kelly's and Tol's distinct colours).
const COLOURS: &[&str] = &[
    "#000000", "#e6194b", "#3cb44b", "#4363d8", "#f58231", "#911eb4", "#42b4d4", "#f032e6",
    "#9a6324", "#808000", "#000075", "#469990",
];

/// Marker shapes, cycled per configuration (seven: coprime with the twelve colours and the
/// three dash patterns, so that no two of the first 84 configurations look alike).
const MARKERS: &[Marker] = &[
    Marker::Circle,
    Marker::Square,
    Marker::TriangleUp,
    Marker::Diamond,
    Marker::TriangleDown,
    Marker::Cross,
    Marker::Plus,
];

/// Dash patterns (SVG `stroke-dasharray`; empty for solid), cycled per configuration.
const DASHES: &[&str] = &["", "7,3", "2,2"];

/// A marker shape.
#[derive(Clone, Copy, Debug)]
enum Marker {
    Circle,
    Square,
    TriangleUp,
    Diamond,
    TriangleDown,
    Cross,
    Plus,
}

impl Marker {
    /// The SVG element of the marker centred at `(x, y)` in `colour`.
    fn svg(self, x: f64, y: f64, colour: &str) -> String {
        let r = 4.0;
        let filled = format!("fill=\"{colour}\" stroke=\"{colour}\"");
        let open = format!("fill=\"none\" stroke=\"{colour}\" stroke-width=\"1.8\"");
        let polygon = |points: &[(f64, f64)]| {
            let points: Vec<String> = points
                .iter()
                .map(|(dx, dy)| format!("{:.1},{:.1}", x + dx, y + dy))
                .collect();
            format!("<polygon points=\"{}\" {filled}/>", points.join(" "))
        };
        match self {
            Marker::Circle => format!("<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"{r}\" {filled}/>"),
            Marker::Square => format!(
                "<rect x=\"{:.1}\" y=\"{:.1}\" width=\"{}\" height=\"{}\" {filled}/>",
                x - r,
                y - r,
                2.0 * r,
                2.0 * r
            ),
            Marker::TriangleUp => polygon(&[(0.0, -r - 1.0), (r + 1.0, r), (-r - 1.0, r)]),
            Marker::TriangleDown => polygon(&[(0.0, r + 1.0), (r + 1.0, -r), (-r - 1.0, -r)]),
            Marker::Diamond => polygon(&[(0.0, -r - 1.0), (r, 0.0), (0.0, r + 1.0), (-r, 0.0)]),
            Marker::Cross => format!(
                "<path d=\"M{:.1} {:.1}L{:.1} {:.1}M{:.1} {:.1}L{:.1} {:.1}\" {open}/>",
                x - r,
                y - r,
                x + r,
                y + r,
                x - r,
                y + r,
                x + r,
                y - r
            ),
            Marker::Plus => format!(
                "<path d=\"M{:.1} {y:.1}L{:.1} {y:.1}M{x:.1} {:.1}L{x:.1} {:.1}\" {open}/>",
                x - r - 1.0,
                x + r + 1.0,
                y - r - 1.0,
                y + r + 1.0
            ),
        }
    }
}

/// The look of configuration `index`: colour, marker and dash pattern.
fn style(index: usize) -> (&'static str, Marker, &'static str) {
    (
        COLOURS[index % COLOURS.len()],
        MARKERS[index % MARKERS.len()],
        DASHES[index % DASHES.len()],
    )
}

/// One plotted point: a configuration at one budget, over its seeds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    /// Median rendering time, seconds.
    pub seconds: f64,
    /// relMSE over the seeds.
    pub relmse: Spread,
}

/// The points of `configuration`, one per budget in increasing order; renders with a
/// non-positive relMSE (exact) or time are left out.
pub fn points(report: &SceneReport, configuration: &str) -> Vec<Point> {
    let mut budgets: Vec<f64> = report
        .measurements
        .iter()
        .filter(|m| m.configuration == configuration)
        .map(|m| m.budget)
        .collect();
    budgets.sort_by(f64::total_cmp);
    budgets.dedup();
    budgets
        .into_iter()
        .filter_map(|budget| {
            let renders: Vec<_> = report
                .measurements
                .iter()
                .filter(|m| {
                    m.configuration == configuration
                        && m.budget == budget
                        && m.relmse > 0.0
                        && m.seconds > 0.0
                })
                .collect();
            let seconds = Spread::of(&renders.iter().map(|m| m.seconds).collect::<Vec<_>>())?;
            let relmse = Spread::of(&renders.iter().map(|m| m.relmse).collect::<Vec<_>>())?;
            Some(Point {
                seconds: seconds.median,
                relmse,
            })
        })
        .collect()
}

/// The log10 range of `values` padded by [`PAD`] on each side (a decade around a single value).
fn log_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .map(f64::log10)
        .fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if lo > hi {
        return (0.0, 1.0);
    }
    if hi - lo < 1e-9 {
        return (lo - 0.5, hi + 0.5);
    }
    let pad = PAD * (hi - lo);
    (lo - pad, hi + pad)
}

/// Tick values within the log10 range `(lo, hi)`, each with its label: powers of ten over more
/// than four decades; else 1, 2 and 5 times powers of ten, or every whole multiple when that
/// gives fewer than three.
pub fn ticks(lo: f64, hi: f64, unit: &str) -> Vec<(f64, String)> {
    let decades = (lo.floor() as i32)..=(hi.ceil() as i32);
    let within = |multiples: &[u32]| -> Vec<(f64, String)> {
        decades
            .clone()
            .flat_map(|d| multiples.iter().map(move |&m| (m, d)))
            .map(|(m, d)| (f64::from(m) * 10f64.powi(d), m, d))
            .filter(|(v, _, _)| (lo..=hi).contains(&v.log10()))
            .map(|(v, m, d)| (v, label(m, d, unit)))
            .collect()
    };
    if hi - lo > 4.0 {
        return within(&[1]);
    }
    let sparse = within(&[1, 2, 5]);
    if sparse.len() >= 3 {
        sparse
    } else {
        within(&[1, 2, 3, 4, 5, 6, 7, 8, 9])
    }
}

/// Whether a tick label at `position` (pixels along its axis) keeps `gap` pixels from the last
/// one drawn, `last`; updates `last` when it does. Grid lines are drawn for every tick.
fn label_fits(position: f64, last: &mut Option<f64>, gap: f64) -> bool {
    let fits = last.is_none_or(|l| (position - l).abs() >= gap);
    if fits {
        *last = Some(position);
    }
    fits
}

/// `m × 10^d` as a plain decimal with `unit` (`0.25 s`, `2 s`) when `unit` is given, else in
/// scientific notation (`2e-3`).
fn label(m: u32, d: i32, unit: &str) -> String {
    if unit.is_empty() {
        return format!("{m}e{d}");
    }
    let digits = m.to_string();
    let text = if d >= 0 {
        format!("{digits}{}", "0".repeat(d as usize))
    } else {
        format!("0.{}{digits}", "0".repeat((-d - 1) as usize))
    };
    format!("{text} {unit}")
}

/// The plot of `report`'s measurements: log seconds across, log relMSE up, each axis spanning
/// its data.
pub fn log_log_svg(report: &SceneReport) -> String {
    let series: Vec<(usize, &str, Vec<Point>)> = report
        .rungs
        .iter()
        .enumerate()
        .map(|(i, r)| (i, r.name.as_str(), points(report, &r.name)))
        .collect();
    let all = || series.iter().flat_map(|(_, _, p)| p.iter());
    let (x0, x1) = log_range(all().map(|p| p.seconds));
    let (y0, y1) = log_range(all().flat_map(|p| [p.relmse.min, p.relmse.max]));
    let right = WIDTH - LEGEND;
    let bottom = HEIGHT - BOTTOM;
    let sx = |x: f64| LEFT + (x.log10() - x0) / (x1 - x0) * (right - LEFT);
    let sy = |y: f64| bottom - (y.log10() - y0) / (y1 - y0) * (bottom - TOP);
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{WIDTH}\" height=\"{HEIGHT}\" \
         viewBox=\"0 0 {WIDTH} {HEIGHT}\" font-family=\"sans-serif\" font-size=\"11\">\n\
         <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n\
         <text x=\"{LEFT}\" y=\"18\" font-size=\"13\">{}: relMSE against rendering time \
         (median over seeds, bars: min&#8211;max)</text>\n\
         <rect class=\"frame\" x=\"{LEFT}\" y=\"{TOP}\" width=\"{:.1}\" height=\"{:.1}\" fill=\"none\" \
         stroke=\"#888\"/>\n",
        report.scene,
        right - LEFT,
        bottom - TOP
    );
    let mut last = None;
    for (value, text) in ticks(x0, x1, "s") {
        let x = sx(value);
        let _ = write!(
            svg,
            "<line x1=\"{x:.1}\" y1=\"{TOP}\" x2=\"{x:.1}\" y2=\"{bottom}\" stroke=\"#e4e4e4\"/>"
        );
        if label_fits(x, &mut last, 44.0) {
            let _ = write!(
                svg,
                "<text x=\"{x:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{text}</text>",
                bottom + 14.0
            );
        }
        svg.push('\n');
    }
    let mut last = None;
    for (value, text) in ticks(y0, y1, "") {
        let y = sy(value);
        let _ = write!(
            svg,
            "<line x1=\"{LEFT}\" y1=\"{y:.1}\" x2=\"{right}\" y2=\"{y:.1}\" stroke=\"#e4e4e4\"/>"
        );
        if label_fits(y, &mut last, 14.0) {
            let _ = write!(
                svg,
                "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\">{text}</text>",
                LEFT - 4.0,
                y + 4.0
            );
        }
        svg.push('\n');
    }
    let _ = writeln!(
        svg,
        "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\" font-size=\"12\">rendering time \
         per image, seconds (log scale)</text>\n<text transform=\"translate(16 {:.1}) \
         rotate(-90)\" text-anchor=\"middle\" font-size=\"12\">relMSE (log scale)</text>",
        0.5 * (LEFT + right),
        HEIGHT - 10.0,
        0.5 * (TOP + bottom)
    );
    let legend_x = right + 14.0;
    for (index, name, points) in &series {
        let (colour, marker, dash) = style(*index);
        let dash_attribute = if dash.is_empty() {
            String::new()
        } else {
            format!(" stroke-dasharray=\"{dash}\"")
        };
        let line: Vec<String> = points
            .iter()
            .map(|p| format!("{:.1},{:.1}", sx(p.seconds), sy(p.relmse.median)))
            .collect();
        let _ = writeln!(
            svg,
            "<polyline fill=\"none\" stroke=\"{colour}\" stroke-width=\"1.5\"{dash_attribute} \
             points=\"{}\"/>",
            line.join(" ")
        );
        for p in points {
            let (x, lo, hi) = (sx(p.seconds), sy(p.relmse.min), sy(p.relmse.max));
            let _ = writeln!(
                svg,
                "<path d=\"M{x:.1} {lo:.1}L{x:.1} {hi:.1}M{:.1} {lo:.1}L{:.1} {lo:.1}\
                 M{:.1} {hi:.1}L{:.1} {hi:.1}\" stroke=\"{colour}\" fill=\"none\"/>{}",
                x - 3.0,
                x + 3.0,
                x - 3.0,
                x + 3.0,
                marker.svg(x, sy(p.relmse.median), colour)
            );
        }
        let legend_y = TOP + 8.0 + 16.0 * *index as f64;
        let slope = report
            .slope(name)
            .map_or(String::new(), |s| format!(" (slope {s:+.2})"));
        let exact = if points.is_empty() {
            " (exact: not plotted)"
        } else {
            ""
        };
        let _ = writeln!(
            svg,
            "<line x1=\"{legend_x:.1}\" y1=\"{legend_y:.1}\" x2=\"{:.1}\" y2=\"{legend_y:.1}\" \
             stroke=\"{colour}\" stroke-width=\"1.5\"{dash_attribute}/>{}\
             <text x=\"{:.1}\" y=\"{:.1}\" fill=\"{colour}\">{name}{slope}{exact}</text>",
            legend_x + 28.0,
            marker.svg(legend_x + 14.0, legend_y, colour),
            legend_x + 34.0,
            legend_y + 4.0
        );
    }
    svg.push_str("</svg>\n");
    svg
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render_all::report::{Measurement, Rung};

    fn measurement(name: &str, budget: f64, seed: u32, seconds: f64, relmse: f64) -> Measurement {
        Measurement {
            configuration: name.to_string(),
            budget,
            seed,
            spp: 1,
            seconds,
            rmse: 0.0,
            relmse,
            non_finite: 0,
        }
    }

    fn report() -> SceneReport {
        SceneReport {
            scene: "s".to_string(),
            rungs: ["mis", "bsdf"]
                .iter()
                .map(|n| Rung {
                    name: n.to_string(),
                    builds_on: None,
                    techniques: Vec::new(),
                })
                .collect(),
            auto_choices: Vec::new(),
            measurements: vec![
                measurement("mis", 0.4, 4, 0.41, 0.02),
                measurement("mis", 0.4, 5, 0.43, 0.01),
                measurement("mis", 0.4, 6, 0.39, 0.04),
                measurement("mis", 0.2, 1, 0.21, 0.05),
                measurement("mis", 0.2, 2, 0.22, 0.06),
                measurement("mis", 0.2, 3, 0.20, 0.07),
                // Exact renders are not plotted.
                measurement("bsdf", 0.2, 1, 0.2, 0.0),
            ],
            exposure: 1.0,
        }
    }

    #[test]
    fn a_point_is_the_median_time_and_relmse_range_per_budget() {
        let r = report();
        let p = points(&r, "mis");
        assert_eq!(p.len(), 2);
        assert_eq!(p[0].seconds, 0.21);
        assert_eq!(
            (p[0].relmse.median, p[0].relmse.min, p[0].relmse.max),
            (0.06, 0.05, 0.07)
        );
        assert_eq!(p[1].seconds, 0.41);
        assert_eq!(
            (p[1].relmse.median, p[1].relmse.min, p[1].relmse.max),
            (0.02, 0.01, 0.04)
        );
        assert!(points(&r, "bsdf").is_empty());
    }

    #[test]
    fn the_axes_span_the_data_not_whole_decades() {
        // Data from 0.2 to 2.4 s: ticks within, none at 0.1 or 10 s.
        let (lo, hi) = log_range([0.2, 2.4].into_iter());
        assert!(lo < 0.2f64.log10() && lo > 0.15f64.log10(), "{lo}");
        assert!(hi > 2.4f64.log10() && hi < 3.0f64.log10(), "{hi}");
        let labels: Vec<String> = ticks(lo, hi, "s").into_iter().map(|t| t.1).collect();
        assert_eq!(labels, ["0.2 s", "0.5 s", "1 s", "2 s"]);
        // A narrow range gets every whole multiple.
        let (lo, hi) = log_range([0.21, 0.43].into_iter());
        let labels: Vec<String> = ticks(lo, hi, "s").into_iter().map(|t| t.1).collect();
        assert_eq!(labels, ["0.3 s", "0.4 s"]);
        // Over more than four decades, powers of ten only.
        let labels: Vec<String> = ticks(-10.3, -1.7, "").into_iter().map(|t| t.1).collect();
        assert_eq!(labels.len(), 9);
        assert_eq!((labels[0].as_str(), labels[8].as_str()), ("1e-10", "1e-2"));
        assert_eq!(label(5, -2, ""), "5e-2");
        assert_eq!(label(2, 1, "s"), "20 s");
    }

    #[test]
    fn a_tick_label_too_close_to_the_last_is_left_out() {
        let mut last = None;
        let drawn: Vec<f64> = [0.0, 30.0, 50.0, 80.0, 100.0]
            .into_iter()
            .filter(|&x| label_fits(x, &mut last, 44.0))
            .collect();
        assert_eq!(drawn, [0.0, 50.0, 100.0]);
    }

    #[test]
    fn no_two_of_the_first_configurations_look_alike() {
        let looks: Vec<String> = (0..84)
            .map(|i| {
                let (colour, marker, dash) = style(i);
                format!("{colour} {marker:?} {dash}")
            })
            .collect();
        for (i, a) in looks.iter().enumerate() {
            assert!(!looks[..i].contains(a), "configuration {i} repeats {a}");
        }
    }

    #[test]
    fn the_plot_has_axis_titles_markers_error_bars_and_a_legend() {
        let svg = log_log_svg(&report());
        assert!(svg.contains("rendering time per image, seconds"));
        assert!(svg.contains("relMSE (log scale)"));
        // mis: a circle per budget and one in the legend; bsdf: a square in the legend only.
        assert_eq!(svg.matches("<circle").count(), 3);
        assert_eq!(svg.matches("<rect x=").count(), 1);
        assert!(svg.contains("stroke-dasharray=\"7,3\""));
        assert!(svg.contains("bsdf (exact: not plotted)"));
        assert!(svg.contains("mis (slope"));
    }
}
