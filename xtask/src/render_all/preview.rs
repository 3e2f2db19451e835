//! The report's previews: linear images scaled by an exposure chosen per scene, so that a
//! scene brighter than 1 (the furnace's radiance is 2) is not clipped to white and a dim one is
//! not black.

use render::image::Image;

/// Luminance the reference's [`PERCENTILE`] pixel is shown at (linear, before sRGB encoding).
pub const TARGET_LUMINANCE: f64 = 0.9;

/// The share of the reference's pixels at or below the luminance mapped to
/// [`TARGET_LUMINANCE`]: the brightest 1% (light sources, highlights) may clip.
pub const PERCENTILE: f64 = 0.99;

/// Rec. 709 luminance of linear RGB.
fn luminance(rgb: glam::Vec3) -> f64 {
    0.2126 * f64::from(rgb.x) + 0.7152 * f64::from(rgb.y) + 0.0722 * f64::from(rgb.z)
}

/// The exposure for a scene whose reference is `reference`: [`TARGET_LUMINANCE`] over the
/// reference's [`PERCENTILE`] luminance (nearest rank, non-finite pixels left out); 1 when that
/// luminance is not positive (a black image).
pub fn exposure(reference: &Image) -> f32 {
    let mut values: Vec<f64> = reference
        .data
        .iter()
        .map(|&p| luminance(p))
        .filter(|v| v.is_finite())
        .collect();
    if values.is_empty() {
        return 1.0;
    }
    let rank = ((PERCENTILE * values.len() as f64).ceil() as usize).clamp(1, values.len()) - 1;
    let (_, &mut percentile, _) = values.select_nth_unstable_by(rank, f64::total_cmp);
    if percentile > 0.0 {
        (TARGET_LUMINANCE / percentile) as f32
    } else {
        1.0
    }
}

/// `image` with every value multiplied by `exposure`.
pub fn exposed(image: &Image, exposure: f32) -> Image {
    Image {
        data: image.data.iter().map(|&p| p * exposure).collect(),
        ..image.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use render::image::linear_to_srgb8;

    #[test]
    fn a_uniform_furnace_of_radiance_two_is_shown_grey_not_white() {
        let furnace = Image::from_fn(8, 8, |_, _| Vec3::splat(2.0));
        let e = exposure(&furnace);
        assert!((e - 0.45).abs() < 1e-6, "exposure {e}");
        let shown = exposed(&furnace, e);
        let code = linear_to_srgb8(shown.data[0].x);
        // 0.9 linear is sRGB code 243: visible, below white.
        assert_eq!(code, 243);
        // Without the exposure the furnace is clipped.
        assert_eq!(linear_to_srgb8(furnace.data[0].x), 255);
    }

    #[test]
    fn the_99th_percentile_by_nearest_rank_maps_to_the_target() {
        // Grey levels 1..=200: the 99th percentile by nearest rank is the 198th value, 198;
        // one NaN pixel is left out.
        let mut image = Image::from_fn(201, 1, |x, _| Vec3::splat(x as f32 + 1.0));
        image.data[200] = Vec3::splat(f32::NAN);
        let e = exposure(&image);
        assert!((f64::from(e) - 0.9 / 198.0).abs() < 1e-9, "exposure {e}");
        assert_eq!(exposure(&Image::from_fn(4, 4, |_, _| Vec3::ZERO)), 1.0);
    }
}
