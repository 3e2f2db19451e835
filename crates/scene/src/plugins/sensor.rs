//! `<sensor>` (perspective, thinlens) with its `<film>`, `<rfilter>` and `<sampler>`.

use glam::{DMat3, DMat4};

use super::{unexpected_child, unknown_type};
use crate::desc::{FilmDesc, FilterDesc, FovAxis, SamplerDesc, SensorDesc, ThinLensDesc};
use crate::error::Result;
use crate::limits::{MAX_FILM_PIXELS, MAX_LANCZOS_LOBES, MAX_SAMPLE_COUNT};
use crate::params::{Params, Placement};
use crate::xml::tree::{Child, ObjectNode};
use sampling::SamplerKind;

/// Largest accepted image side, pixels.
const MAX_SIDE: i64 = 1 << 16;

/// A sensor together with the film and sampler it holds.
pub(crate) struct Camera {
    pub sensor: SensorDesc,
    pub film: FilmDesc,
    pub sampler: SamplerDesc,
}

/// Interprets a `<sensor>` element; a missing film or sampler takes Mitsuba's defaults.
pub(crate) fn sensor(node: &ObjectNode) -> Result<Camera> {
    let (thin_lens, orthographic) = match node.plugin.as_str() {
        "perspective" => (false, false),
        "thinlens" => (true, false),
        "orthographic" => (false, true),
        _ => {
            return Err(unknown_type(
                node,
                &["perspective", "thinlens", "orthographic"],
            ));
        }
    };
    let mut film = None;
    let mut sampler = None;
    for child in &node.children {
        match child {
            Child::Object(object) if object.tag == "film" && film.is_none() => {
                film = Some(film_desc(object)?);
            }
            Child::Object(object) if object.tag == "sampler" && sampler.is_none() => {
                sampler = Some(sampler_desc(object)?);
            }
            _ => {
                return Err(unexpected_child(
                    node,
                    child,
                    "one <film> and one <sampler>",
                ));
            }
        }
    }

    let mut params = Params::new(node);
    // Times keep double precision: a shutter of 1e-9 may open at any time.
    let shutter = [
        finite(&mut params, "shutter_open", 0.0)?,
        finite(&mut params, "shutter_close", 0.0)?,
    ];
    if shutter[0] > shutter[1] {
        return Err(params
            .loc_of("shutter_close")
            .error("shutter_close must not come before shutter_open"));
    }
    // A moving camera is placed where it is when the shutter opens, its motion kept beside.
    let (to_world, animation) = match params.placement("to_world")? {
        None => (DMat4::IDENTITY, None),
        Some(Placement::Fixed(m)) => (m, None),
        Some(Placement::Animated(a)) => (a.at(shutter[0]), Some(a)),
    };
    let keyframes: Vec<DMat4> = match &animation {
        Some(a) => a.keyframes().map(|(_, m)| m).collect(),
        None => vec![to_world],
    };
    for m in &keyframes {
        // An orthographic camera's to_world may scale its viewing region, as Mitsuba's may.
        if orthographic && !(m.is_finite() && DMat3::from_mat4(*m).determinant() != 0.0) {
            return Err(params
                .loc_of("to_world")
                .error("the camera's to_world must be finite and invertible"));
        }
        if !orthographic && !is_rigid(m) {
            return Err(params.loc_of("to_world").error(
                "the camera's to_world must not scale or shear (Mitsuba forbids it); use rotations, translations and lookat",
            ));
        }
    }
    let position = to_world.w_axis.truncate();
    let motion = animation.map(|a| a.translated(-position));
    let (fov_deg, fov_axis) = if orthographic {
        (90.0, FovAxis::X)
    } else {
        field_of_view(&mut params)?
    };
    let near_clip = params.float_or("near_clip", 1e-2)?;
    let far_clip = params.float_or("far_clip", 1e4)?;
    if near_clip <= 0.0 {
        return Err(params
            .loc_of("near_clip")
            .error("near_clip must be positive"));
    }
    if far_clip <= near_clip {
        return Err(params
            .loc_of("far_clip")
            .error("far_clip must be larger than near_clip"));
    }
    // Mitsuba reads focus_distance for every projective camera; a pinhole ignores it.
    let focus_distance = if orthographic {
        far_clip
    } else {
        params.float_or("focus_distance", far_clip)?
    };
    if focus_distance <= 0.0 {
        return Err(params
            .loc_of("focus_distance")
            .error("focus_distance must be positive"));
    }
    // Mitsuba's perspective sensor takes a principal point offset; its thinlens does not.
    let principal_point_offset = if thin_lens || orthographic {
        [0.0, 0.0]
    } else {
        [
            finite(&mut params, "principal_point_offset_x", 0.0)? as f32,
            finite(&mut params, "principal_point_offset_y", 0.0)? as f32,
        ]
    };
    let lens = if thin_lens {
        let aperture_radius = params
            .float("aperture_radius")?
            .ok_or_else(|| node.loc.error("thinlens needs an \"aperture_radius\""))?;
        if aperture_radius < 0.0 {
            return Err(params
                .loc_of("aperture_radius")
                .error("aperture_radius must not be negative"));
        }
        Some(ThinLensDesc {
            aperture_radius: aperture_radius as f32,
            focus_distance: focus_distance as f32,
        })
    } else {
        None
    };
    params.finish()?;
    Ok(Camera {
        sensor: SensorDesc {
            to_world: DMat4::from_cols(
                to_world.x_axis,
                to_world.y_axis,
                to_world.z_axis,
                glam::DVec4::W,
            )
            .as_mat4(),
            position,
            fov_deg: fov_deg as f32,
            fov_axis,
            near_clip: near_clip as f32,
            far_clip: far_clip as f32,
            lens,
            principal_point_offset,
            orthographic,
            shutter,
            motion,
        },
        film: match film {
            Some(film) => film,
            None => default_film(),
        },
        sampler: sampler.unwrap_or(SamplerDesc {
            kind: None,
            sample_count: 4,
            mitsuba_sample_count: 4,
            seed: 0,
        }),
    })
}

/// True when the linear part is orthonormal within Mitsuba's tolerance (`has_scale` is false).
fn is_rigid(m: &DMat4) -> bool {
    let linear = DMat3::from_mat4(*m);
    let gram = linear.transpose() * linear;
    m.is_finite()
        && (gram - DMat3::IDENTITY)
            .to_cols_array()
            .iter()
            .all(|d| d.abs() <= 1e-3)
}

/// `fov` with `fov_axis`, or the diagonal field of view of `focal_length` (default 50 mm) on
/// 36×24 mm film, as Mitsuba's `parse_fov`.
fn field_of_view(params: &mut Params) -> Result<(f64, FovAxis)> {
    let fov = params.float("fov")?;
    let focal_length = params.string("focal_length")?;
    let axis = params.string("fov_axis")?;
    let (fov, axis) = match (fov, focal_length) {
        (Some(_), Some((_, loc))) => {
            return Err(loc.error("give either \"fov\" or \"focal_length\", not both"));
        }
        (Some(fov), None) => {
            let axis = match axis {
                None => FovAxis::X,
                Some((name, loc)) => match name.to_ascii_lowercase().as_str() {
                    "x" => FovAxis::X,
                    "y" => FovAxis::Y,
                    "diagonal" => FovAxis::Diagonal,
                    "smaller" => FovAxis::Smaller,
                    "larger" => FovAxis::Larger,
                    _ => {
                        return Err(loc.error(format!(
                            "unknown fov_axis \"{name}\" (supported: x, y, diagonal, smaller, larger)"
                        )));
                    }
                },
            };
            (fov, axis)
        }
        (None, focal_length) => {
            if let Some((_, loc)) = axis {
                return Err(loc.error("\"fov_axis\" only applies together with \"fov\""));
            }
            let millimetres = match focal_length {
                None => 50.0,
                Some((text, loc)) => {
                    let number = text.trim().strip_suffix("mm").unwrap_or(text.trim());
                    match number.trim().parse::<f64>() {
                        Ok(v) if v.is_finite() && v > 0.0 => v,
                        _ => {
                            return Err(loc.error(format!(
                                "could not parse focal_length \"{text}\" (expected e.g. \"50mm\")"
                            )));
                        }
                    }
                }
            };
            let diagonal_mm = (36.0f64 * 36.0 + 24.0 * 24.0).sqrt();
            let fov = 2.0 * (diagonal_mm / (2.0 * millimetres)).atan().to_degrees();
            (fov, FovAxis::Diagonal)
        }
    };
    if !(fov > 0.0 && fov < 180.0) {
        return Err(params.loc_of("fov").error(format!(
            "the field of view must lie strictly between 0 and 180 degrees, got {fov}"
        )));
    }
    Ok((fov, axis))
}

/// Mitsuba's film when a sensor has none: 768×576 with a gaussian filter.
fn default_film() -> FilmDesc {
    FilmDesc {
        width: 768,
        height: 576,
        full_size: [768, 576],
        crop_offset: [0, 0],
        filter: FilterDesc::Gaussian { stddev: 0.5 },
    }
}

/// Interprets a `<film>` element.
fn film_desc(node: &ObjectNode) -> Result<FilmDesc> {
    if node.plugin != "hdrfilm" {
        return Err(unknown_type(node, &["hdrfilm"]));
    }
    let mut filter = None;
    for child in &node.children {
        match child {
            Child::Object(object) if object.tag == "rfilter" && filter.is_none() => {
                filter = Some(filter_desc(object)?);
            }
            _ => return Err(unexpected_child(node, child, "one <rfilter>")),
        }
    }
    let mut params = Params::new(node);
    let width = params.integer_in("width", 768, 1, MAX_SIDE)? as u32;
    let height = params.integer_in("height", 576, 1, MAX_SIDE)? as u32;
    if u64::from(width) * u64::from(height) > MAX_FILM_PIXELS {
        return Err(node.loc.error(format!(
            "{width}x{height} pixels is more than the supported {MAX_FILM_PIXELS}"
        )));
    }
    // Output encodings that do not change the rendered values: Strata always writes float32 RGB.
    for (name, accepted) in [
        ("pixel_format", &["rgb", "rgba"][..]),
        ("component_format", &["float16", "float32"][..]),
        ("file_format", &["openexr", "exr"][..]),
    ] {
        if let Some((value, loc)) = params.string(name)?
            && !accepted.contains(&value.to_ascii_lowercase().as_str())
        {
            return Err(loc.error(format!(
                "unsupported {name} \"{value}\" (supported: {})",
                accepted.join(", ")
            )));
        }
    }
    if params.boolean_or("sample_border", false)? {
        return Err(params
            .loc_of("sample_border")
            .error("sample_border=\"true\" is not supported"));
    }
    params.ignore("banner");
    let crop_offset = [
        params.integer_in("crop_offset_x", 0, 0, i64::from(width) - 1)? as u32,
        params.integer_in("crop_offset_y", 0, 0, i64::from(height) - 1)? as u32,
    ];
    let crop_size = [
        params.integer_in("crop_width", i64::from(width - crop_offset[0]), 1, MAX_SIDE)? as u32,
        params.integer_in(
            "crop_height",
            i64::from(height - crop_offset[1]),
            1,
            MAX_SIDE,
        )? as u32,
    ];
    for (axis, (offset, size, full)) in [
        ("x", (crop_offset[0], crop_size[0], width)),
        ("y", (crop_offset[1], crop_size[1], height)),
    ] {
        if u64::from(offset) + u64::from(size) > u64::from(full) {
            let name = if axis == "x" {
                "crop_width"
            } else {
                "crop_height"
            };
            let loc = if params.has(name) {
                params.loc_of(name)
            } else {
                &node.loc
            };
            return Err(loc.error(format!(
                "the crop window ({offset} + {size} pixels along {axis}) does not fit the film's {full}"
            )));
        }
    }
    params.finish()?;
    Ok(FilmDesc {
        width: crop_size[0],
        height: crop_size[1],
        full_size: [width, height],
        crop_offset,
        filter: filter.unwrap_or(FilterDesc::Gaussian { stddev: 0.5 }),
    })
}

/// Interprets an `<rfilter>` element.
fn filter_desc(node: &ObjectNode) -> Result<FilterDesc> {
    super::no_children(node)?;
    let mut params = Params::new(node);
    let filter = match node.plugin.as_str() {
        "box" => FilterDesc::Box,
        "tent" => FilterDesc::Tent {
            radius: positive(&mut params, "radius", 1.0)?,
        },
        "gaussian" => FilterDesc::Gaussian {
            stddev: positive(&mut params, "stddev", 0.5)?,
        },
        "mitchell" => FilterDesc::Mitchell {
            b: finite(&mut params, "B", 1.0 / 3.0)? as f32,
            c: finite(&mut params, "C", 1.0 / 3.0)? as f32,
        },
        "catmullrom" => FilterDesc::CatmullRom,
        "lanczos" => FilterDesc::Lanczos {
            lobes: params.integer_in("lobes", 3, 1, i64::from(MAX_LANCZOS_LOBES))? as u32,
        },
        _ => return Err(unknown_type(node, &FILTERS)),
    };
    params.finish()?;
    Ok(filter)
}

/// The `rfilter` plugins.
const FILTERS: [&str; 6] = [
    "box",
    "tent",
    "gaussian",
    "mitchell",
    "catmullrom",
    "lanczos",
];

/// A float parameter with a default that must be finite in single precision (returned in
/// double precision, which times keep).
fn finite(params: &mut Params, name: &'static str, default: f64) -> Result<f64> {
    let value = params.float_or(name, default)?;
    if !(value as f32).is_finite() {
        return Err(params
            .loc_of(name)
            .error(format!("\"{name}\" must be finite, got {value}")));
    }
    Ok(value)
}

/// A positive float parameter with a default.
fn positive(params: &mut Params, name: &'static str, default: f64) -> Result<f32> {
    let value = params.float_or(name, default)?;
    if value <= 0.0 {
        return Err(params
            .loc_of(name)
            .error(format!("\"{name}\" must be positive, got {value}")));
    }
    Ok(value as f32)
}

/// Mitsuba's samplers whose names are not Strata's, each with the Strata sampler nearest to it
/// (see [`SamplerDesc::kind`]). Every other `<sampler type>` is a [`SamplerKind`] name, read by
/// its [`FromStr`](std::str::FromStr) as the command line reads it.
const MITSUBA_SAMPLERS: [(&str, SamplerKind); 3] = [
    ("multijitter", SamplerKind::Stratified),
    ("orthogonal", SamplerKind::Stratified),
    // A scrambled (0, 2)-sequence with per-dimension shuffles.
    ("ldsampler", SamplerKind::Sobol),
];

/// Interprets a `<sampler>` element: the one place where Mitsuba's sampler names meet
/// Strata's samplers (see [`SamplerDesc::kind`]).
fn sampler_desc(node: &ObjectNode) -> Result<SamplerDesc> {
    super::no_children(node)?;
    let mut params = Params::new(node);
    let plugin = node.plugin.as_str();
    let kind = match MITSUBA_SAMPLERS.iter().find(|(name, _)| *name == plugin) {
        Some(&(_, kind)) => Some(kind),
        // Mitsuba's default: no intent (see `SamplerDesc::kind`).
        None if plugin == "independent" => None,
        None => Some(plugin.parse::<SamplerKind>().map_err(|_| {
            let strata = SamplerKind::ALL.map(SamplerKind::name);
            let mitsuba = MITSUBA_SAMPLERS.map(|(name, _)| name);
            unknown_type(node, &[&strata[..], &mitsuba[..]].concat())
        })?),
    };
    if plugin == "orthogonal" {
        // The array's strength changes only how the dimensions are stratified together.
        params.integer_in("strength", 2, 2, 64)?;
    }
    if kind == Some(SamplerKind::Stratified) && !params.boolean_or("jitter", true)? {
        return Err(params
            .loc_of("jitter")
            .error("jitter=\"false\" is not supported (it biases the image)"));
    }
    let sample_count = params.integer_in("sample_count", 4, 1, i64::from(MAX_SAMPLE_COUNT))? as u32;
    let desc = SamplerDesc {
        kind,
        sample_count,
        mitsuba_sample_count: mitsuba_sample_count(plugin, sample_count),
        seed: params.integer_in("seed", 0, 0, i64::from(u32::MAX))? as u32,
    };
    params.finish()?;
    Ok(desc)
}

/// The samples per pixel Mitsuba's sampler `plugin` renders for `sample_count`: `stratified`
/// rounds up to a square, `multijitter` to a near-square product, `ldsampler` to a square of a
/// power of two and `orthogonal` to the square of a prime; `independent` takes it as it is.
pub(crate) fn mitsuba_sample_count(plugin: &str, sample_count: u32) -> u64 {
    let spp = u64::from(sample_count);
    match plugin {
        "stratified" => {
            let mut res = 1u64;
            while res * res < spp {
                res += 1;
            }
            res * res
        }
        "multijitter" => {
            let rows = (spp as f64).sqrt() as u64;
            let cols = spp.div_ceil(rows);
            rows * cols
        }
        "ldsampler" => {
            let mut res = 2u64;
            while res * res < spp {
                res = (res + 1).next_power_of_two();
            }
            res * res
        }
        "orthogonal" => {
            let is_prime = |x: u64| {
                x >= 2
                    && (2..)
                        .take_while(|d| d * d <= x)
                        .all(|d| !x.is_multiple_of(d))
            };
            let mut res = 2u64;
            while res * res < spp || !is_prime(res) {
                res += 1;
            }
            res * res
        }
        _ => spp,
    }
}
