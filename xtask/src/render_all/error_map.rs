//! False-colour maps of per-pixel error: each pixel's relative squared error against the
//! reference on a logarithmic scale from 1e-4 (dark blue) to 1 (yellow), the same scale for every
//! configuration so that maps compare at a glance.

use render::image::Image;
use render::metrics::relmse_per_pixel;

/// Smallest error shown (darkest colour), relative squared error.
pub const ERROR_FLOOR: f64 = 1e-4;
/// Largest error shown (brightest colour), relative squared error.
pub const ERROR_CEILING: f64 = 1.0;

/// Viridis-like colour ramp, sRGB in [0, 1], at evenly spaced positions from 0 to 1.
const RAMP: [[f64; 3]; 5] = [
    [0.267, 0.005, 0.329],
    [0.230, 0.322, 0.546],
    [0.128, 0.567, 0.551],
    [0.369, 0.789, 0.383],
    [0.993, 0.906, 0.144],
];

/// The false-colour error map of `image` against `reference` (linear RGB, so that writing it
/// as an sRGB PNG shows the ramp's colours).
pub fn error_map(image: &Image, reference: &Image) -> Result<Image, String> {
    let errors = relmse_per_pixel(image, reference).map_err(|e| e.to_string())?;
    let mut map = Image::new(image.width, image.height);
    for (pixel, error) in map.data.iter_mut().zip(errors) {
        let position = (error.max(ERROR_FLOOR).log10() - ERROR_FLOOR.log10())
            / (ERROR_CEILING.log10() - ERROR_FLOOR.log10());
        let [r, g, b] = ramp(position.clamp(0.0, 1.0));
        *pixel = glam::Vec3::new(linear(r), linear(g), linear(b));
    }
    Ok(map)
}

/// The ramp's sRGB colour at `t` in [0, 1], interpolated linearly between stops.
fn ramp(t: f64) -> [f64; 3] {
    let scaled = t * (RAMP.len() - 1) as f64;
    let i = (scaled as usize).min(RAMP.len() - 2);
    let f = scaled - i as f64;
    std::array::from_fn(|c| RAMP[i][c] * (1.0 - f) + RAMP[i + 1][c] * f)
}

/// sRGB-encoded value to linear (the inverse of the PNG writer's encoding).
fn linear(srgb: f64) -> f32 {
    (if srgb <= 0.04045 {
        srgb / 12.92
    } else {
        ((srgb + 0.055) / 1.055).powf(2.4)
    }) as f32
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn exact_pixels_are_darkest_and_errors_of_one_or_more_brightest() {
        let reference = Image::from_fn(3, 1, |_, _| Vec3::splat(1.0));
        // Relative squared errors 0, 0.01 (half-way on the log scale) and 4.
        let image = Image {
            width: 3,
            height: 1,
            data: vec![
                Vec3::ONE,
                Vec3::splat(1.0 + 0.1 * 1.01_f32.sqrt()),
                Vec3::splat(3.0),
            ],
        };
        let map = error_map(&image, &reference).unwrap();
        let srgb = |p: Vec3| {
            p.to_array().map(|c| {
                let c = f64::from(c);
                if c <= 0.0031308 {
                    12.92 * c
                } else {
                    1.055 * c.powf(1.0 / 2.4) - 0.055
                }
            })
        };
        let close = |a: [f64; 3], b: [f64; 3]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-3);
        assert!(close(srgb(map.data[0]), RAMP[0]));
        assert!(close(srgb(map.data[1]), RAMP[2]));
        assert!(close(srgb(map.data[2]), RAMP[4]));
    }
}
