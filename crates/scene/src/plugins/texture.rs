//! `<texture>`: Mitsuba's `checkerboard` and `bitmap`, as the reflectance of a diffuse or
//! coated BSDF.

use std::path::Path;
use std::sync::Arc;

use super::unknown_type;
use crate::error::Result;
use crate::params::{ColorKind, Params};
use crate::xml::tree::ObjectNode;
use glam::{Affine2, Vec2, Vec3};
use materials::{BitmapTexture, TextureFilter, TextureWrap};

/// The texture plugins this loader understands.
const SUPPORTED: [&str; 2] = ["checkerboard", "bitmap"];

/// A `<texture>` as Strata reads it.
pub(crate) enum TextureDesc {
    /// Mitsuba's `checkerboard`.
    Checkerboard {
        /// The colour of the even squares.
        color0: Vec3,
        /// The colour of the odd squares.
        color1: Vec3,
        /// `to_uv` as two rows: u' = row 0 · (u, v, 1), v' = row 1 · (u, v, 1).
        to_uv: [[f32; 3]; 2],
    },
    /// Mitsuba's `bitmap`, loaded.
    Bitmap(Arc<BitmapTexture>),
}

/// The 2D affine map that the rows of a `to_uv` give (see [`TextureDesc::Checkerboard`]).
pub(crate) fn affine_to_uv(rows: &[[f32; 3]; 2]) -> Affine2 {
    Affine2::from_cols(
        Vec2::new(rows[0][0], rows[1][0]),
        Vec2::new(rows[0][1], rows[1][1]),
        Vec2::new(rows[0][2], rows[1][2]),
    )
}

/// Reads a `<texture>` element; an unknown plugin is an error naming the element.
pub(crate) fn texture(node: &ObjectNode) -> Result<TextureDesc> {
    match node.plugin.as_str() {
        "checkerboard" => checkerboard(node),
        "bitmap" => bitmap(node),
        _ => Err(unknown_type(node, &SUPPORTED)),
    }
}

/// `checkerboard`: `color0` (default 0.4), `color1` (default 0.2) and `to_uv`.
fn checkerboard(node: &ObjectNode) -> Result<TextureDesc> {
    super::no_children(node)?;
    let mut params = Params::new(node);
    let color0 = params
        .color("color0", ColorKind::Reflectance, 0.4)?
        .as_vec3();
    let color1 = params
        .color("color1", ColorKind::Reflectance, 0.2)?
        .as_vec3();
    let to_uv = to_uv_rows(&mut params)?;
    params.finish()?;
    Ok(TextureDesc::Checkerboard {
        color0,
        color1,
        to_uv,
    })
}

/// `bitmap`: a PNG or JPEG (decoded from sRGB unless `raw`), OpenEXR or RGBE image named by
/// `filename`
/// (relative to the scene file), with `filter_type`, `wrap_mode` and `to_uv`. Mitsuba's `format`
/// (storage precision) and `accel` (CUDA hardware lookups) are accepted without effect.
fn bitmap(node: &ObjectNode) -> Result<TextureDesc> {
    super::no_children(node)?;
    let mut params = Params::new(node);
    if params.has("bitmap") || params.has("data") {
        return Err(node
            .loc
            .error("a bitmap texture must name its image by \"filename\""));
    }
    let (filename, loc) = params
        .string("filename")?
        .ok_or_else(|| node.loc.error("missing required parameter \"filename\""))?;
    let raw = params.boolean_or("raw", false)?;
    let filter = match params.string("filter_type")? {
        None | Some(("bilinear", _)) => TextureFilter::Bilinear,
        Some(("nearest", _)) => TextureFilter::Nearest,
        Some((other, loc)) => {
            return Err(loc.error(format!(
                "unknown filter_type \"{other}\" (supported: bilinear, nearest)"
            )));
        }
    };
    let wrap = match params.string("wrap_mode")? {
        None | Some(("repeat", _)) => TextureWrap::Repeat,
        Some(("mirror", _)) => TextureWrap::Mirror,
        Some(("clamp", _)) => TextureWrap::Clamp,
        Some((other, loc)) => {
            return Err(loc.error(format!(
                "unknown wrap_mode \"{other}\" (supported: repeat, mirror, clamp)"
            )));
        }
    };
    match params.string("format")? {
        None | Some(("auto" | "variant" | "float16" | "fp16" | "uint8", _)) => {}
        Some((other, loc)) => {
            return Err(loc.error(format!(
                "unknown format \"{other}\" (supported: auto, variant, float16, uint8)"
            )));
        }
    }
    params.boolean_or("accel", true)?;
    let to_uv = affine_to_uv(&to_uv_rows(&mut params)?);
    params.finish()?;
    let dir = loc.file.parent().unwrap_or(Path::new(""));
    let path = dir.join(filename);
    let image = crate::image_file::read_linear_rgb(&path, raw, "bitmap", loc)?;
    let texture = BitmapTexture::new(
        image.width as usize,
        image.height as usize,
        image.texels,
        filter,
        wrap,
        to_uv,
    )
    .map_err(|e| loc.error(format!("bitmap \"{}\": {e}", path.display())))?;
    Ok(TextureDesc::Bitmap(Arc::new(texture)))
}

/// Mitsuba's `to_uv` (default identity): the 2D affine part of the 4 × 4 transform, as rows.
fn to_uv_rows(params: &mut Params) -> Result<[[f32; 3]; 2]> {
    let m = params.transform("to_uv")?.unwrap_or(glam::DMat4::IDENTITY);
    Ok([
        [m.x_axis.x, m.y_axis.x, m.w_axis.x].map(|v| v as f32),
        [m.x_axis.y, m.y_axis.y, m.w_axis.y].map(|v| v as f32),
    ])
}
