//! 8-bit sRGB PNG output for previews.

use std::path::Path;

use glam::Vec3;

use super::{Image, ImageError};
use crate::atomic_write::write_atomically;

/// Encodes a linear value with the sRGB transfer function (IEC 61966-2-1) into 8 bits:
/// clamped to `[0, 1]` and rounded to the nearest code. NaN maps to 0.
pub fn linear_to_srgb8(linear: f32) -> u8 {
    let v = if linear.is_nan() {
        0.0
    } else {
        linear.clamp(0.0, 1.0)
    };
    let encoded = if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    };
    (encoded * 255.0).round().clamp(0.0, 255.0) as u8
}

impl Image {
    /// Writes the image to `path` as an 8-bit RGB PNG tagged sRGB: each linear channel is
    /// clamped to `[0, 1]` and sRGB-encoded (no tone mapping, no exposure). Atomic (see
    /// [`crate::atomic_write::write_atomically`]).
    pub fn write_png(&self, path: &Path) -> Result<(), ImageError> {
        self.write_png_with_exposure(path, 0.0)
    }

    /// [`write_png`](Self::write_png) of the image scaled by `2^stops` (its exposure in photographic
    /// stops): each channel is `linear_to_srgb8(linear × 2^stops)`. At 0 stops the scale is
    /// exactly 1. `stops` should be finite and small enough for `2^stops` to be a finite,
    /// non-zero `f32` (the command line allows ±[`crate::cli::MAX_EXPOSURE_STOPS`]).
    pub fn write_png_with_exposure(&self, path: &Path, stops: f32) -> Result<(), ImageError> {
        self.check_dimensions()?;
        let scale = stops.exp2();
        let bytes: Vec<u8> = self
            .data
            .iter()
            .flat_map(|v: &Vec3| (*v * scale).to_array().map(linear_to_srgb8))
            .collect();
        let result: Result<(), png::EncodingError> = write_atomically(path, |writer| {
            let mut encoder = png::Encoder::new(writer, self.width, self.height);
            encoder.set_color(png::ColorType::Rgb);
            encoder.set_depth(png::BitDepth::Eight);
            encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
            let mut png_writer = encoder.write_header()?;
            png_writer.write_image_data(&bytes)?;
            png_writer.finish()
        });
        result.map_err(|e| ImageError::Write {
            path: path.to_path_buf(),
            reason: e.to_string(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_encoding_matches_the_standard() {
        assert_eq!(linear_to_srgb8(0.0), 0);
        assert_eq!(linear_to_srgb8(1.0), 255);
        assert_eq!(linear_to_srgb8(7.0), 255);
        assert_eq!(linear_to_srgb8(-1.0), 0);
        assert_eq!(linear_to_srgb8(f32::NAN), 0);
        // 0.5 linear is 0.7354 encoded: 187.5 → 188. 0.18 linear is 0.4614: 117.7 → 118.
        assert_eq!(linear_to_srgb8(0.5), 188);
        assert_eq!(linear_to_srgb8(0.18), 118);
        // The linear toe: 0.002 · 12.92 · 255 = 6.59 → 7.
        assert_eq!(linear_to_srgb8(0.002), 7);
    }

    #[test]
    fn png_holds_the_encoded_pixels_top_row_first() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.png");
        let image = Image::from_fn(2, 2, |x, y| Vec3::new(x as f32, y as f32, 0.5));
        image.write_png(&path).unwrap();
        let decoder =
            png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&path).unwrap()));
        let mut reader = decoder.read_info().unwrap();
        let mut buffer = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buffer).unwrap();
        assert_eq!(
            (info.width, info.height, info.color_type),
            (2, 2, png::ColorType::Rgb)
        );
        assert_eq!(
            &buffer[..info.buffer_size()],
            [0, 0, 188, 255, 0, 188, 0, 255, 188, 255, 255, 188]
        );
        assert!(reader.info().srgb.is_some(), "the file is tagged sRGB");
    }

    /// The 8-bit codes of the PNG at `path`.
    fn png_bytes(path: &Path) -> Vec<u8> {
        let decoder =
            png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
        let mut reader = decoder.read_info().unwrap();
        let mut buffer = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buffer).unwrap();
        buffer.truncate(info.buffer_size());
        buffer
    }

    #[test]
    fn exposure_scales_the_linear_values_by_powers_of_two() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.png");
        let image = Image::from_fn(2, 1, |x, _| Vec3::new(0.05, 0.1, 0.3) * (x + 1) as f32);
        let codes = |stops: f32| {
            image.write_png_with_exposure(&path, stops).unwrap();
            png_bytes(&path)
        };
        image.write_png(&path).unwrap();
        assert_eq!(png_bytes(&path), codes(0.0), "write_png is exposure 0");
        // 0.05, 0.1, 0.3, 0.1, 0.2, 0.6 doubled and quartered, encoded by hand.
        let expect = |values: [f32; 6]| values.map(linear_to_srgb8).to_vec();
        assert_eq!(codes(1.0), expect([0.1, 0.2, 0.6, 0.2, 0.4, 1.2]));
        assert_eq!(
            codes(-2.0),
            expect([0.0125, 0.025, 0.075, 0.025, 0.05, 0.15])
        );
        assert_ne!(codes(1.0), codes(0.0));
    }

    #[test]
    fn png_into_a_missing_directory_fails_cleanly() {
        let dir = tempfile::tempdir().unwrap();
        let error = Image::new(1, 1)
            .write_png(&dir.path().join("no/a.png"))
            .unwrap_err();
        assert!(matches!(error, ImageError::Write { .. }));
        assert!(std::fs::read_dir(dir.path()).unwrap().next().is_none());
    }
}
