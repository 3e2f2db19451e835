//! Reading an OpenEXR image's RGB channels, for environment maps.

use exr::prelude::{ReadChannels, ReadLayers, read};
use glam::Vec3;
use std::path::Path;

/// An RGB image as linear floats, row-major from the top row.
pub(crate) struct RgbImage {
    /// Pixels per row.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// The pixels, `width × height` of them.
    pub texels: Vec<Vec3>,
}

/// The first layer of the OpenEXR file at `path` with R, G and B channels (half, float or
/// integer, converted to `f32`; alpha ignored), or the decoder's reason for refusing it.
pub(crate) fn read_rgb(path: &Path) -> Result<RgbImage, String> {
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .rgba_channels(
            |resolution, _| RgbImage {
                width: resolution.width() as u32,
                height: resolution.height() as u32,
                texels: vec![Vec3::ZERO; resolution.width() * resolution.height()],
            },
            |image: &mut RgbImage, position, (r, g, b, _a): (f32, f32, f32, f32)| {
                let index = position.y() * image.width as usize + position.x();
                image.texels[index] = Vec3::new(r, g, b);
            },
        )
        .first_valid_layer()
        .all_attributes()
        .from_file(path)
        .map_err(|e| e.to_string())?;
    Ok(image.layer_data.channel_data.pixels)
}
