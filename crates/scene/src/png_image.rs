//! Reading a PNG image as linear RGB, for bitmap textures.

use crate::exr_image::RgbImage;
use glam::Vec3;
use png::{BitDepth, ColorType, Transformations};
use std::path::Path;

/// The PNG file at `path` as linear RGB: 8- or 16-bit grey, grey with alpha, RGB, RGBA or
/// palette images (alpha dropped, grey copied to all three channels), each value scaled to
/// [0, 1] and, unless `raw`, decoded from sRGB as Mitsuba decodes every PNG; or the decoder's
/// reason for refusing the file.
pub(crate) fn read_rgb(path: &Path, raw: bool) -> Result<RgbImage, String> {
    let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    let mut decoder = png::Decoder::new(std::io::BufReader::new(file));
    decoder.set_transformations(Transformations::EXPAND);
    let mut reader = decoder.read_info().map_err(|e| e.to_string())?;
    let size = reader
        .output_buffer_size()
        .ok_or("the image is too large to decode")?;
    let mut bytes = vec![0; size];
    let frame = reader.next_frame(&mut bytes).map_err(|e| e.to_string())?;
    bytes.truncate(frame.buffer_size());
    let channels = match frame.color_type {
        ColorType::Grayscale => 1,
        ColorType::GrayscaleAlpha => 2,
        ColorType::Rgb => 3,
        ColorType::Rgba => 4,
        ColorType::Indexed => return Err("a palette image was not expanded".to_string()),
    };
    let values: Vec<f32> = match frame.bit_depth {
        BitDepth::Eight => bytes.iter().map(|&b| f32::from(b) / 255.0).collect(),
        BitDepth::Sixteen => bytes
            .chunks_exact(2)
            .map(|b| f32::from(u16::from_be_bytes([b[0], b[1]])) / 65535.0)
            .collect(),
        other => return Err(format!("{other:?}-bit samples were not expanded to 8 bits")),
    };
    let decode = |v: f32| if raw { v } else { srgb_to_linear(v) };
    let texels = values
        .chunks_exact(channels)
        .map(|pixel| match pixel.len() {
            1 | 2 => Vec3::splat(decode(pixel[0])),
            _ => Vec3::new(decode(pixel[0]), decode(pixel[1]), decode(pixel[2])),
        })
        .collect();
    Ok(RgbImage {
        width: frame.width,
        height: frame.height,
        texels,
    })
}

/// The sRGB transfer function inverted: an encoded value in [0, 1] to linear.
pub(crate) fn srgb_to_linear(v: f32) -> f32 {
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Writes `data` as a `width` × `height` PNG of `color` at `depth` and reads it back.
    fn round_trip(
        width: u32,
        height: u32,
        color: ColorType,
        depth: BitDepth,
        data: &[u8],
        raw: bool,
    ) -> RgbImage {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.png");
        let file = std::fs::File::create(&path).unwrap();
        let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), width, height);
        encoder.set_color(color);
        encoder.set_depth(depth);
        let mut writer = encoder.write_header().unwrap();
        writer.write_image_data(data).unwrap();
        writer.finish().unwrap();
        read_rgb(&path, raw).unwrap()
    }

    #[test]
    fn srgb_values_decode_as_mitsuba_decodes_them() {
        // Mitsuba 3.9.1 decodes sRGB 128 to 0.21586 and 255 to 1.
        let image = round_trip(
            2,
            1,
            ColorType::Rgb,
            BitDepth::Eight,
            &[128, 0, 255, 255, 10, 1],
            false,
        );
        assert_eq!((image.width, image.height), (2, 1));
        assert!(
            (image.texels[0] - Vec3::new(0.215_861, 0.0, 1.0))
                .abs()
                .max_element()
                < 1e-5
        );
        assert!((image.texels[1].x - 1.0).abs() < 1e-6);
        // 10/255 is on the linear segment: 10 / 255 / 12.92.
        assert!((image.texels[1].y - 10.0 / 255.0 / 12.92).abs() < 1e-7);
    }

    #[test]
    fn raw_images_are_not_decoded() {
        let image = round_trip(1, 1, ColorType::Rgb, BitDepth::Eight, &[128, 64, 0], true);
        assert!(
            (image.texels[0] - Vec3::new(128.0, 64.0, 0.0) / 255.0)
                .abs()
                .max_element()
                < 1e-6
        );
    }

    #[test]
    fn grey_alpha_and_sixteen_bits_are_read() {
        let grey_alpha = round_trip(
            1,
            2,
            ColorType::GrayscaleAlpha,
            BitDepth::Eight,
            &[255, 0, 0, 255],
            true,
        );
        assert_eq!(grey_alpha.texels, vec![Vec3::ONE, Vec3::ZERO]);
        // 16-bit big-endian 0x8000 = 32768 / 65535; alpha dropped.
        let rgba16 = round_trip(
            1,
            1,
            ColorType::Rgba,
            BitDepth::Sixteen,
            &[0x80, 0x00, 0xff, 0xff, 0x00, 0x00, 0x12, 0x34],
            true,
        );
        assert!(
            (rgba16.texels[0] - Vec3::new(32768.0 / 65535.0, 1.0, 0.0))
                .abs()
                .max_element()
                < 1e-7
        );
    }

    #[test]
    fn a_file_that_is_not_a_png_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.png");
        std::fs::write(&path, b"not a png").unwrap();
        assert!(read_rgb(&path, false).is_err());
        assert!(read_rgb(&dir.path().join("missing.png"), false).is_err());
    }
}
