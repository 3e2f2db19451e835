//! The render-all report: `errors.csv`, `index.html` with each configuration's image, and the
//! terminal summary table.

use super::ladder::REFERENCE;
use super::plot::log_log_svg;
use render::atomic_write::write_bytes_atomically;
use std::fmt::Write as _;
use std::path::Path;

/// One render measured against the stored reference.
#[derive(Clone, Debug)]
pub struct Measurement {
    /// Configuration name.
    pub configuration: String,
    /// Time budget asked for, in seconds.
    pub budget: f64,
    /// Samples per pixel rendered.
    pub spp: u32,
    /// Rendering time spent, in seconds.
    pub seconds: f64,
    /// Root-mean-square error against the reference (radiance units).
    pub rmse: f64,
    /// Relative mean squared error against the reference (dimensionless).
    pub relmse: f64,
    /// Samples that were NaN or infinite (left out of the image).
    pub non_finite: u64,
}

impl Measurement {
    /// Efficiency 1 / (relMSE × seconds), per second (infinite for an exact image).
    pub fn efficiency(&self) -> f64 {
        1.0 / (self.relmse * self.seconds)
    }
}

/// Everything measured on one scene.
#[derive(Clone, Debug)]
pub struct SceneReport {
    /// Scene name (file stem).
    pub scene: String,
    /// Configuration names in ladder order.
    pub configurations: Vec<String>,
    /// Techniques `auto` turned on.
    pub auto_techniques: Vec<String>,
    /// Every render, in ladder order then budget order.
    pub measurements: Vec<Measurement>,
}

impl SceneReport {
    /// The render of `configuration` at the largest budget.
    fn final_of(&self, configuration: &str) -> Option<&Measurement> {
        self.measurements
            .iter()
            .filter(|m| m.configuration == configuration)
            .max_by(|a, b| a.budget.total_cmp(&b.budget))
    }

    /// Efficiency of `configuration` at the largest budget over the reference integrator's.
    fn efficiency_ratio(&self, configuration: &str) -> Option<f64> {
        let reference = self.final_of(REFERENCE)?.efficiency();
        Some(self.final_of(configuration)?.efficiency() / reference)
    }

    /// The convergence slope of `configuration`: the least-squares slope of log relMSE against
    /// log seconds over its budgets (−1 for an unbiased estimator whose variance falls as
    /// 1/samples; steeper for stratified sampling of smooth integrands). `None` with fewer than
    /// two usable measurements.
    pub fn slope(&self, configuration: &str) -> Option<f64> {
        let points: Vec<(f64, f64)> = self
            .measurements
            .iter()
            .filter(|m| m.configuration == configuration && m.relmse > 0.0 && m.seconds > 0.0)
            .map(|m| (m.seconds.ln(), m.relmse.ln()))
            .collect();
        fitted_slope(&points)
    }
}

/// Least-squares slope of `points` (x, y); `None` with fewer than two distinct x.
fn fitted_slope(points: &[(f64, f64)]) -> Option<f64> {
    let n = points.len() as f64;
    let mean_x = points.iter().map(|p| p.0).sum::<f64>() / n;
    let mean_y = points.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = points.iter().map(|p| (p.0 - mean_x).powi(2)).sum();
    let sxy: f64 = points.iter().map(|p| (p.0 - mean_x) * (p.1 - mean_y)).sum();
    (points.len() >= 2 && sxx > 0.0).then(|| sxy / sxx)
}

/// Writes `errors.csv`, `index.html` and the per-scene plots under `out_dir`, and prints the
/// summary table.
pub fn write_report(out_dir: &Path, reports: &[SceneReport]) -> Result<(), String> {
    let write = |name: &str, text: &str| {
        write_bytes_atomically(&out_dir.join(name), text.as_bytes()).map_err(|e| e.to_string())
    };
    write("errors.csv", &csv(reports))?;
    for report in reports {
        write(
            &format!("{}/relmse.svg", report.scene),
            &log_log_svg(report),
        )?;
    }
    let page = html(reports);
    write("index.html", &page)?;
    print!("{}", summary(reports));
    let missing = missing_files(out_dir, &page);
    if !missing.is_empty() {
        return Err(format!(
            "index.html refers to files that were not written: {}",
            missing.join(", ")
        ));
    }
    println!("report: {}", out_dir.join("index.html").display());
    Ok(())
}

/// The files `page` refers to (`src="…"` and `href="…"`, relative to `dir`) that do not exist.
pub fn missing_files(dir: &Path, page: &str) -> Vec<String> {
    let mut missing = Vec::new();
    for attribute in ["src=\"", "href=\""] {
        for (start, _) in page.match_indices(attribute) {
            let rest = &page[start + attribute.len()..];
            let Some(end) = rest.find('"') else {
                continue;
            };
            let target = &rest[..end];
            if !dir.join(target).is_file() && !missing.iter().any(|m| m == target) {
                missing.push(target.to_string());
            }
        }
    }
    missing
}

/// The CSV of every measurement.
fn csv(reports: &[SceneReport]) -> String {
    let mut text =
        String::from("scene,configuration,spp,seconds,rmse,relmse,efficiency,non_finite\n");
    for report in reports {
        for m in &report.measurements {
            let _ = writeln!(
                text,
                "{},{},{},{:.4},{:.6e},{:.6e},{:.6e},{}",
                report.scene,
                m.configuration,
                m.spp,
                m.seconds,
                m.rmse,
                m.relmse,
                m.efficiency(),
                m.non_finite
            );
        }
    }
    text
}

/// A number for the tables: `inf` when infinite (an exact image), `-` when missing or undefined.
fn number(value: Option<f64>, digits: usize) -> String {
    match value {
        Some(v) if v.is_finite() => format!("{v:.digits$}"),
        Some(v) if v.is_infinite() => "inf".to_string(),
        _ => "-".to_string(),
    }
}

/// The terminal table: scene × configuration, relMSE at the largest budget and efficiency
/// relative to the reference integrator.
fn summary(reports: &[SceneReport]) -> String {
    let mut text = format!(
        "{:<16} {:<15} {:>6} {:>11} {:>9} {:>6}\n",
        "scene", "configuration", "spp", "relMSE", "eff/ref", "slope"
    );
    for report in reports {
        for name in &report.configurations {
            let Some(last) = report.final_of(name) else {
                continue;
            };
            let _ = writeln!(
                text,
                "{:<16} {:<15} {:>6} {:>11.3e} {:>9} {:>6}",
                report.scene,
                name,
                last.spp,
                last.relmse,
                number(report.efficiency_ratio(name), 2),
                number(report.slope(name), 2)
            );
        }
    }
    text
}

/// The HTML page: per scene the techniques `auto` chose, a table of each configuration's
/// samples, relMSE, efficiency relative to the reference integrator and convergence slope, the
/// stored reference, each configuration's image at the largest (equal) time budget above its
/// false-colour error map, and the error-against-time plot.
fn html(reports: &[SceneReport]) -> String {
    let mut page = String::from(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>Strata render-all</title>\n\
         <style>body{font-family:sans-serif} figure{display:inline-block;margin:4px;\
         text-align:center;vertical-align:top} img{image-rendering:pixelated;width:192px} \
         table{border-collapse:collapse} td,th{padding:2px 8px;text-align:right}</style></head>\
         <body>\n<h1>Strata: error against time</h1>\n<p>Every configuration rendered for the \
         same time; efficiency = 1/(relMSE &times; seconds), relative to the reference \
         integrator; slope = fitted d log relMSE / d log seconds. Error maps: per-pixel relative \
         squared error, log scale from 1e-4 (dark) to 1 (yellow). All numbers: \
         <a href=\"errors.csv\">errors.csv</a>.</p>\n",
    );
    for report in reports {
        let scene = &report.scene;
        let _ = writeln!(
            page,
            "<h2>{scene}</h2>\n<p>auto chose: {}</p>\n<table><tr><th>configuration</th>\
             <th>spp</th><th>seconds</th><th>relMSE</th><th>efficiency / reference</th>\
             <th>slope</th></tr>",
            report.auto_techniques.join(", ")
        );
        for name in &report.configurations {
            let Some(last) = report.final_of(name) else {
                continue;
            };
            let _ = writeln!(
                page,
                "<tr><td>{name}</td><td>{}</td><td>{:.2}</td><td>{:.3e}</td><td>{}</td>\
                 <td>{}</td></tr>",
                last.spp,
                last.seconds,
                last.relmse,
                number(report.efficiency_ratio(name), 2),
                number(report.slope(name), 2)
            );
        }
        let _ = writeln!(
            page,
            "</table>\n<figure><img src=\"{scene}/stored-reference.png\">\
             <figcaption>stored reference</figcaption></figure>"
        );
        for name in &report.configurations {
            let Some(last) = report.final_of(name) else {
                continue;
            };
            let _ = writeln!(
                page,
                "<figure><img src=\"{scene}/{name}.png\"><br><img src=\"{scene}/{name}-error.png\">\
                 <figcaption>{name}<br>{} spp, relMSE {:.3e}<br>efficiency &times;{}\
                 </figcaption></figure>",
                last.spp,
                last.relmse,
                number(report.efficiency_ratio(name), 2)
            );
        }
        let _ = writeln!(
            page,
            "<p><img style=\"width:480px\" src=\"{scene}/relmse.svg\"></p>"
        );
    }
    page.push_str("</body></html>\n");
    page
}

#[cfg(test)]
mod tests {
    use super::*;

    fn measurement(configuration: &str, budget: f64, relmse: f64) -> Measurement {
        Measurement {
            configuration: configuration.to_string(),
            budget,
            spp: 1,
            seconds: budget,
            rmse: relmse.sqrt(),
            relmse,
            non_finite: 0,
        }
    }

    #[test]
    fn efficiency_ratio_compares_the_largest_budgets() {
        let report = SceneReport {
            scene: "s".to_string(),
            configurations: vec![REFERENCE.to_string(), "mis".to_string()],
            auto_techniques: Vec::new(),
            measurements: vec![
                measurement(REFERENCE, 1.0, 0.5),
                measurement(REFERENCE, 2.0, 0.25),
                measurement("mis", 2.0, 0.05),
                measurement("mis", 1.0, 10.0),
            ],
        };
        assert_eq!(report.efficiency_ratio(REFERENCE), Some(1.0));
        let ratio = report.efficiency_ratio("mis").expect("both rendered");
        assert!((ratio - 5.0).abs() < 1e-12, "ratio {ratio}");
        assert_eq!(report.efficiency_ratio("absent"), None);
        // relMSE falls from 0.5 to 0.25 as time doubles: slope -1.
        let slope = report.slope(REFERENCE).expect("two budgets");
        assert!((slope + 1.0).abs() < 1e-12, "slope {slope}");
        assert_eq!(report.slope("absent"), None);
    }

    #[test]
    fn a_fitted_slope_is_exact_on_a_power_law() {
        let points: Vec<(f64, f64)> = [1.0_f64, 2.0, 4.0, 8.0]
            .iter()
            .map(|&t| (t.ln(), (3.0 * t.powf(-1.5)).ln()))
            .collect();
        let slope = fitted_slope(&points).expect("four points");
        assert!((slope + 1.5).abs() < 1e-12, "slope {slope}");
        assert_eq!(fitted_slope(&points[..1]), None);
    }

    #[test]
    fn every_file_the_page_refers_to_is_checked() {
        let dir = std::env::temp_dir().join(format!("strata-report-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("cbox")).unwrap();
        std::fs::write(dir.join("cbox/auto.png"), b"png").unwrap();
        std::fs::write(dir.join("errors.csv"), b"csv").unwrap();
        let page = "<img src=\"cbox/auto.png\"><a href=\"errors.csv\"></a>\
                    <img src=\"cbox/auto-error.png\"><img src=\"cbox/auto-error.png\">";
        let missing = missing_files(&dir, page);
        std::fs::remove_dir_all(&dir).unwrap();
        assert_eq!(missing, ["cbox/auto-error.png"]);
    }

    #[test]
    fn the_page_shows_an_image_and_an_error_map_per_configuration() {
        let report = SceneReport {
            scene: "cbox".to_string(),
            configurations: vec![REFERENCE.to_string(), "auto".to_string()],
            auto_techniques: vec!["mis".to_string()],
            measurements: vec![
                measurement(REFERENCE, 1.0, 0.5),
                measurement("auto", 1.0, 0.1),
            ],
        };
        let page = html(&[report]);
        for file in [
            "cbox/stored-reference.png",
            "cbox/reference.png",
            "cbox/reference-error.png",
            "cbox/auto.png",
            "cbox/auto-error.png",
            "cbox/relmse.svg",
            "errors.csv",
        ] {
            assert!(
                page.contains(&format!("\"{file}\"")),
                "{file} is not on the page"
            );
        }
        assert!(page.contains("auto chose: mis"));
    }
}
