//! Image error metrics: RMSE, relative MSE against a reference, and mean value.
//!
//! All sums run in `f64` over every pixel and every channel (R, G, B count as separate values).
//! Empty images give NaN.

use std::fmt;

use glam::Vec3;

use crate::image::Image;

/// Two images that cannot be compared because their sizes differ.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SizeMismatch {
    /// Width and height of the first image, in pixels.
    pub a: (u32, u32),
    /// Width and height of the second image, in pixels.
    pub b: (u32, u32),
}

impl fmt::Display for SizeMismatch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "image sizes differ: {}x{} against {}x{}",
            self.a.0, self.a.1, self.b.0, self.b.1
        )
    }
}

impl std::error::Error for SizeMismatch {}

/// Mean over pixels and channels of `term(a, b)` for corresponding channel values.
fn mean_over_channels(
    a: &Image,
    b: &Image,
    term: impl Fn(f64, f64) -> f64,
) -> Result<f64, SizeMismatch> {
    if a.width != b.width || a.height != b.height || a.data.len() != b.data.len() {
        return Err(SizeMismatch {
            a: (a.width, a.height),
            b: (b.width, b.height),
        });
    }
    let sum: f64 = a
        .data
        .iter()
        .zip(&b.data)
        .flat_map(|(pa, pb): (&Vec3, &Vec3)| {
            (0..3).map(move |c| (f64::from(pa[c]), f64::from(pb[c])))
        })
        .map(|(va, vb)| term(va, vb))
        .sum();
    Ok(sum / (3 * a.data.len()) as f64)
}

/// Root mean square difference `sqrt(mean((a − b)²))` over pixels and channels.
pub fn rmse(a: &Image, b: &Image) -> Result<f64, SizeMismatch> {
    mean_over_channels(a, b, |va, vb| (va - vb).powi(2)).map(f64::sqrt)
}

/// The ε of relative errors `(a − b)² / (b² + ε)`: keeps black reference pixels from dividing
/// by zero (radiance units squared).
pub const RELMSE_EPSILON: f64 = 0.01;

/// Relative mean square error of `a` against the reference `b`:
/// `mean((a − b)² / (b² + 0.01))` over pixels and channels.
pub fn relmse(a: &Image, reference: &Image) -> Result<f64, SizeMismatch> {
    mean_over_channels(a, reference, |va, vb| {
        (va - vb).powi(2) / (vb * vb + RELMSE_EPSILON)
    })
}

/// Each pixel's relative squared error against the reference, `mean over channels of
/// (a − b)² / (b² + 0.01)`, in row order (top row first): [`relmse`] is their mean. For error
/// maps and for the error of an image region.
pub fn relmse_per_pixel(a: &Image, reference: &Image) -> Result<Vec<f64>, SizeMismatch> {
    if a.width != reference.width || a.height != reference.height {
        return Err(SizeMismatch {
            a: (a.width, a.height),
            b: (reference.width, reference.height),
        });
    }
    Ok(a.data
        .iter()
        .zip(&reference.data)
        .map(|(pa, pb)| {
            (0..3)
                .map(|c| {
                    let (va, vb) = (f64::from(pa[c]), f64::from(pb[c]));
                    (va - vb).powi(2) / (vb * vb + RELMSE_EPSILON)
                })
                .sum::<f64>()
                / 3.0
        })
        .collect())
}

/// Mean value over pixels and channels.
pub fn mean(image: &Image) -> f64 {
    let sum: f64 = image
        .data
        .iter()
        .map(|p| p.to_array().iter().map(|&c| f64::from(c)).sum::<f64>())
        .sum();
    sum / (3 * image.data.len()) as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 2×1 image from two RGB triples.
    fn two_pixels(p: [f32; 3], q: [f32; 3]) -> Image {
        Image {
            width: 2,
            height: 1,
            data: vec![Vec3::from(p), Vec3::from(q)],
        }
    }

    #[test]
    fn rmse_by_hand() {
        let a = two_pixels([1.0, 2.0, 3.0], [0.0, 0.0, 0.0]);
        let b = two_pixels([1.0, 0.0, 3.0], [0.0, 0.0, 4.0]);
        // Squared differences 0, 4, 0, 0, 0, 16: mean 20/6, root 1.8257...
        assert!((rmse(&a, &b).unwrap() - (20.0f64 / 6.0).sqrt()).abs() < 1e-12);
        assert_eq!(rmse(&a, &a).unwrap(), 0.0);
    }

    #[test]
    fn relmse_by_hand_uses_the_reference_in_the_denominator() {
        let a = two_pixels([2.0, 0.1, 0.0], [1.0, 1.0, 1.0]);
        let b = two_pixels([1.0, 0.0, 0.0], [1.0, 1.0, 1.0]);
        // (2−1)²/(1+0.01) + 0.1²/(0+0.01) = 1/1.01 + 1, over 6 values.
        let expected = (1.0 / 1.01 + 1.0) / 6.0;
        assert!((relmse(&a, &b).unwrap() - expected).abs() < 1e-7);
        // Swapping the roles changes the denominators: 1/(4+0.01) + 0.01/(0.01+0.01).
        let swapped = (1.0 / 4.01 + 0.5) / 6.0;
        assert!((relmse(&b, &a).unwrap() - swapped).abs() < 1e-7);
    }

    #[test]
    fn per_pixel_relmse_by_hand_averages_to_relmse() {
        let a = two_pixels([2.0, 0.1, 0.0], [1.0, 1.0, 1.0]);
        let b = two_pixels([1.0, 0.0, 0.0], [1.0, 1.0, 2.0]);
        let per_pixel = relmse_per_pixel(&a, &b).unwrap();
        assert!((per_pixel[0] - (1.0 / 1.01 + 1.0) / 3.0).abs() < 1e-7);
        assert!((per_pixel[1] - (1.0 / 4.01) / 3.0).abs() < 1e-7);
        let mean = (per_pixel[0] + per_pixel[1]) / 2.0;
        assert!((mean - relmse(&a, &b).unwrap()).abs() < 1e-12);
        assert!(relmse_per_pixel(&a, &Image::new(1, 2)).is_err());
    }

    #[test]
    fn mean_by_hand() {
        assert!((mean(&two_pixels([1.0, 2.0, 3.0], [4.0, 5.0, 6.0])) - 3.5).abs() < 1e-12);
        assert!(mean(&Image::new(0, 0)).is_nan());
    }

    #[test]
    fn size_mismatch_is_an_error() {
        let a = Image::new(2, 1);
        let b = Image::new(1, 2);
        let error = rmse(&a, &b).unwrap_err();
        assert_eq!(
            error,
            SizeMismatch {
                a: (2, 1),
                b: (1, 2)
            }
        );
        assert_eq!(error.to_string(), "image sizes differ: 2x1 against 1x2");
        assert!(relmse(&a, &b).is_err());
    }
}
