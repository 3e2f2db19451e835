//! `strata diff A.exr B.exr`: error metrics of image A against reference image B.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::commands::CommandError;
use crate::image::Image;
use crate::metrics::{SizeMismatch, mean, relmse, rmse};

/// The comparison printed by `strata diff` as one JSON line (a contract).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct DiffReport {
    /// Root mean square difference over pixels and channels.
    pub rmse: f64,
    /// Mean over pixels and channels of `(a − b)² / (b² + 0.01)`, `b` the reference.
    pub relmse: f64,
    /// Mean of image A over pixels and channels.
    pub mean_a: f64,
    /// Mean of image B over pixels and channels.
    pub mean_b: f64,
}

impl DiffReport {
    /// Compares `a` against the reference `b`; an error if their sizes differ.
    pub fn of_images(a: &Image, b: &Image) -> Result<Self, SizeMismatch> {
        Ok(Self {
            rmse: rmse(a, b)?,
            relmse: relmse(a, b)?,
            mean_a: mean(a),
            mean_b: mean(b),
        })
    }

    /// Reads the EXR files `a` and `b` and compares them. Unreadable files and differing sizes
    /// are bad input, with messages naming the files.
    pub fn of_files(a: &Path, b: &Path) -> Result<Self, CommandError> {
        let image_a = Image::read_exr(a).map_err(|e| CommandError::BadInput(e.to_string()))?;
        let image_b = Image::read_exr(b).map_err(|e| CommandError::BadInput(e.to_string()))?;
        Self::of_images(&image_a, &image_b).map_err(|e| {
            CommandError::BadInput(format!(
                "cannot compare '{}' with '{}': {e}",
                a.display(),
                b.display()
            ))
        })
    }

    /// The report as one line of JSON with the keys `rmse`, `relmse`, `mean_a`, `mean_b` in
    /// that order (non-finite values print as `null`), without a trailing newline.
    pub fn to_json_line(&self) -> String {
        serde_json::to_string(self).expect("four numbers serialise to JSON")
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;

    #[test]
    fn report_by_hand() {
        let a = Image {
            width: 1,
            height: 1,
            data: vec![Vec3::new(1.0, 1.0, 1.0)],
        };
        let b = Image {
            width: 1,
            height: 1,
            data: vec![Vec3::new(0.0, 1.0, 2.0)],
        };
        let report = DiffReport::of_images(&a, &b).unwrap();
        // Squared differences 1, 0, 1.
        assert!((report.rmse - (2.0f64 / 3.0).sqrt()).abs() < 1e-12);
        assert!((report.relmse - (1.0 / 0.01 + 1.0 / 4.01) / 3.0).abs() < 1e-9);
        assert_eq!((report.mean_a, report.mean_b), (1.0, 1.0));
        let line = report.to_json_line();
        assert!(
            line.starts_with("{\"rmse\":") && !line.contains('\n'),
            "{line}"
        );
        let keys: Vec<usize> = ["\"rmse\"", "\"relmse\"", "\"mean_a\"", "\"mean_b\""]
            .iter()
            .map(|k| line.find(k).unwrap())
            .collect();
        assert!(keys.windows(2).all(|w| w[0] < w[1]), "key order: {line}");
    }

    #[test]
    fn unreadable_files_are_bad_input_naming_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let good = dir.path().join("good.exr");
        Image::new(2, 2).write_exr(&good).unwrap();
        let error = DiffReport::of_files(&good, &dir.path().join("nope.exr")).unwrap_err();
        assert!(
            matches!(&error, CommandError::BadInput(m) if m.contains("nope.exr")),
            "{error}"
        );
        let other = dir.path().join("other.exr");
        Image::new(3, 2).write_exr(&other).unwrap();
        let error = DiffReport::of_files(&good, &other).unwrap_err();
        assert!(
            matches!(&error, CommandError::BadInput(m) if m.contains("other.exr") && m.contains("3x2"))
        );
    }
}
