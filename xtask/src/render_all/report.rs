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
    write("index.html", &html(reports))?;
    print!("{}", summary(reports));
    println!("report: {}", out_dir.join("index.html").display());
    Ok(())
}

/// The CSV of every measurement.
fn csv(reports: &[SceneReport]) -> String {
    let mut text = String::from("scene,configuration,spp,seconds,rmse,relmse,efficiency\n");
    for report in reports {
        for m in &report.measurements {
            let _ = writeln!(
                text,
                "{},{},{},{:.4},{:.6e},{:.6e},{:.6e}",
                report.scene,
                m.configuration,
                m.spp,
                m.seconds,
                m.rmse,
                m.relmse,
                m.efficiency()
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
        "{:<16} {:<15} {:>6} {:>11} {:>9}\n",
        "scene", "configuration", "spp", "relMSE", "eff/ref"
    );
    for report in reports {
        for name in &report.configurations {
            let Some(last) = report.final_of(name) else {
                continue;
            };
            let _ = writeln!(
                text,
                "{:<16} {:<15} {:>6} {:>11.3e} {:>9}",
                report.scene,
                name,
                last.spp,
                last.relmse,
                number(report.efficiency_ratio(name), 2)
            );
        }
    }
    text
}

/// The HTML page: per scene the stored reference, each configuration's image at the largest
/// budget with its relMSE and efficiency relative to the reference integrator, the techniques
/// `auto` chose, and the error-against-time plot.
fn html(reports: &[SceneReport]) -> String {
    let mut page = String::from(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>Strata render-all</title>\n\
         <style>body{font-family:sans-serif} figure{display:inline-block;margin:4px;\
         text-align:center} img{image-rendering:pixelated;width:192px}</style></head><body>\n\
         <h1>Strata: error against time</h1>\n<p>Images at the largest time budget; \
         efficiency = 1/(relMSE &times; seconds), relative to the reference integrator. \
         All numbers: <a href=\"errors.csv\">errors.csv</a>.</p>\n",
    );
    for report in reports {
        let scene = &report.scene;
        let _ = writeln!(
            page,
            "<h2>{scene}</h2>\n<p>auto chose: {}</p>\n<figure><img src=\"{scene}/stored-reference.png\">\
             <figcaption>stored reference</figcaption></figure>",
            report.auto_techniques.join(", ")
        );
        for name in &report.configurations {
            let Some(last) = report.final_of(name) else {
                continue;
            };
            let _ = writeln!(
                page,
                "<figure><img src=\"{scene}/{name}.png\"><figcaption>{name}<br>{} spp, \
                 relMSE {:.3e}<br>efficiency &times;{}</figcaption></figure>",
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
    }
}
