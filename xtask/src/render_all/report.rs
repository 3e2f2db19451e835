//! The render-all report: `errors.csv`, `index.html` (a summary across scenes, then per scene
//! each rung's techniques, figures over seeds, images and plot), and the terminal tables.

use super::ladder::REFERENCE;
use super::plot::log_log_svg;
use super::summary::{SceneSummary, Spread};
use render::atomic_write::write_bytes_atomically;
use std::fmt::Write as _;
use std::path::Path;

/// Name of the rung rendered as `strata render` does without flags.
pub const AUTO: &str = "auto";

/// File stem, in each scene's directory, of the stored reference's preview and EXR.
pub const STORED_REFERENCE: &str = "stored-reference";

/// One render measured against the stored reference.
#[derive(Clone, Debug)]
pub struct Measurement {
    /// Configuration name.
    pub configuration: String,
    /// Time budget asked for, in seconds.
    pub budget: f64,
    /// Sampler seed.
    pub seed: u32,
    /// Samples per pixel rendered.
    pub spp: u32,
    /// Rendering time spent, in seconds (pilots included).
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

/// A rung of a scene's ladder as the report shows it.
#[derive(Clone, Debug)]
pub struct Rung {
    /// Configuration name.
    pub name: String,
    /// The rung it adds a technique to, if any.
    pub builds_on: Option<String>,
    /// Every technique it renders with.
    pub techniques: Vec<String>,
}

/// What `auto`'s pilot chose for one render.
#[derive(Clone, Debug, PartialEq)]
pub struct AutoRecord {
    /// Sampler seed of the render.
    pub seed: u32,
    /// The pilot's label for its choice (`base`, or the switched trials such as `+ris`).
    pub label: String,
    /// Every technique of the chosen settings.
    pub techniques: Vec<String>,
    /// The pilot's measured reason, one line.
    pub reason: String,
}

/// Everything measured on one scene.
#[derive(Clone, Debug)]
pub struct SceneReport {
    /// Scene name (file stem).
    pub scene: String,
    /// The ladder's rungs in order.
    pub rungs: Vec<Rung>,
    /// What `auto` chose at the largest budget, one record per seed.
    pub auto_choices: Vec<AutoRecord>,
    /// Every render, in ladder order, then budget order, then seed order.
    pub measurements: Vec<Measurement>,
    /// Factor the previews' linear values are multiplied by before sRGB encoding.
    pub exposure: f32,
}

impl SceneReport {
    /// The largest budget rendered, in seconds.
    fn largest_budget(&self) -> Option<f64> {
        self.measurements
            .iter()
            .map(|m| m.budget)
            .max_by(f64::total_cmp)
    }

    /// The renders of `configuration` at the largest budget, one per seed.
    pub fn finals(&self, configuration: &str) -> Vec<&Measurement> {
        let Some(largest) = self.largest_budget() else {
            return Vec::new();
        };
        self.measurements
            .iter()
            .filter(|m| m.configuration == configuration && m.budget == largest)
            .collect()
    }

    /// `quantity` of `configuration`'s renders at the largest budget, over seeds.
    fn spread(
        &self,
        configuration: &str,
        quantity: impl Fn(&Measurement) -> f64,
    ) -> Option<Spread> {
        let values: Vec<f64> = self
            .finals(configuration)
            .into_iter()
            .map(quantity)
            .collect();
        Spread::of(&values)
    }

    /// Efficiency of `configuration` at the largest budget, over seeds, per second.
    pub fn efficiency(&self, configuration: &str) -> Option<Spread> {
        self.spread(configuration, Measurement::efficiency)
    }

    /// Efficiency of `configuration` at the largest budget, over seeds, each divided by the
    /// reference integrator's median.
    fn efficiency_ratio(&self, configuration: &str) -> Option<Spread> {
        let reference = self.efficiency(REFERENCE)?.median;
        Some(self.efficiency(configuration)?.scaled(reference))
    }

    /// The convergence slope of `configuration`: the least-squares slope of log relMSE against
    /// log seconds over every render of it, all budgets and seeds (−1 for an unbiased estimator
    /// whose variance falls as 1/samples; steeper for stratified sampling of smooth integrands).
    /// `None` with fewer than two distinct times.
    pub fn slope(&self, configuration: &str) -> Option<f64> {
        let points: Vec<(f64, f64)> = self
            .measurements
            .iter()
            .filter(|m| m.configuration == configuration && m.relmse > 0.0 && m.seconds > 0.0)
            .map(|m| (m.seconds.ln(), m.relmse.ln()))
            .collect();
        fitted_slope(&points)
    }

    /// The distinct choices `auto` made at the largest budget, most frequent first, each with
    /// the number of seeds that made it.
    pub fn auto_choice_counts(&self) -> Vec<(&AutoRecord, usize)> {
        let mut counts: Vec<(&AutoRecord, usize)> = Vec::new();
        for record in &self.auto_choices {
            match counts
                .iter_mut()
                .find(|(r, _)| r.techniques == record.techniques)
            {
                Some((_, n)) => *n += 1,
                None => counts.push((record, 1)),
            }
        }
        counts.sort_by_key(|c| std::cmp::Reverse(c.1));
        counts
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

/// How the whole run was made, for the CSV and the page's header.
#[derive(Clone, Debug)]
pub struct RunInfo {
    /// `git rev-parse HEAD` of the checkout, or `unknown`.
    pub commit: String,
    /// The time budgets, in seconds.
    pub budgets: Vec<f64>,
    /// Seeds rendered per budget.
    pub seeds: u32,
}

/// Writes `errors.csv`, `index.html` and the per-scene plots under `out_dir`, and prints the
/// summary tables. Fails when the page refers to a file that is not there.
pub fn write_report(out_dir: &Path, reports: &[SceneReport], run: &RunInfo) -> Result<(), String> {
    let write = |name: &str, text: &str| {
        write_bytes_atomically(&out_dir.join(name), text.as_bytes()).map_err(|e| e.to_string())
    };
    write("errors.csv", &csv(reports, &run.commit))?;
    for report in reports {
        write(
            &format!("{}/relmse.svg", report.scene),
            &log_log_svg(report),
        )?;
    }
    let page = html(reports, run);
    write("index.html", &page)?;
    print!("{}", terminal_tables(reports));
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

/// The files `page` refers to (`src="…"` and `href="…"`, relative to `dir`; links within the
/// page, `#…`, are not files) that do not exist.
pub fn missing_files(dir: &Path, page: &str) -> Vec<String> {
    let mut missing = Vec::new();
    for attribute in ["src=\"", "href=\""] {
        for (start, _) in page.match_indices(attribute) {
            let rest = &page[start + attribute.len()..];
            let Some(end) = rest.find('"') else {
                continue;
            };
            let target = &rest[..end];
            if target.starts_with('#') {
                continue;
            }
            if !dir.join(target).is_file() && !missing.iter().any(|m| m == target) {
                missing.push(target.to_string());
            }
        }
    }
    missing
}

/// The CSV of every measurement, each row with the commit it was made at.
fn csv(reports: &[SceneReport], commit: &str) -> String {
    let mut text = String::from(
        "scene,configuration,spp,seconds,rmse,relmse,efficiency,non_finite,budget,seed,commit\n",
    );
    for report in reports {
        for m in &report.measurements {
            let _ = writeln!(
                text,
                "{},{},{},{:.4},{:.6e},{:.6e},{:.6e},{},{},{},{commit}",
                report.scene,
                m.configuration,
                m.spp,
                m.seconds,
                m.rmse,
                m.relmse,
                m.efficiency(),
                m.non_finite,
                m.budget,
                m.seed,
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

/// A ratio: two decimals below 1000, scientific notation above (`12.34`, `1.80e7`).
fn ratio(value: Option<f64>) -> String {
    match value {
        Some(v) if v.abs() >= 1000.0 => sci(Some(v)),
        _ => number(value, 2),
    }
}

/// A positive figure of any size, in scientific notation with three significant digits:
/// `1.23e3`, `inf`, or `-`.
fn sci(value: Option<f64>) -> String {
    match value {
        Some(v) if v.is_finite() => format!("{v:.2e}"),
        Some(v) if v.is_infinite() => "inf".to_string(),
        _ => "-".to_string(),
    }
}

/// A spread as `median [min–max]` in `format`.
fn spread_text(spread: Option<Spread>, format: impl Fn(Option<f64>) -> String) -> String {
    match spread {
        Some(s) => format!(
            "{} [{}&ndash;{}]",
            format(Some(s.median)),
            format(Some(s.min)),
            format(Some(s.max))
        ),
        None => "-".to_string(),
    }
}

/// `text` with `&`, `<`, `>` and `"` escaped for HTML.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The terminal tables: scene × configuration (median spp, median relMSE at the largest budget
/// and its range over seeds, median efficiency relative to the reference integrator, slope),
/// then the summary across scenes.
fn terminal_tables(reports: &[SceneReport]) -> String {
    let mut text = format!(
        "{:<16} {:<15} {:>6} {:>11} {:>23} {:>9} {:>6}\n",
        "scene", "configuration", "spp", "relMSE", "relMSE range", "eff/ref", "slope"
    );
    for report in reports {
        for rung in &report.rungs {
            let Some(relmse) = report.spread(&rung.name, |m| m.relmse) else {
                continue;
            };
            let spp = report.spread(&rung.name, |m| f64::from(m.spp));
            let _ = writeln!(
                text,
                "{:<16} {:<15} {:>6} {:>11.3e} {:>11.3e}-{:<11.3e} {:>9} {:>6}",
                report.scene,
                rung.name,
                number(spp.map(|s| s.median), 0),
                relmse.median,
                relmse.min,
                relmse.max,
                ratio(report.efficiency_ratio(&rung.name).map(|s| s.median)),
                number(report.slope(&rung.name), 2)
            );
        }
    }
    let _ = writeln!(
        text,
        "\n{:<16} {:<15} {:>9} {:>9} {:>9}  auto chose",
        "scene", "best", "eff/s", "best/mis", "auto/best"
    );
    for report in reports {
        let Some(summary) = SceneSummary::of(report) else {
            continue;
        };
        let chose = report
            .auto_choice_counts()
            .first()
            .map_or(String::new(), |(r, _)| r.label.clone());
        let _ = writeln!(
            text,
            "{:<16} {:<15} {:>9} {:>9} {:>9}  {chose}{}",
            report.scene,
            summary.best,
            sci(Some(summary.best_efficiency.median)),
            ratio(summary.best_over_baseline()),
            ratio(summary.auto_over_best()),
            if summary.auto_flagged() {
                "  <- auto worse than the best beyond the seeds' spread"
            } else {
                ""
            }
        );
    }
    text
}

/// In the page's head: records errors (failed loads, uncaught exceptions) and, once the page
/// has loaded, marks `<body>` with `data-image-check="ok N"` (N images, all decoded) or
/// `"broken SRC …"`, and `data-page-errors` with the number of errors; a broken image also
/// puts a red line at the top of the page. `cargo xtask report-check` reads the marks.
const CHECK_SCRIPT: &str = "<script>\n\
var pageErrors = [];\n\
window.addEventListener('error', function (e) {\n\
  var t = e.target;\n\
  pageErrors.push(t && t.getAttribute ? 'cannot load ' + t.getAttribute('src') : String(e.message));\n\
}, true);\n\
window.addEventListener('load', function () {\n\
  var broken = [];\n\
  for (var i = 0; i < document.images.length; i++) {\n\
    var img = document.images[i];\n\
    if (!img.complete || img.naturalWidth === 0) broken.push(img.getAttribute('src'));\n\
  }\n\
  document.body.setAttribute('data-image-check', broken.length ? 'broken ' + broken.join(' ') : 'ok ' + document.images.length);\n\
  document.body.setAttribute('data-page-errors', String(pageErrors.length));\n\
  if (broken.length) {\n\
    var p = document.createElement('p');\n\
    p.className = 'bad';\n\
    p.textContent = broken.length + ' image(s) failed to load: ' + broken.join(', ');\n\
    document.body.insertBefore(p, document.body.firstChild);\n\
  }\n\
});\n\
</script>\n";

/// The page's style sheet.
const STYLE: &str = "<style>\n\
body{font-family:sans-serif;max-width:1400px;margin:0 auto;padding:0 12px}\n\
figure{display:inline-block;margin:4px;text-align:center;vertical-align:top;font-size:small}\n\
figure img{image-rendering:pixelated;width:192px;display:block;border:1px solid #888}\n\
table{border-collapse:collapse;margin:8px 0}\n\
td,th{padding:2px 8px;text-align:right;border-bottom:1px solid #ddd;vertical-align:top}\n\
td{white-space:nowrap}\n\
td.text,th.text{text-align:left;white-space:normal}\n\
td.techniques{text-align:left;font-size:small;max-width:420px;white-space:normal}\n\
tr.flag td.auto{background:#fdd;color:#b00;font-weight:bold}\n\
tr.best td{background:#efe}\n\
.bad{color:#b00;font-weight:bold}\n\
.note{font-size:small;color:#444}\n\
nav a{margin-right:10px}\n\
</style>\n";

/// The HTML page: a table of contents, the summary across scenes, then per scene what `auto`
/// chose, a table of each rung (what it builds on, its techniques, median samples and time,
/// relMSE and efficiency relative to the reference integrator with their ranges over seeds,
/// convergence slope), the stored reference, each rung's last render (tone-mapped preview that
/// links to the full-size PNG, its EXR, and its false-colour error map) and the
/// error-against-time plot.
fn html(reports: &[SceneReport], run: &RunInfo) -> String {
    let budgets: Vec<String> = run.budgets.iter().map(|b| format!("{b} s")).collect();
    let largest = run.budgets.iter().copied().fold(0.0, f64::max);
    let mut page = format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <title>Strata render-all</title>\n{STYLE}{CHECK_SCRIPT}</head>\n<body>\n\
         <h1 id=\"top\">Strata: error against time</h1>\n\
         <p>Each configuration of each scene's technique ladder rendered for time budgets of \
         {budgets} with {seeds} seeds each (commit <code>{commit}</code>), measured against the \
         scene's stored reference. Efficiency = 1/(relMSE &times; seconds): twice the \
         efficiency is the same error in half the time. Figures are medians over the seeds at \
         the largest budget ({largest} s), with [min&ndash;max] over the seeds. All numbers: \
         <a href=\"errors.csv\">errors.csv</a>.</p>\n<nav><a href=\"#summary\">summary</a>",
        budgets = budgets.join(", "),
        seeds = run.seeds,
        commit = escape(&run.commit),
    );
    for report in reports {
        let _ = write!(
            page,
            "<a href=\"#scene-{scene}\">{scene}</a>",
            scene = report.scene
        );
    }
    page.push_str("</nav>\n");
    summary_table(&mut page, reports, run.seeds);
    for report in reports {
        scene_section(&mut page, report);
    }
    page.push_str("</body></html>\n");
    page
}

/// The summary: one row per scene.
fn summary_table(page: &mut String, reports: &[SceneReport], seeds: u32) {
    let chance = 1.0 / binomial(2 * u64::from(seeds), u64::from(seeds));
    let _ = writeln!(
        page,
        "<h2 id=\"summary\">Summary</h2>\n<table><tr><th class=\"text\">scene</th>\
         <th class=\"text\">best rung</th><th>its efficiency (1/s)</th>\
         <th>best &divide; mis</th><th class=\"text\">auto chose</th>\
         <th>auto efficiency (1/s)</th><th>auto &divide; best</th></tr>"
    );
    for report in reports {
        let scene = &report.scene;
        let Some(summary) = SceneSummary::of(report) else {
            let _ = writeln!(
                page,
                "<tr><td class=\"text\"><a href=\"#scene-{scene}\">{scene}</a></td>\
                 <td class=\"text\" colspan=\"6\">nothing measured</td></tr>"
            );
            continue;
        };
        let ties = if summary.within_noise.is_empty() {
            String::new()
        } else {
            format!(
                "<br><span class=\"note\">within noise: {}</span>",
                summary.within_noise.join(", ")
            )
        };
        let baseline = match &summary.baseline {
            Some((name, _)) if name != "mis" => format!(
                "{} <span class=\"note\">(over {name})</span>",
                ratio(summary.best_over_baseline())
            ),
            _ => ratio(summary.best_over_baseline()),
        };
        let flagged = summary.auto_flagged();
        let _ = writeln!(
            page,
            "<tr{row}><td class=\"text\"><a href=\"#scene-{scene}\">{scene}</a></td>\
             <td class=\"text\">{best}{ties}</td><td>{best_eff}</td><td>{baseline}</td>\
             <td class=\"techniques\">{chose}</td><td class=\"auto\">{auto_eff}</td>\
             <td class=\"auto\">{ratio}{mark}</td></tr>",
            row = if flagged { " class=\"flag\"" } else { "" },
            best = escape(&summary.best),
            best_eff = spread_text(Some(summary.best_efficiency), sci),
            chose = auto_choice_text(report),
            auto_eff = spread_text(summary.auto_efficiency, sci),
            ratio = ratio(summary.auto_over_best()),
            mark = if flagged {
                " &#x2717; beyond noise"
            } else {
                ""
            },
        );
    }
    let _ = writeln!(
        page,
        "</table>\n<p class=\"note\">Best rung: the highest median efficiency among the \
         ladder's rungs (auto excluded); \"within noise\" lists rungs whose best seed reaches \
         its worst. Best &divide; mis compares medians (with the closest rung named where MIS \
         does not apply). Red: every seed of auto less efficient than every seed of the best \
         &mdash; were the two equally efficient, {:.1}% chance per scene ({seeds} seeds each; \
         the best is picked after looking, so among equals the flag fires more often).</p>",
        100.0 * chance
    );
}

/// `n` choose `k`.
fn binomial(n: u64, k: u64) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// What `auto` chose at the largest budget: each distinct technique list with its pilot label
/// and how many seeds chose it.
fn auto_choice_text(report: &SceneReport) -> String {
    let counts = report.auto_choice_counts();
    if counts.is_empty() {
        return "-".to_string();
    }
    let seeds = report.auto_choices.len();
    counts
        .iter()
        .map(|(record, n)| {
            format!(
                "<b>{}</b> ({n} of {seeds} seeds): {}",
                escape(&record.label),
                escape(&record.techniques.join(", "))
            )
        })
        .collect::<Vec<_>>()
        .join("<br>")
}

/// One scene's section.
fn scene_section(page: &mut String, report: &SceneReport) {
    let scene = &report.scene;
    let best = SceneSummary::of(report).map(|s| s.best);
    let _ = writeln!(
        page,
        "<section id=\"scene-{scene}\">\n<h2>{scene} <a class=\"note\" href=\"#top\">top</a></h2>\n\
         <p>auto chose: {}</p>",
        auto_choice_text(report)
    );
    for record in &report.auto_choices {
        let _ = writeln!(
            page,
            "<p class=\"note\">seed {}: {}</p>",
            record.seed,
            escape(&record.reason)
        );
    }
    let _ = writeln!(
        page,
        "<table><tr><th class=\"text\">rung</th><th class=\"text\">builds on</th>\
         <th class=\"text\">techniques</th><th>spp</th><th>seconds</th>\
         <th>relMSE [min&ndash;max]</th><th>efficiency &divide; reference [min&ndash;max]</th>\
         <th>slope</th></tr>"
    );
    for rung in &report.rungs {
        let name = &rung.name;
        if report.finals(name).is_empty() {
            continue;
        }
        let _ = writeln!(
            page,
            "<tr{row}><td class=\"text\">{}</td><td class=\"text\">{}</td>\
             <td class=\"techniques\">{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>\
             <td>{}</td></tr>",
            escape(name),
            escape(rung.builds_on.as_deref().unwrap_or("-")),
            escape(&rung.techniques.join(", ")),
            number(
                report.spread(name, |m| f64::from(m.spp)).map(|s| s.median),
                0
            ),
            number(report.spread(name, |m| m.seconds).map(|s| s.median), 2),
            spread_text(report.spread(name, |m| m.relmse), sci),
            spread_text(report.efficiency_ratio(name), ratio),
            number(report.slope(name), 2),
            row = if best.as_deref() == Some(name) {
                " class=\"best\""
            } else {
                ""
            },
        );
    }
    let _ = writeln!(
        page,
        "</table>\n<p class=\"note\">Images: each rung's render at the largest budget with its \
         last seed, exposure chosen per scene (the reference's 99th-percentile luminance shown at \
         0.9: &times;{exposure:.3}); click for the full-size PNG, or take the EXR. Error maps: per-pixel relative \
         squared error, log scale from 1e-4 (dark) to 1 (yellow).</p>\n\
         <figure><a href=\"{scene}/{STORED_REFERENCE}.png\"><img \
         src=\"{scene}/{STORED_REFERENCE}.png\" alt=\"stored reference\"></a>\
         <figcaption>stored reference<br><a href=\"{scene}/{STORED_REFERENCE}.exr\">EXR</a>\
         </figcaption></figure>",
        exposure = report.exposure
    );
    for rung in &report.rungs {
        let name = &rung.name;
        let Some(last) = report.finals(name).last().copied() else {
            continue;
        };
        let _ = writeln!(
            page,
            "<figure><a href=\"{scene}/{name}.png\"><img src=\"{scene}/{name}.png\" \
             alt=\"{name}\"></a><a href=\"{scene}/{name}-error.png\"><img \
             src=\"{scene}/{name}-error.png\" alt=\"{name} error\"></a>\
             <figcaption>{name}<br>seed {}, {} spp, relMSE {}<br>\
             <a href=\"{scene}/{name}.exr\">EXR</a></figcaption></figure>",
            last.seed,
            last.spp,
            sci(Some(last.relmse)),
        );
    }
    let _ = writeln!(
        page,
        "<p><img style=\"max-width:100%\" src=\"{scene}/relmse.svg\" \
         alt=\"{scene}: relMSE against seconds\"></p>\n</section>"
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    fn measurement(configuration: &str, budget: f64, seed: u32, relmse: f64) -> Measurement {
        Measurement {
            configuration: configuration.to_string(),
            budget,
            seed,
            spp: 1,
            seconds: budget,
            rmse: relmse.sqrt(),
            relmse,
            non_finite: 0,
        }
    }

    fn rung(name: &str) -> Rung {
        Rung {
            name: name.to_string(),
            builds_on: None,
            techniques: vec![format!("{name}-technique")],
        }
    }

    fn report(scene: &str, names: &[&str], measurements: Vec<Measurement>) -> SceneReport {
        SceneReport {
            scene: scene.to_string(),
            rungs: names.iter().map(|n| rung(n)).collect(),
            auto_choices: Vec::new(),
            measurements,
            exposure: 0.5,
        }
    }

    fn run_info() -> RunInfo {
        RunInfo {
            commit: "0123abc".to_string(),
            budgets: vec![1.0, 2.0],
            seeds: 3,
        }
    }

    #[test]
    fn efficiency_ratio_compares_the_largest_budgets_over_seeds() {
        let r = report(
            "s",
            &[REFERENCE, "mis"],
            vec![
                measurement(REFERENCE, 1.0, 1, 0.5),
                measurement(REFERENCE, 2.0, 4, 0.25),
                measurement(REFERENCE, 2.0, 5, 0.25),
                measurement("mis", 2.0, 4, 0.05),
                measurement("mis", 2.0, 5, 0.025),
                measurement("mis", 1.0, 1, 10.0),
            ],
        );
        let reference = r.efficiency_ratio(REFERENCE).expect("rendered");
        assert_eq!(
            (reference.median, reference.min, reference.max),
            (1.0, 1.0, 1.0)
        );
        // The reference's efficiency is 2; MIS's seeds are 10 and 20.
        let mis = r.efficiency_ratio("mis").expect("both rendered");
        assert!(
            (mis.min - 5.0).abs() < 1e-12 && (mis.max - 10.0).abs() < 1e-12,
            "{mis:?}"
        );
        assert!((mis.median - 7.5).abs() < 1e-12, "{mis:?}");
        assert!(r.efficiency_ratio("absent").is_none());
        assert_eq!(r.finals("mis").len(), 2);
        // relMSE falls from 0.5 to 0.25 as time doubles: slope -1.
        let slope = r.slope(REFERENCE).expect("two budgets");
        assert!((slope + 1.0).abs() < 1e-12, "slope {slope}");
        assert_eq!(r.slope("absent"), None);
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
        let page = "<img src=\"cbox/auto.png\"><a href=\"errors.csv\"></a><a href=\"#cbox\">\
                    <img src=\"cbox/auto-error.png\"><img src=\"cbox/auto-error.png\">";
        let missing = missing_files(&dir, page);
        std::fs::remove_dir_all(&dir).unwrap();
        assert_eq!(missing, ["cbox/auto-error.png"]);
    }

    #[test]
    fn the_csv_names_budget_seed_and_commit_of_every_render() {
        let r = report(
            "cbox",
            &[REFERENCE],
            vec![
                measurement(REFERENCE, 0.5, 7, 0.5),
                measurement(REFERENCE, 1.0, 9, 0.25),
            ],
        );
        let text = csv(&[r], "0123abc");
        let mut lines = text.lines();
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        let column = |name: &str| header.iter().position(|h| *h == name).expect(name);
        let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
        assert_eq!(rows.len(), 2);
        for (row, (budget, seed)) in rows.iter().zip([("0.5", "7"), ("1", "9")]) {
            assert_eq!(row.len(), header.len());
            assert_eq!(row[column("budget")], budget);
            assert_eq!(row[column("seed")], seed);
            assert_eq!(row[column("commit")], "0123abc");
            assert_eq!(row[column("scene")], "cbox");
        }
    }

    #[test]
    fn the_page_shows_previews_exrs_and_error_maps_per_configuration() {
        let mut r = report(
            "cbox",
            &[REFERENCE, AUTO],
            vec![
                measurement(REFERENCE, 1.0, 1, 0.5),
                measurement(AUTO, 1.0, 1, 0.1),
            ],
        );
        r.auto_choices.push(AutoRecord {
            seed: 1,
            label: "+path-reuse".to_string(),
            techniques: vec!["nee".to_string(), "path-reuse-4x4".to_string()],
            reason: "pilot: path reuse 2.0".to_string(),
        });
        let page = html(&[r], &run_info());
        for file in [
            "cbox/stored-reference.png",
            "cbox/stored-reference.exr",
            "cbox/reference.png",
            "cbox/reference.exr",
            "cbox/reference-error.png",
            "cbox/auto.png",
            "cbox/auto.exr",
            "cbox/auto-error.png",
            "cbox/relmse.svg",
            "errors.csv",
        ] {
            assert!(
                page.contains(&format!("\"{file}\"")),
                "{file} is not on the page"
            );
        }
        // A click on a preview opens the full-size PNG.
        assert!(page.contains("<a href=\"cbox/auto.png\"><img src=\"cbox/auto.png\""));
        assert!(page.contains("+path-reuse</b> (1 of 1 seeds): nee, path-reuse-4x4"));
        assert!(page.contains("pilot: path reuse 2.0"));
        assert!(page.contains("reference-technique"));
        assert!(page.contains("0123abc"));
    }

    #[test]
    fn auto_choices_are_counted_over_seeds_most_frequent_first() {
        let record = |seed, label: &str| AutoRecord {
            seed,
            label: label.to_string(),
            techniques: vec![label.to_string()],
            reason: String::new(),
        };
        let mut r = report("s", &[AUTO], vec![measurement(AUTO, 1.0, 1, 0.1)]);
        r.auto_choices = vec![record(7, "base"), record(8, "+ris"), record(9, "+ris")];
        let counts: Vec<(&str, usize)> = r
            .auto_choice_counts()
            .into_iter()
            .map(|(record, n)| (record.label.as_str(), n))
            .collect();
        assert_eq!(counts, [("+ris", 2), ("base", 1)]);
        let text = auto_choice_text(&r);
        assert!(text.starts_with("<b>+ris</b> (2 of 3 seeds)"), "{text}");
        assert!(text.contains("<b>base</b> (1 of 3 seeds)"), "{text}");
    }

    #[test]
    fn the_table_of_contents_links_every_scene_section() {
        let a = report(
            "cbox",
            &[REFERENCE],
            vec![measurement(REFERENCE, 1.0, 1, 0.5)],
        );
        let b = report(
            "veach-mis",
            &[REFERENCE],
            vec![measurement(REFERENCE, 1.0, 1, 0.5)],
        );
        let page = html(&[a, b], &run_info());
        for scene in ["cbox", "veach-mis"] {
            let anchor = format!("id=\"scene-{scene}\"");
            assert_eq!(page.matches(&anchor).count(), 1, "{anchor}");
            // In the contents and in the summary table.
            assert_eq!(page.matches(&format!("href=\"#scene-{scene}\"")).count(), 2);
        }
        assert!(page.contains("id=\"summary\"") && page.contains("href=\"#summary\""));
    }

    /// A scene where MIS has efficiencies 10, 12, 14 and `auto` these, over three seeds.
    fn scene_with_auto(auto: [f64; 3]) -> SceneReport {
        let mut measurements = Vec::new();
        for (seed, (mis, auto)) in [10.0, 12.0, 14.0].into_iter().zip(auto).enumerate() {
            measurements.push(measurement("mis", 1.0, seed as u32, 1.0 / mis));
            measurements.push(measurement(AUTO, 1.0, seed as u32, 1.0 / auto));
        }
        report("s", &["mis", AUTO], measurements)
    }

    #[test]
    fn the_summary_row_is_red_exactly_when_auto_is_flagged() {
        for (auto, flagged) in [([5.0, 6.0, 9.9], true), ([5.0, 6.0, 10.0], false)] {
            let page = html(&[scene_with_auto(auto)], &run_info());
            assert_eq!(page.contains("<tr class=\"flag\">"), flagged, "{auto:?}");
            assert_eq!(page.contains("beyond noise"), flagged, "{auto:?}");
            let tables = terminal_tables(&[scene_with_auto(auto)]);
            assert_eq!(tables.contains("auto worse than the best"), flagged);
        }
    }

    #[test]
    fn the_flags_chance_is_stated_for_the_seed_count() {
        assert_eq!(binomial(6, 3), 20.0);
        let page = html(&[scene_with_auto([1.0; 3])], &run_info());
        assert!(page.contains("5.0% chance per scene"));
    }
}
