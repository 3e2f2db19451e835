//! The line `strata render` prints on standard error after a successful render (unless
//! `--quiet`):
//!
//! ```text
//! cbox.exr: 256×256, 128 spp, 1.84 s, 9.61 M rays/s, auto: bsdf-sampling+nee+mis-power+…
//! ```
//!
//! The image file; its width × height in pixels; the samples per pixel rendered (the mean over
//! pixels with adaptive sampling, the pilot's included, resumed samples included: the count the
//! EXR header records); the rendering seconds of this run (loading excluded); the rays traced
//! per second in this run, closest-hit and shadow rays together, with an SI prefix and three
//! significant digits; the integrator preset and, joined by `+`, the techniques that were on
//! (the names of the `techniques` field of `--stats`).

use std::path::Path;

use scene::IntegratorPreset;

use crate::stats::RenderStats;

/// The summary line (without a newline) of a render that wrote `out`, with `stats`, as
/// `preset` asked.
pub fn summary_line(out: &Path, stats: &RenderStats, preset: IntegratorPreset) -> String {
    let rays = stats.rays.saturating_add(stats.shadow_rays) as f64;
    let rate = if stats.seconds > 0.0 {
        rays / stats.seconds
    } else {
        0.0
    };
    format!(
        "{}: {}×{}, {} spp, {:.2} s, {} rays/s, {preset}: {}",
        out.display(),
        stats.width,
        stats.height,
        stats.spp,
        stats.seconds,
        si_prefixed(rate),
        stats.techniques.join("+")
    )
}

/// `value` (non-negative) with three significant digits and an SI prefix after a space:
/// `"9.61 M"`, `"961 k"`, `"12.0"`.
fn si_prefixed(value: f64) -> String {
    const PREFIXES: [(f64, &str); 4] = [(1e12, "T"), (1e9, "G"), (1e6, "M"), (1e3, "k")];
    let (scale, prefix) = PREFIXES
        .into_iter()
        .find(|&(scale, _)| value >= scale * 0.9995)
        .unwrap_or((1.0, ""));
    let scaled = value / scale;
    let prefix = if prefix.is_empty() {
        String::new()
    } else {
        format!(" {prefix}")
    };
    let decimals = if scaled >= 99.95 {
        0
    } else if scaled >= 9.995 {
        1
    } else {
        2
    };
    format!("{scaled:.decimals$}{prefix}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_get_three_significant_digits_and_a_prefix() {
        assert_eq!(si_prefixed(0.0), "0.00");
        assert_eq!(si_prefixed(12.0), "12.0");
        assert_eq!(si_prefixed(999.0), "999");
        assert_eq!(si_prefixed(999.6), "1.00 k");
        assert_eq!(si_prefixed(961_000.0), "961 k");
        assert_eq!(si_prefixed(9_612_345.0), "9.61 M");
        assert_eq!(si_prefixed(99_960_000.0), "100 M");
        assert_eq!(si_prefixed(1.234e9), "1.23 G");
    }

    #[test]
    fn the_line_names_the_file_size_samples_time_rate_and_techniques() {
        let stats = RenderStats {
            seconds: 2.0,
            spp: 128,
            width: 256,
            height: 192,
            rays: 12_000_000,
            shadow_rays: 7_000_000,
            techniques: vec!["nee".into(), "mis-power".into(), "path-reuse-4x4".into()],
            ..RenderStats::default()
        };
        assert_eq!(
            summary_line(Path::new("out/cbox.exr"), &stats, IntegratorPreset::Auto),
            "out/cbox.exr: 256×192, 128 spp, 2.00 s, 9.50 M rays/s, auto: nee+mis-power+path-reuse-4x4"
        );
        let instant = RenderStats {
            seconds: 0.0,
            ..stats
        };
        assert!(
            summary_line(Path::new("a.exr"), &instant, IntegratorPreset::Mis)
                .contains(", 0.00 s, 0.00 rays/s, mis: "),
        );
    }
}
