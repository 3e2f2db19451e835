//! Spectra given as wavelength–value pairs (`<spectrum value="400:0.5, 500:0.7"/>`) turned into
//! linear sRGB the way Mitsuba 3's RGB variants do (`spectrum_list_to_srgb`): the piecewise-linear
//! spectrum times the CIE 1931 colour-matching functions (and, for everything but emission, times
//! illuminant D65) integrated over 360–830 nm by 1000 equally spaced samples, then XYZ to sRGB.
//!
//! Normalisation: a spectrum of constant value 1 has luminance Y = 1; for reflectances, a
//! constant 1 under D65 has Y = 1 (so it is white, (1, 1, 1) up to the tables' rounding).
//! Mitsuba's D65 constant is 0.11% off this, so its reflectance spectra come out 0.11% darker.

use std::sync::OnceLock;

use glam::DVec3;

use crate::cie_tables::{CIE_1931_XYZ, CIE_MAX_NM, CIE_MIN_NM, CIE_SAMPLES, D65};

/// Number of wavelengths the integral samples, equally spaced from 360 to 830 nm inclusive.
const STEPS: usize = 1000;

/// The linear-sRGB primaries' matrix applied to CIE XYZ (rows R, G, B; D65 white).
const XYZ_TO_SRGB: [[f64; 3]; 3] = [
    [3.240479, -1.537150, -0.498535],
    [-0.969256, 1.875991, 0.041556],
    [0.055648, -0.204043, 1.057311],
];

/// Linear sRGB of the CIE XYZ colour `xyz`.
pub(crate) fn xyz_to_srgb(xyz: DVec3) -> DVec3 {
    let row = |r: [f64; 3]| r[0] * xyz.x + r[1] * xyz.y + r[2] * xyz.z;
    DVec3::new(
        row(XYZ_TO_SRGB[0]),
        row(XYZ_TO_SRGB[1]),
        row(XYZ_TO_SRGB[2]),
    )
}

/// What a spectrum describes, which decides how it is weighted and clamped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum SpectrumRole {
    /// A reflectance: weighted by D65, clamped to [0, 1] per channel.
    Reflectance,
    /// An unbounded quantity (a conductor's `eta`, `k`): weighted by D65, negatives clamped to 0.
    Unbounded,
    /// Emitted radiance or intensity: not weighted by an illuminant, negatives clamped to 0.
    Emission,
}

/// The wavelength (nm) of the integral's sample `i`.
fn wavelength(i: usize) -> f64 {
    CIE_MIN_NM + i as f64 / (STEPS - 1) as f64 * (CIE_MAX_NM - CIE_MIN_NM)
}

/// Linear interpolation of a 5-nm table at `nm` (inside the tables' range).
fn interpolate<T: Copy>(table: &[T; CIE_SAMPLES], nm: f64, lerp: impl Fn(T, T, f64) -> T) -> T {
    let t = (nm - CIE_MIN_NM) * ((CIE_SAMPLES - 1) as f64 / (CIE_MAX_NM - CIE_MIN_NM));
    let i = (t.max(0.0) as usize).min(CIE_SAMPLES - 2);
    lerp(table[i], table[i + 1], t - i as f64)
}

/// x̄, ȳ, z̄ at `nm`.
fn cie_xyz(nm: f64) -> DVec3 {
    let [x, y, z] = interpolate(&CIE_1931_XYZ, nm, |a, b, s| {
        [0, 1, 2].map(|c| a[c] + (b[c] - a[c]) * s)
    });
    DVec3::new(x, y, z)
}

/// D65's relative power at `nm`.
fn d65(nm: f64) -> f64 {
    interpolate(&D65, nm, |a, b, s| a + (b - a) * s)
}

/// The sums of ȳ and of ȳ · D65 over the integral's samples, which normalise it.
fn normalisation() -> (f64, f64) {
    static SUMS: OnceLock<(f64, f64)> = OnceLock::new();
    *SUMS.get_or_init(|| {
        (0..STEPS).map(wavelength).fold((0.0, 0.0), |(y, yd), nm| {
            let bar_y = cie_xyz(nm).y;
            (y + bar_y, yd + bar_y * d65(nm))
        })
    })
}

/// Linear sRGB of the piecewise-linear spectrum through `pairs` (wavelength in nm, value; at
/// least two, wavelengths increasing), zero outside its first and last wavelength, for `role`.
/// A colour outside the role's range (a spectral colour outside sRGB's gamut) is clamped into it,
/// as Mitsuba does.
pub(crate) fn spectrum_to_srgb(pairs: &[(f64, f64)], role: SpectrumRole) -> DVec3 {
    debug_assert!(pairs.len() >= 2);
    let (first, last) = (pairs[0].0, pairs[pairs.len() - 1].0);
    let with_d65 = role != SpectrumRole::Emission;
    let mut xyz = DVec3::ZERO;
    for nm in (0..STEPS).map(wavelength) {
        if nm < first || nm > last {
            continue;
        }
        let i = pairs[..pairs.len() - 1]
            .partition_point(|&(w, _)| w <= nm)
            .max(1)
            - 1;
        let ((w0, v0), (w1, v1)) = (pairs[i], pairs[i + 1]);
        let value = v0 + (v1 - v0) * (nm - w0) / (w1 - w0);
        let weight = if with_d65 { d65(nm) } else { 1.0 };
        xyz += cie_xyz(nm) * (value * weight);
    }
    let (sum_y, sum_y_d65) = normalisation();
    xyz /= if with_d65 { sum_y_d65 } else { sum_y };
    let rgb = xyz_to_srgb(xyz);
    match role {
        SpectrumRole::Reflectance => rgb.clamp(DVec3::ZERO, DVec3::ONE),
        SpectrumRole::Unbounded | SpectrumRole::Emission => rgb.max(DVec3::ZERO),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALL_VISIBLE: [(f64, f64); 2] = [(360.0, 1.0), (830.0, 1.0)];

    #[test]
    fn a_constant_reflectance_is_grey() {
        for level in [1.0, 0.5, 0.1] {
            let pairs = ALL_VISIBLE.map(|(w, v)| (w, v * level));
            let rgb = spectrum_to_srgb(&pairs, SpectrumRole::Reflectance);
            // sRGB's white is D65's chromaticity, which the matrix maps to (1, 1, 1) within
            // the rounding of its published coefficients and of the tables.
            assert!(
                (rgb - DVec3::splat(level)).abs().max_element() < 2e-3 * level,
                "level {level}: {rgb}"
            );
        }
    }

    /// A constant emission spectrum is the equal-energy white, as Mitsuba's uniform emission
    /// `<spectrum value="v"/>` gives it: `v × xyz_to_srgb(1, 1, 1)` (purplish in sRGB).
    #[test]
    fn a_constant_emission_is_equal_energy_white() {
        let rgb = spectrum_to_srgb(&ALL_VISIBLE.map(|(w, _)| (w, 3.0)), SpectrumRole::Emission);
        let expected = 3.0 * xyz_to_srgb(DVec3::ONE).max(DVec3::ZERO);
        let relative =
            ((rgb - expected).abs() / expected.abs().max(DVec3::splat(1e-3))).max_element();
        assert!(relative < 5e-3, "{rgb} against {expected}");
    }

    #[test]
    fn extra_points_on_the_same_lines_change_nothing_and_values_scale_linearly() {
        let coarse = [(400.0, 0.2), (600.0, 0.6), (700.0, 0.1)];
        let fine = [
            (400.0, 0.2),
            (500.0, 0.4),
            (600.0, 0.6),
            (650.0, 0.35),
            (700.0, 0.1),
        ];
        for role in [SpectrumRole::Reflectance, SpectrumRole::Emission] {
            let a = spectrum_to_srgb(&coarse, role);
            let b = spectrum_to_srgb(&fine, role);
            assert!(
                (a - b).abs().max_element() < 1e-12,
                "{role:?}: {a} against {b}"
            );
        }
        let doubled = coarse.map(|(w, v)| (w, 2.0 * v));
        let a = spectrum_to_srgb(&coarse, SpectrumRole::Emission);
        let b = spectrum_to_srgb(&doubled, SpectrumRole::Emission);
        assert!(
            (2.0 * a - b).abs().max_element() < 1e-12,
            "{a} doubled is not {b}"
        );
    }

    #[test]
    fn hues_land_where_the_eye_puts_them_and_out_of_gamut_colours_clamp() {
        let narrow = |centre: f64| [(centre - 10.0, 0.0), (centre, 1.0), (centre + 10.0, 0.0)];
        let red = spectrum_to_srgb(&narrow(620.0), SpectrumRole::Emission);
        let green = spectrum_to_srgb(&narrow(530.0), SpectrumRole::Emission);
        let blue = spectrum_to_srgb(&narrow(450.0), SpectrumRole::Emission);
        assert!(red.x > red.y && red.x > red.z, "{red}");
        assert!(green.y > green.x && green.y > green.z, "{green}");
        assert!(blue.z > blue.x && blue.z > blue.y, "{blue}");
        // A spectral green is outside sRGB: its red would be negative, and is clamped to 0.
        let rgb = spectrum_to_srgb(&narrow(520.0), SpectrumRole::Reflectance);
        assert!(
            rgb.x == 0.0 && rgb.min_element() >= 0.0 && rgb.max_element() <= 1.0,
            "{rgb}"
        );
    }

    #[test]
    fn light_outside_360_to_830_nm_is_invisible() {
        let rgb = spectrum_to_srgb(&[(200.0, 5.0), (355.0, 5.0)], SpectrumRole::Emission);
        assert_eq!(rgb, DVec3::ZERO);
    }
}
