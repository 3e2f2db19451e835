//! `strata merge A.exr B.exr … --out C.exr`: combines renders of one scene made with different
//! seeds (by separate processes or machines) into the image of all their samples.
//!
//! Each input's pixels are means of its samples, and its header records how many samples per
//! pixel (the `spp` attribute that `strata render` writes). The merged pixel is the mean over
//! all samples: the inputs' values weighted by their sample counts, computed in `f64`, and the
//! merged image records the total count, so merged images can be merged again.

use std::path::{Path, PathBuf};

use glam::DVec3;

use crate::commands::CommandError;
use crate::image::{Image, SPP_ATTRIBUTE};

/// An image with the samples per pixel its values average.
#[derive(Clone, Debug, PartialEq)]
pub struct Weighted {
    /// The per-pixel means.
    pub image: Image,
    /// Samples per pixel behind each mean.
    pub spp: u32,
}

/// Reads the EXR at `path` with its sample count; bad input when the file is unreadable or its
/// header has no `spp` attribute.
pub fn read_weighted(path: &Path) -> Result<Weighted, CommandError> {
    let (image, spp) =
        Image::read_exr_with_spp(path).map_err(|e| CommandError::BadInput(e.to_string()))?;
    let spp = spp.ok_or_else(|| {
        CommandError::BadInput(format!(
            "'{}' has no \"{SPP_ATTRIBUTE}\" header attribute (the samples per pixel that \
             strata render records), so it cannot be weighted",
            path.display()
        ))
    })?;
    Ok(Weighted { image, spp })
}

/// The sample-weighted mean of `inputs` (named by `paths` in messages): bad input unless all
/// have the same size, and unless there is at least one sample in all.
pub fn merge(inputs: &[Weighted], paths: &[PathBuf]) -> Result<Weighted, CommandError> {
    let first = inputs
        .first()
        .ok_or_else(|| CommandError::BadInput("nothing to merge".to_string()))?;
    let size = (first.image.width, first.image.height);
    for (input, path) in inputs.iter().zip(paths) {
        if (input.image.width, input.image.height) != size {
            return Err(CommandError::BadInput(format!(
                "'{}' is {}x{} pixels but '{}' is {}x{}",
                path.display(),
                input.image.width,
                input.image.height,
                paths[0].display(),
                size.0,
                size.1
            )));
        }
    }
    let total: u64 = inputs.iter().map(|i| u64::from(i.spp)).sum();
    let spp = u32::try_from(total)
        .map_err(|_| CommandError::BadInput(format!("{total} samples per pixel in all")))?;
    if spp == 0 {
        return Err(CommandError::BadInput(
            "the inputs hold no samples (spp 0)".to_string(),
        ));
    }
    let mut sums = vec![DVec3::ZERO; first.image.data.len()];
    for input in inputs {
        let weight = f64::from(input.spp);
        for (sum, value) in sums.iter_mut().zip(&input.image.data) {
            *sum += weight * value.as_dvec3();
        }
    }
    let image = Image {
        width: size.0,
        height: size.1,
        data: sums
            .iter()
            .map(|s| (*s / f64::from(spp)).as_vec3())
            .collect(),
    };
    Ok(Weighted { image, spp })
}

/// Reads and merges the EXR files at `paths` (see [`merge`]).
pub fn merge_files(paths: &[PathBuf]) -> Result<Weighted, CommandError> {
    let inputs = paths
        .iter()
        .map(|p| read_weighted(p))
        .collect::<Result<Vec<_>, _>>()?;
    merge(&inputs, paths)
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;

    fn weighted(spp: u32, f: impl Fn(u32, u32) -> Vec3) -> Weighted {
        Weighted {
            image: Image::from_fn(3, 2, f),
            spp,
        }
    }

    #[test]
    fn the_merge_is_the_sample_weighted_mean() {
        let a = weighted(1, |x, y| Vec3::new(x as f32, y as f32, 0.25));
        let b = weighted(3, |x, _| Vec3::new(2.0 * x as f32, 1.0, 0.75));
        let paths = [PathBuf::from("a.exr"), PathBuf::from("b.exr")];
        let merged = merge(&[a, b], &paths).unwrap();
        assert_eq!(merged.spp, 4);
        // (1·x + 3·2x) / 4 = 1.75x; (1·y + 3) / 4; (0.25 + 2.25) / 4 = 0.625.
        assert_eq!(merged.image.pixel(2, 1), Vec3::new(3.5, 1.0, 0.625));
        assert_eq!(merged.image.pixel(1, 0), Vec3::new(1.75, 0.75, 0.625));
    }

    #[test]
    fn mismatched_or_empty_inputs_are_bad_input() {
        let paths = [PathBuf::from("a.exr"), PathBuf::from("b.exr")];
        let small = Weighted {
            image: Image::new(2, 2),
            spp: 1,
        };
        let error = merge(&[weighted(1, |_, _| Vec3::ONE), small], &paths).unwrap_err();
        assert_eq!(error.exit_code(), 2);
        assert!(error.to_string().contains("'b.exr' is 2x2"), "{error}");
        assert!(merge(&[], &[]).is_err());
        assert!(merge(&[weighted(0, |_, _| Vec3::ONE)], &paths).is_err());
    }

    #[test]
    fn files_without_a_sample_count_are_refused_by_name() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("plain.exr");
        Image::new(2, 2).write_exr(&path).unwrap();
        let error = read_weighted(&path).unwrap_err();
        assert_eq!(error.exit_code(), 2);
        assert!(error.to_string().contains("plain.exr"), "{error}");
    }
}
