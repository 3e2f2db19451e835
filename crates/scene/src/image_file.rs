//! Reading an image file as linear RGB by its extension, for bitmap textures and environment
//! maps.

use crate::error::{Loc, Result};
use crate::exr_image::RgbImage;
use std::path::Path;

/// The image at `path` as linear RGB, by its extension: PNG or JPEG (decoded from sRGB unless
/// `raw`), OpenEXR or Radiance RGBE (`.hdr`, `.rgbe`; linear already). A missing file, another
/// format or an unreadable file is an error at `loc` naming the `what` (`"bitmap"`,
/// `"environment map"`) and the path.
pub(crate) fn read_linear_rgb(path: &Path, raw: bool, what: &str, loc: &Loc) -> Result<RgbImage> {
    if !path.is_file() {
        return Err(loc.error(format!("{what} \"{}\" not found", path.display())));
    }
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let image = match extension.as_deref() {
        Some("png") => crate::png_image::read_rgb(path, raw),
        Some("jpg" | "jpeg") => crate::jpeg_image::read_rgb(path, raw),
        Some("exr") => crate::exr_image::read_rgb(path),
        Some("hdr" | "rgbe") => crate::rgbe_image::read_rgb(path),
        _ => {
            return Err(loc.error(format!(
                "{what} \"{}\": only PNG, JPEG, OpenEXR and RGBE (.png, .jpg, .jpeg, .exr, .hdr, .rgbe) images are supported",
                path.display()
            )));
        }
    };
    image.map_err(|e| loc.error(format!("cannot read {what} \"{}\": {e}", path.display())))
}
