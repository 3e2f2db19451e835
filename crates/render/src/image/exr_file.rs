//! OpenEXR input and output in the layout of Mitsuba 3's `hdrfilm`.

use std::path::Path;

use exr::compression::Compression;
use exr::image::Blocks;
use exr::meta::attribute::{AttributeValue, Text};
use exr::prelude::{
    Encoding, Image as ExrImage, Layer, LayerAttributes, LineOrder, ReadChannels, ReadLayers,
    SpecificChannels, WritableImage, read,
};
use glam::Vec3;

use super::{Image, ImageError};
use crate::atomic_write::write_atomically;

/// Name of the custom EXR header attribute (an `int`) holding the samples per pixel of a render.
pub const SPP_ATTRIBUTE: &str = "spp";

impl Image {
    /// Reads the first RGB(A) layer of the OpenEXR file at `path`. Half, float and integer
    /// channels are all accepted and converted to `f32`; an alpha channel is ignored. Mitsuba's
    /// `hdrfilm` output (float16 by default, or float32) reads this way.
    pub fn read_exr(path: &Path) -> Result<Self, ImageError> {
        Self::read_exr_with_spp(path).map(|(image, _)| image)
    }

    /// Reads an EXR file as [`Image::read_exr`] does, with the samples per pixel recorded in its
    /// header's [`SPP_ATTRIBUTE`] (`None` when absent, or not a non-negative `int`).
    pub fn read_exr_with_spp(path: &Path) -> Result<(Self, Option<u32>), ImageError> {
        let read_error = |reason: String| ImageError::Read {
            path: path.to_path_buf(),
            reason,
        };
        let image = read()
            .no_deep_data()
            .largest_resolution_level()
            .rgba_channels(
                |resolution, _| Image::new(resolution.width() as u32, resolution.height() as u32),
                |image: &mut Image, position, (r, g, b, _a): (f32, f32, f32, f32)| {
                    let index = position.y() * image.width as usize + position.x();
                    image.data[index] = Vec3::new(r, g, b);
                },
            )
            .first_valid_layer()
            .all_attributes()
            .from_file(path)
            .map_err(|e| read_error(e.to_string()))?;
        // EXR sizes are stored as 32-bit signed integers, so the casts above cannot truncate.
        let spp = match image
            .layer_data
            .attributes
            .other
            .get(&Text::from(SPP_ATTRIBUTE))
        {
            Some(AttributeValue::I32(spp)) => u32::try_from(*spp).ok(),
            _ => None,
        };
        Ok((image.layer_data.channel_data.pixels, spp))
    }

    /// Writes the image to `path` as OpenEXR with three float32 channels `R`, `G`, `B`, scan
    /// lines top row first (increasing y), ZIP-compressed: the layout of Mitsuba's `hdrfilm`
    /// with `component_format` float32. The write is atomic (see
    /// [`crate::atomic_write::write_atomically`]).
    pub fn write_exr(&self, path: &Path) -> Result<(), ImageError> {
        self.write_exr_attributes(path, LayerAttributes::default())
    }

    /// Writes the image as [`Image::write_exr`] does, recording `spp`, the samples per pixel
    /// each pixel's value averages, in the header as the `int` attribute [`SPP_ATTRIBUTE`] (as
    /// the files of `strata render` record it, see [`crate::film_exr`]). Counts above
    /// `i32::MAX` are an error.
    pub fn write_exr_with_spp(&self, path: &Path, spp: u32) -> Result<(), ImageError> {
        let spp = i32::try_from(spp).map_err(|_| ImageError::Write {
            path: path.to_path_buf(),
            reason: format!("{spp} samples per pixel do not fit the EXR header's int"),
        })?;
        let mut attributes = LayerAttributes::default();
        attributes
            .other
            .insert(Text::from(SPP_ATTRIBUTE), AttributeValue::I32(spp));
        self.write_exr_attributes(path, attributes)
    }

    /// Writes the image with these layer attributes (see [`Image::write_exr`]).
    fn write_exr_attributes(
        &self,
        path: &Path,
        attributes: LayerAttributes,
    ) -> Result<(), ImageError> {
        self.check_dimensions()?;
        let width = self.width as usize;
        let channels = SpecificChannels::rgb(|position: exr::math::Vec2<usize>| {
            let v = self.data[position.y() * width + position.x()];
            (v.x, v.y, v.z)
        });
        let encoding = Encoding {
            compression: Compression::ZIP16,
            blocks: Blocks::ScanLines,
            line_order: LineOrder::Increasing,
        };
        let layer = Layer::new(
            (width, self.height as usize),
            attributes,
            encoding,
            channels,
        );
        let result: Result<(), exr::error::Error> = write_atomically(path, |writer| {
            ExrImage::from_layer(layer).write().to_unbuffered(writer)
        });
        result.map_err(|e| ImageError::Write {
            path: path.to_path_buf(),
            reason: e.to_string(),
        })
    }
}

#[cfg(test)]
mod tests {
    use exr::prelude::f16;

    use super::*;

    /// A small image with distinct, non-round values in every channel of every pixel.
    fn sample_image() -> Image {
        Image::from_fn(5, 3, |x, y| {
            Vec3::new(
                x as f32 + 0.125,
                y as f32 * 3.5,
                1e-3 * (x * 7 + y) as f32 - 0.01,
            )
        })
    }

    #[test]
    fn write_then_read_round_trips_exactly() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.exr");
        let image = sample_image();
        image.write_exr(&path).unwrap();
        assert_eq!(Image::read_exr(&path).unwrap(), image);
    }

    #[test]
    fn the_sample_count_round_trips_through_the_header() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.exr");
        let image = sample_image();
        image.write_exr_with_spp(&path, 37).unwrap();
        assert_eq!(
            Image::read_exr_with_spp(&path).unwrap(),
            (image.clone(), Some(37))
        );
        let meta = exr::meta::MetaData::read_from_file(&path, false).unwrap();
        assert_eq!(
            meta.headers[0].own_attributes.other.get(&Text::from("spp")),
            Some(&AttributeValue::I32(37)),
            "an int attribute named spp, readable by any EXR tool"
        );
        image.write_exr(&path).unwrap();
        assert_eq!(Image::read_exr_with_spp(&path).unwrap().1, None);
        assert!(image.write_exr_with_spp(&path, u32::MAX).is_err());
    }

    #[test]
    fn written_file_is_float32_rgb_top_row_first() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.exr");
        sample_image().write_exr(&path).unwrap();
        let meta = exr::meta::MetaData::read_from_file(&path, false).unwrap();
        let header = &meta.headers[0];
        let names: Vec<String> = header
            .channels
            .list
            .iter()
            .map(|c| c.name.to_string())
            .collect();
        assert_eq!(names, ["B", "G", "R"], "EXR stores channels sorted by name");
        assert!(
            header
                .channels
                .list
                .iter()
                .all(|c| c.sample_type == exr::meta::attribute::SampleType::F32)
        );
        assert_eq!(header.line_order, LineOrder::Increasing);
        assert_eq!(
            (header.layer_size.width(), header.layer_size.height()),
            (5, 3)
        );
    }

    /// Mitsuba's default `hdrfilm` output: float16 RGBA. Written here with the exr crate directly.
    #[test]
    fn reads_half_float_rgba() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("half.exr");
        let channels = SpecificChannels::rgba(|p: exr::math::Vec2<usize>| {
            (
                f16::from_f32(p.x() as f32),
                f16::from_f32(0.5),
                f16::from_f32(p.y() as f32 * 0.25),
                f16::from_f32(1.0),
            )
        });
        ExrImage::from_channels((3, 2), channels)
            .write()
            .to_file(&path)
            .unwrap();
        let image = Image::read_exr(&path).unwrap();
        assert_eq!((image.width, image.height), (3, 2));
        assert_eq!(image.pixel(2, 1), Vec3::new(2.0, 0.5, 0.25));
        assert_eq!(image.pixel(0, 0), Vec3::new(0.0, 0.5, 0.0));
    }

    #[test]
    fn reading_a_missing_or_invalid_file_names_it() {
        let dir = tempfile::tempdir().unwrap();
        let missing = dir.path().join("missing.exr");
        let message = Image::read_exr(&missing).unwrap_err().to_string();
        assert!(message.contains("missing.exr"), "{message}");
        let garbage = dir.path().join("garbage.exr");
        std::fs::write(&garbage, b"not an exr").unwrap();
        let error = Image::read_exr(&garbage).unwrap_err();
        assert!(
            matches!(error, ImageError::Read { .. }) && error.to_string().contains("garbage.exr")
        );
    }

    #[test]
    fn writing_into_a_missing_directory_fails_cleanly() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("no").join("a.exr");
        let error = sample_image().write_exr(&path).unwrap_err();
        assert!(matches!(error, ImageError::Write { .. }) && error.to_string().contains("a.exr"));
        assert!(
            std::fs::read_dir(dir.path()).unwrap().next().is_none(),
            "nothing may be left behind"
        );
    }

    #[test]
    fn inconsistent_dimensions_are_an_error_and_write_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.exr");
        let mut image = sample_image();
        image.data.pop();
        assert!(matches!(
            image.write_exr(&path),
            Err(ImageError::Dimensions { len: 14, .. })
        ));
        assert!(!path.exists());
    }
}
