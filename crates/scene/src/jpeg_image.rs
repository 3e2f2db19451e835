//! Reading a JPEG image as linear RGB, for bitmap textures (the `jpeg-decoder` crate).

use crate::exr_image::RgbImage;
use crate::png_image::srgb_to_linear;
use glam::Vec3;
use jpeg_decoder::{Decoder, PixelFormat};
use std::path::Path;

/// The JPEG file at `path` as linear RGB: a colour image (converted to RGB) or an 8-bit grey one
/// (copied to all three channels), each value scaled to [0, 1] and, unless `raw`, decoded from
/// sRGB as Mitsuba decodes every JPEG; or the decoder's reason for refusing the file (CMYK and
/// 16-bit grey images among them).
pub(crate) fn read_rgb(path: &Path, raw: bool) -> Result<RgbImage, String> {
    let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    let mut decoder = Decoder::new(std::io::BufReader::new(file));
    let bytes = decoder.decode().map_err(|e| e.to_string())?;
    let info = decoder.info().ok_or("the decoder gave no image size")?;
    let channels = match info.pixel_format {
        PixelFormat::L8 => 1,
        PixelFormat::RGB24 => 3,
        other => return Err(format!("unsupported pixel format {other:?}")),
    };
    let (width, height) = (u32::from(info.width), u32::from(info.height));
    if bytes.len() != width as usize * height as usize * channels {
        return Err(format!(
            "{} bytes decoded for a {width} x {height} image of {channels} channels",
            bytes.len()
        ));
    }
    let decode = |b: u8| {
        let v = f32::from(b) / 255.0;
        if raw { v } else { srgb_to_linear(v) }
    };
    let texels = bytes
        .chunks_exact(channels)
        .map(|pixel| match pixel {
            [grey] => Vec3::splat(decode(*grey)),
            _ => Vec3::new(decode(pixel[0]), decode(pixel[1]), decode(pixel[2])),
        })
        .collect();
    Ok(RgbImage {
        width,
        height,
        texels,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decodes_as_mitsuba_decodes() {
        let path =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/crosscheck/texture-photo.jpg");
        let raw = read_rgb(&path, true).unwrap();
        assert_eq!((raw.width, raw.height), (24, 16));
        // Mitsuba 3.9.1's bytes (libjpeg-turbo) at (row, column). The two decoders round
        // differently: over the whole image the bytes differ by 0.10-0.16 on average (per
        // channel) and by at most 3.
        let mitsuba = [
            ((0, 0), [54u8, 80, 141]),
            ((3, 7), [107, 104, 185]),
            ((15, 23), [224, 199, 169]),
            ((8, 12), [145, 143, 128]),
        ];
        for ((row, column), bytes) in mitsuba {
            let got = raw.texels[row * 24 + column] * 255.0;
            let want = Vec3::from(bytes.map(f32::from));
            assert!(
                (got - want).abs().max_element() <= 3.0,
                "({row}, {column}): {got} against Mitsuba's {want}"
            );
        }
        let linear = read_rgb(&path, false).unwrap();
        let expected = raw.texels[0].to_array().map(srgb_to_linear);
        assert_eq!(linear.texels[0], Vec3::from(expected));
    }

    #[test]
    fn a_file_that_is_not_a_jpeg_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.jpg");
        std::fs::write(&path, b"not a jpeg").unwrap();
        assert!(read_rgb(&path, false).is_err());
    }
}
