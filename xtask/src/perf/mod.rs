//! Performance measurements: `cargo xtask raycast-limit` (render time against the time to trace
//! the same rays alone, thread scaling, and Strata's ray casting against Embree's) and `cargo xtask vs-mitsuba` (error at equal time
//! against Mitsuba 3).

mod embree;
mod generate;
mod mitsuba_server;
mod noise;
mod raycast_limit;
mod vs_mitsuba;

pub use raycast_limit::raycast_limit;
pub use vs_mitsuba::vs_mitsuba;

use std::path::{Path, PathBuf};

/// The median of `values` (the mean of the middle two for an even count); NaN when empty.
fn median(values: &[f64]) -> f64 {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len();
    match n {
        0 => f64::NAN,
        _ if n % 2 == 1 => sorted[n / 2],
        _ => 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]),
    }
}

/// `value`, the argument after `flag`, parsed as a positive number.
fn positive<T: std::str::FromStr + PartialOrd + Default>(
    flag: &str,
    value: Option<&String>,
) -> Result<T, String> {
    value
        .and_then(|v| v.parse::<T>().ok())
        .filter(|v| *v > T::default())
        .ok_or_else(|| format!("{flag} takes a positive number"))
}

/// `scenes/NAME.xml` under `root` for a bare name, the path itself otherwise.
fn scene_path(root: &Path, arg: &str) -> PathBuf {
    if arg.ends_with(".xml") {
        PathBuf::from(arg)
    } else {
        root.join("scenes").join(format!("{arg}.xml"))
    }
}

/// A rayon pool of `threads` threads.
fn pool(threads: usize) -> Result<rayon::ThreadPool, String> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&[4.0, 1.0, 3.0, 2.0]), 2.5);
        assert!(median(&[]).is_nan());
    }

    #[test]
    fn positive_rejects_zero_and_garbage() {
        assert_eq!(positive::<u32>("--spp", Some(&"8".to_string())), Ok(8));
        assert!(positive::<u32>("--spp", Some(&"0".to_string())).is_err());
        assert!(positive::<f64>("--time", Some(&"x".to_string())).is_err());
        assert!(positive::<u32>("--spp", None).is_err());
    }
}
