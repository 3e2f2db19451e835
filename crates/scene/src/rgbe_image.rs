//! Reading a Radiance RGBE (`.hdr`) image, for bitmap textures and environment maps.

use crate::exr_image::RgbImage;
use glam::Vec3;
use std::io::{BufRead, Read};
use std::path::Path;

/// The RGBE file at `path` (`#?` header, `FORMAT=32-bit_rle_rgbe`, `-Y height +X width`; flat
/// or with per-channel run-length scanlines) as linear RGB, each texel its bytes times
/// 2^(e − 136) as Mitsuba reads them; or why the file cannot be read (XYZE files and other
/// orientations among the reasons).
pub(crate) fn read_rgb(path: &Path) -> Result<RgbImage, String> {
    let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    let mut reader = std::io::BufReader::new(file);
    let (width, height) = read_header(&mut reader)?;
    let mut bytes = Vec::new();
    reader.read_to_end(&mut bytes).map_err(|e| e.to_string())?;
    let texels = decode_pixels(&bytes, width, height)?;
    Ok(RgbImage {
        width: width as u32,
        height: height as u32,
        texels,
    })
}

/// The header up to its resolution line: (width, height).
fn read_header(reader: &mut impl BufRead) -> Result<(usize, usize), String> {
    let mut line = String::new();
    let mut next_line = |line: &mut String| -> Result<(), String> {
        line.clear();
        match reader.read_line(line) {
            Ok(0) => Err("the header ends before the resolution line".to_string()),
            Ok(_) => Ok(()),
            Err(e) => Err(e.to_string()),
        }
    };
    next_line(&mut line)?;
    if !line.starts_with("#?") {
        return Err("not a Radiance RGBE file (no \"#?\" header)".to_string());
    }
    let mut format = None;
    loop {
        next_line(&mut line)?;
        let text = line.trim_end();
        if let Some(value) = text.strip_prefix("FORMAT=") {
            format = Some(value.to_string());
            continue;
        }
        let tokens: Vec<&str> = text.split_whitespace().collect();
        if tokens.len() == 4 && (tokens[0].ends_with('Y') || tokens[0].ends_with('X')) {
            if tokens[0] != "-Y" || tokens[2] != "+X" {
                return Err(format!(
                    "only \"-Y height +X width\" images are supported, not \"{text}\""
                ));
            }
            let number = |s: &str| {
                s.parse::<usize>()
                    .map_err(|_| format!("bad resolution line \"{text}\""))
            };
            let (height, width) = (number(tokens[1])?, number(tokens[3])?);
            if width == 0 || height == 0 || width.checked_mul(height).is_none() {
                return Err(format!("bad resolution {width} x {height}"));
            }
            return match format.as_deref() {
                Some("32-bit_rle_rgbe") => Ok((width, height)),
                Some(other) => Err(format!(
                    "unsupported format \"{other}\" (supported: 32-bit_rle_rgbe)"
                )),
                None => Err("the header names no FORMAT".to_string()),
            };
        }
    }
}

/// The `width` × `height` texels of the pixel data `bytes`, scanline by scanline.
fn decode_pixels(bytes: &[u8], width: usize, height: usize) -> Result<Vec<Vec3>, String> {
    let short = || "the pixel data ends early".to_string();
    let mut texels = Vec::with_capacity(width * height);
    let mut at = 0;
    let run_length = (8..=0x7fff).contains(&width);
    let mut scanline = vec![0u8; 4 * width];
    for _ in 0..height {
        let start = bytes.get(at..at + 4).ok_or_else(short)?;
        if !run_length || start[0] != 2 || start[1] != 2 || start[2] & 0x80 != 0 {
            // Flat pixels from here to the end, as Mitsuba reads a file that is not encoded.
            let rest = bytes.get(at..).ok_or_else(short)?;
            let needed = width * height - texels.len();
            if rest.len() < 4 * needed {
                return Err(short());
            }
            texels.extend(rest.chunks_exact(4).take(needed).map(rgbe_to_rgb));
            return Ok(texels);
        }
        if (usize::from(start[2]) << 8 | usize::from(start[3])) != width {
            return Err("a scanline's width differs from the image's".to_string());
        }
        at += 4;
        for channel in scanline.chunks_exact_mut(width) {
            let mut filled = 0;
            while filled < width {
                let [count, value] = [
                    *bytes.get(at).ok_or_else(short)?,
                    *bytes.get(at + 1).ok_or_else(short)?,
                ];
                let (run, count) = if count > 128 {
                    (true, usize::from(count - 128))
                } else {
                    (false, usize::from(count))
                };
                if count == 0 || count > width - filled {
                    return Err("bad run-length scanline data".to_string());
                }
                if run {
                    channel[filled..filled + count].fill(value);
                    at += 2;
                } else {
                    let literal = bytes.get(at + 1..at + 1 + count).ok_or_else(short)?;
                    channel[filled..filled + count].copy_from_slice(literal);
                    at += 1 + count;
                }
                filled += count;
            }
        }
        texels.extend((0..width).map(|x| {
            rgbe_to_rgb(&[
                scanline[x],
                scanline[width + x],
                scanline[2 * width + x],
                scanline[3 * width + x],
            ])
        }));
    }
    Ok(texels)
}

/// One RGBE pixel as linear RGB: the mantissas times 2^(e − 136), black for e = 0.
fn rgbe_to_rgb(rgbe: &[u8]) -> Vec3 {
    if rgbe[3] == 0 {
        return Vec3::ZERO;
    }
    let scale = 2f32.powi(i32::from(rgbe[3]) - 136);
    Vec3::new(f32::from(rgbe[0]), f32::from(rgbe[1]), f32::from(rgbe[2])) * scale
}

#[cfg(test)]
mod tests {
    use super::*;

    fn crosscheck_file(name: &str) -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../tests/crosscheck")
            .join(name)
    }

    /// Asserts that `image`'s texels at (row, column) are the values Mitsuba 3.9.1 decoded.
    fn assert_mitsubas(image: &RgbImage, mitsuba: &[((usize, usize), [f32; 3])]) {
        for &((row, column), want) in mitsuba {
            let got = image.texels[row * image.width as usize + column];
            assert_eq!(got, Vec3::from(want), "({row}, {column})");
        }
    }

    #[test]
    fn run_length_scanlines_decode_as_mitsuba_decodes_them() {
        // sky.hdr: Mitsuba's own RGBE writing of sky.exr, 64 x 32, run-length encoded.
        let image = read_rgb(&crosscheck_file("sky.hdr")).unwrap();
        assert_eq!((image.width, image.height), (64, 32));
        assert_mitsubas(
            &image,
            &[
                ((0, 0), [0.25, 0.449_218_75, 0.898_437_5]),
                ((1, 1), [0.296_875, 0.480_468_75, 0.898_437_5]),
                ((5, 40), [0.488_281_25, 0.609_375, 0.898_437_5]),
                ((31, 63), [0.174_804_69, 0.125, 0.074_218_75]),
                ((16, 10), [0.343_75, 0.244_140_63, 0.146_484_38]),
            ],
        );
    }

    #[test]
    fn flat_pixels_decode_as_mitsuba_decodes_them() {
        // texture-small.hdr: 4 x 2, too narrow for run-length scanlines, so written flat.
        let image = read_rgb(&crosscheck_file("texture-small.hdr")).unwrap();
        assert_eq!((image.width, image.height), (4, 2));
        assert_mitsubas(
            &image,
            &[
                ((0, 0), [0.5, 1.0, 2.0]),
                ((0, 1), [100.0, 0.0, 0.0]),
                ((1, 1), [0.699_218_75, 0.796_875, 0.898_437_5]),
                ((1, 2), [12.0, 1.0, 0.0625]),
                ((1, 3), [0.298_828_13, 0.199_218_75, 0.099_609_375]),
            ],
        );
    }

    #[test]
    fn bad_files_are_errors() {
        let dir = tempfile::tempdir().unwrap();
        let write = |name: &str, bytes: &[u8]| {
            let path = dir.path().join(name);
            std::fs::write(&path, bytes).unwrap();
            match read_rgb(&path) {
                Ok(image) => panic!("{name} read as {} x {}", image.width, image.height),
                Err(e) => e,
            }
        };
        assert!(write("a.hdr", b"P6\n").contains("#?"));
        let xyze = write(
            "b.hdr",
            b"#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\n\x80\x80\x80\x80",
        );
        assert!(xyze.contains("32-bit_rle_xyze"), "{xyze}");
        let turned = write(
            "c.hdr",
            b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n+Y 1 +X 1\n\x80\x80\x80\x80",
        );
        assert!(turned.contains("-Y height +X width"), "{turned}");
        let short = write(
            "d.hdr",
            b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 2\n\x80\x80\x80\x80",
        );
        assert!(short.contains("ends early"), "{short}");
        // A run-length scanline whose run overflows its 8 texels.
        let mut bad_run =
            b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 8\n\x02\x02\x00\x08".to_vec();
        bad_run.extend([0x80 + 9, 1]);
        let overflow = write("e.hdr", &bad_run);
        assert!(overflow.contains("run-length"), "{overflow}");
    }
}
