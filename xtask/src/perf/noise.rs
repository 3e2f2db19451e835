//! How much of a relMSE is a reference's own noise, and whether two renderers agree, for
//! `cargo xtask vs-mitsuba`.
//!
//! An image `x` compared with a reference `r` made independently of it has, per pixel and
//! channel, `E[(x − r)²] = Var x + Var r + (E x − E r)²`. A reference rendered as two halves `a`
//! and `b` of equal sample counts (`r = (a + b) / 2`) gives an unbiased estimate of `Var r`:
//! `(a − b)² / 4`. Divided by relMSE's denominator `r² + ε` and averaged like relMSE, that is the
//! [`noise_term`] the reference adds to every relMSE measured against it, which
//! `vs-mitsuba` subtracts: otherwise a reference's noise adds the same amount to both renderers'
//! errors and pulls their ratio towards 1.
//!
//! The same estimate on a high-sample-count Strata render made in two halves tells how much of its
//! relMSE against Mitsuba's reference is noise; the rest estimates the squared bias between the
//! renderers ([`Agreement`]).

use render::image::Image;
use render::metrics::RELMSE_EPSILON;

/// Disagreement between the renderers that makes a scene's figures unusable: an estimated squared
/// bias above this share of the relMSE credited to Strata at equal time.
pub const DISAGREEMENT_SHARE: f64 = 0.1;

/// The mean of two images of the same size.
pub fn mean_of(a: &Image, b: &Image) -> Result<Image, String> {
    same_size(a, b)?;
    Ok(Image {
        width: a.width,
        height: a.height,
        data: a
            .data
            .iter()
            .zip(&b.data)
            .map(|(x, y)| 0.5 * (*x + *y))
            .collect(),
    })
}

/// The relMSE that the noise of the image `(a + b) / 2` adds to a comparison against
/// `reference` (its denominators are `reference`'s): the mean over pixels and channels of
/// `(a − b)² / 4 / (reference² + ε)`, where `a` and `b` are independent renders with equal sample
/// counts.
pub fn noise_term(a: &Image, b: &Image, reference: &Image) -> Result<f64, String> {
    same_size(a, b)?;
    same_size(a, reference)?;
    let sum: f64 = a
        .data
        .iter()
        .zip(&b.data)
        .zip(&reference.data)
        .map(|((pa, pb), pr)| {
            (0..3)
                .map(|c| {
                    let d = f64::from(pa[c]) - f64::from(pb[c]);
                    let r = f64::from(pr[c]);
                    d * d / 4.0 / (r * r + RELMSE_EPSILON)
                })
                .sum::<f64>()
        })
        .sum();
    Ok(sum / (3 * a.data.len()).max(1) as f64)
}

fn same_size(a: &Image, b: &Image) -> Result<(), String> {
    if (a.width, a.height) == (b.width, b.height) {
        Ok(())
    } else {
        Err(format!(
            "images of {}×{} and {}×{} pixels cannot be compared",
            a.width, a.height, b.width, b.height
        ))
    }
}

/// How far a high-sample-count Strata render lies from Mitsuba's reference beyond their noise.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Agreement {
    /// relMSE of the Strata render against the Mitsuba reference.
    pub relmse: f64,
    /// The part of it the two images' noise explains (their [`noise_term`]s).
    pub noise: f64,
    /// relMSE of Strata at equal time against the same reference, its noise removed: the error
    /// the verdict credits Strata with.
    pub strata_error: f64,
}

impl Agreement {
    /// The estimated squared bias between the renderers (relMSE less noise; may be negative from
    /// the estimates' own scatter).
    pub fn excess(&self) -> f64 {
        self.relmse - self.noise
    }

    /// The excess as a share of Strata's equal-time error.
    pub fn share(&self) -> f64 {
        self.excess() / self.strata_error
    }

    /// Whether the renderers agree well enough for the scene's verdict: the excess is at most
    /// [`DISAGREEMENT_SHARE`] of Strata's error (false when that error is not positive).
    pub fn agrees(&self) -> bool {
        self.strata_error > 0.0 && self.share() <= DISAGREEMENT_SHARE
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use sampling::rng::Rng;

    fn image(values: &[f32]) -> Image {
        Image {
            width: values.len() as u32,
            height: 1,
            data: values.iter().map(|&v| Vec3::splat(v)).collect(),
        }
    }

    #[test]
    fn the_noise_term_of_two_halves_is_their_squared_half_difference_over_the_denominator() {
        let reference = image(&[1.0, 0.0]);
        let a = image(&[1.2, 0.1]);
        let b = image(&[0.8, 0.1]);
        // Pixel 0: 0.4² / 4 / (1 + 0.01); pixel 1: 0.
        let expected = 0.04 / 1.01 / 2.0;
        let got = noise_term(&a, &b, &reference).unwrap();
        assert!((got - expected).abs() < 1e-7, "{got} against {expected}");
        assert_eq!(noise_term(&a, &a, &reference).unwrap(), 0.0);
        assert!(noise_term(&a, &image(&[1.0]), &reference).is_err());
        let mean = mean_of(&a, &b).unwrap();
        assert!((mean.data[0].x - 1.0).abs() < 1e-6 && (mean.data[1].y - 0.1).abs() < 1e-6);
    }

    /// An unbiased image against a reference with a fifth of its noise (standard deviation per
    /// half 0.02 against 0.1, around 1): relMSE less the two noise terms is near zero, and near
    /// the squared bias when the image is 10% too bright. With 4096 independent pixels each term's
    /// relative standard error is about 2%, so the tolerance (20% of the noise) is several standard
    /// errors wide; the reference's noise in relMSE's denominator adds about 3 × 0.0002 × 0.01 to
    /// the biased case, far inside it.
    #[test]
    fn relmse_less_the_noise_terms_estimates_the_squared_bias() {
        let mut rng = Rng::new(7);
        let mut noisy = |scale: f32, deviation: f32| -> Image {
            let values: Vec<f32> = (0..4096)
                .map(|_| scale + deviation * (rng.next_f32() - 0.5) * 12f32.sqrt())
                .collect();
            image(&values)
        };
        let (ra, rb) = (noisy(1.0, 0.02), noisy(1.0, 0.02));
        let reference = mean_of(&ra, &rb).unwrap();
        let reference_noise = noise_term(&ra, &rb, &reference).unwrap();
        for (scale, bias2) in [(1.0, 0.0), (1.1, 0.01 / 1.01)] {
            let (xa, xb) = (noisy(scale, 0.1), noisy(scale, 0.1));
            let x = mean_of(&xa, &xb).unwrap();
            let noise = noise_term(&xa, &xb, &reference).unwrap() + reference_noise;
            let agreement = Agreement {
                relmse: render::metrics::relmse(&x, &reference).unwrap(),
                noise,
                strata_error: 0.01,
            };
            assert!(
                (agreement.excess() - bias2).abs() < 0.2 * noise,
                "scale {scale}: excess {} against {bias2} (noise {noise})",
                agreement.excess()
            );
            assert_eq!(agreement.agrees(), bias2 == 0.0);
        }
    }

    #[test]
    fn agreement_needs_a_small_excess_and_a_positive_error() {
        let agreement = |relmse, strata_error| Agreement {
            relmse,
            noise: 1e-3,
            strata_error,
        };
        assert!(agreement(1.05e-3, 1e-3).agrees());
        assert!(!agreement(1.2e-3, 1e-3).agrees());
        assert!(!agreement(1.0e-3, 0.0).agrees());
    }
}
