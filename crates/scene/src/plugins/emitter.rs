//! `<emitter>`: area (inside a shape), point, spot, directional, constant and envmap.

use glam::{DMat3, DVec3};

use super::{no_children, unknown_type};
use crate::desc::{AreaEmitterDesc, EmitterDesc};
use crate::error::Result;
use crate::params::{ColorKind, Params};
use crate::xml::tree::ObjectNode;
use lights::{ConstantEnvironment, DirectionalLight, EnvironmentMap, Light, PointLight, SpotLight};

/// Interprets an `<emitter>` nested in a `<shape>`; only `area` is allowed there.
pub(crate) fn area_emitter(node: &ObjectNode) -> Result<AreaEmitterDesc> {
    no_children(node)?;
    if node.plugin != "area" {
        return Err(node.loc.error(format!(
            "a shape can only carry an area emitter, not \"{}\" (supported: area)",
            node.plugin
        )));
    }
    let mut params = Params::new(node);
    if params.has("to_world") {
        return Err(params
            .loc_of("to_world")
            .error("an area emitter takes its placement from its shape; remove to_world"));
    }
    let radiance = params.color("radiance", ColorKind::Emission, 1.0)?;
    let sampling_weight = sampling_weight(&mut params)?;
    params.finish()?;
    Ok(AreaEmitterDesc {
        radiance: radiance.as_vec3(),
        sampling_weight,
    })
}

/// Reads the parameters of one type of top-level emitter into its description; positions are
/// given relative to `origin` (world space), subtracted in double precision.
type ReadEmitter = fn(&mut Params, DVec3) -> Result<EmitterDesc>;

/// The emitters a scene holds at its top level, one line per light: Mitsuba's type name and the
/// function that reads its parameters (its light is built by [`scene_light`]). An area emitter
/// is read inside its shape instead ([`area_emitter`]).
const SCENE_EMITTERS: [(&str, ReadEmitter); 5] = [
    ("point", point),
    ("spot", spot),
    ("directional", directional),
    ("constant", constant),
    ("envmap", envmap),
];

/// Interprets an `<emitter>` at the top level of the scene; positions are given relative to
/// `origin` (world space), subtracted in double precision.
pub(crate) fn scene_emitter(node: &ObjectNode, origin: DVec3) -> Result<EmitterDesc> {
    no_children(node)?;
    let mut params = Params::new(node);
    let Some((_, read)) = SCENE_EMITTERS
        .iter()
        .find(|(name, _)| *name == node.plugin.as_str())
    else {
        if node.plugin == "area" {
            return Err(node
                .loc
                .error("an area emitter must be nested inside the <shape> that emits"));
        }
        let mut supported: Vec<&str> = SCENE_EMITTERS.iter().map(|(name, _)| *name).collect();
        supported.push("area (inside a shape)");
        return Err(unknown_type(node, &supported));
    };
    let emitter = read(&mut params, origin)?;
    params.finish()?;
    Ok(emitter)
}

/// The light of a top-level emitter's description, in a scene inside a sphere of
/// `scene_radius` (world units; directional lights and environments count their power over
/// it); an error message when the description cannot make one.
pub(crate) fn scene_light(
    emitter: &EmitterDesc,
    scene_radius: f32,
) -> std::result::Result<Light, String> {
    Ok(match *emitter {
        EmitterDesc::Point {
            position,
            intensity,
            ..
        } => Light::Point(PointLight {
            position,
            intensity,
        }),
        EmitterDesc::Spot {
            position,
            axes,
            intensity,
            cutoff_angle,
            beam_width,
            ..
        } => Light::Spot(
            SpotLight::new(position, axes, intensity, cutoff_angle, beam_width)
                .ok_or("invalid spot light")?,
        ),
        EmitterDesc::Directional {
            direction,
            irradiance,
            ..
        } => Light::Directional(
            DirectionalLight::new(direction, irradiance, scene_radius)
                .ok_or("invalid directional light")?,
        ),
        EmitterDesc::Constant { radiance, .. } => Light::Environment(ConstantEnvironment {
            radiance,
            scene_radius,
        }),
        EmitterDesc::EnvMap {
            width,
            height,
            ref texels,
            scale,
            to_world,
            ..
        } => Light::EnvironmentMap(
            EnvironmentMap::new(width, height, texels, scale, to_world, scene_radius)
                .map_err(|e| format!("envmap: {e}"))?,
        ),
    })
}

/// `point`: at `position`, or at the translation of `to_world` (not both; default the origin),
/// with `intensity`.
fn point(params: &mut Params, origin: DVec3) -> Result<EmitterDesc> {
    let position = params.point("position")?;
    let to_world = params.transform("to_world")?;
    let position = match (position, to_world) {
        (Some(_), Some(_)) => {
            return Err(params
                .loc_of("to_world")
                .error("give either \"position\" or \"to_world\", not both"));
        }
        (Some(p), None) => p,
        (None, Some(m)) => m.transform_point3(DVec3::ZERO),
        (None, None) => DVec3::ZERO,
    };
    Ok(EmitterDesc::Point {
        position: (position - origin).as_vec3(),
        intensity: params
            .color("intensity", ColorKind::Emission, 1.0)?
            .as_vec3(),
        sampling_weight: sampling_weight(params)?,
    })
}

/// `constant`: the same `radiance` from every direction.
fn constant(params: &mut Params, _origin: DVec3) -> Result<EmitterDesc> {
    Ok(EmitterDesc::Constant {
        radiance: params
            .color("radiance", ColorKind::Emission, 1.0)?
            .as_vec3(),
        sampling_weight: sampling_weight(params)?,
    })
}

/// `envmap`: a latitude-longitude image named by `filename` (relative to the scene file; OpenEXR,
/// RGBE, or PNG and JPEG decoded from sRGB), with `scale` and `to_world`; Mitsuba's `mis_compensation` changes only how the map
/// is sampled and is accepted without effect.
fn envmap(params: &mut Params, _origin: DVec3) -> Result<EmitterDesc> {
    if params.has("bitmap") {
        return Err(params
            .loc_of("bitmap")
            .error("an environment map given as a nested bitmap is not supported; use filename"));
    }
    let (filename, loc) = params.string("filename")?.ok_or_else(|| {
        params
            .loc()
            .error("missing required parameter \"filename\"")
    })?;
    let dir = loc.file.parent().unwrap_or(std::path::Path::new(""));
    let path = dir.join(filename);
    let image = crate::image_file::read_linear_rgb(&path, false, "environment map", loc)?;
    let scale = params.float_or("scale", 1.0)?;
    if !(scale.is_finite() && scale >= 0.0) {
        return Err(params.loc_of("scale").error(format!(
            "\"scale\" must be a finite non-negative number, got {scale}"
        )));
    }
    params.boolean_or("mis_compensation", false)?;
    let to_world = params
        .transform("to_world")?
        .unwrap_or(glam::DMat4::IDENTITY);
    let to_world = glam::DMat3::from_mat4(to_world).as_mat3();
    Ok(EmitterDesc::EnvMap {
        width: image.width,
        height: image.height,
        texels: image.texels,
        scale: scale as f32,
        to_world,
        sampling_weight: sampling_weight(params)?,
    })
}

/// `spot`: placed and aimed by `to_world` (+z is the axis), with Mitsuba's `cutoff_angle`
/// (default 20°) and `beam_width` (default 3/4 of the cutoff), its position relative to `origin`.
/// Projected textures are refused.
fn spot(params: &mut Params, origin: DVec3) -> Result<EmitterDesc> {
    if params.has("texture") {
        return Err(params
            .loc_of("texture")
            .error("a spot light's projected texture is not supported"));
    }
    let to_world = params
        .transform("to_world")?
        .unwrap_or(glam::DMat4::IDENTITY);
    let axes = DMat3::from_mat4(to_world);
    let determinant = axes.determinant();
    if !(determinant.is_finite() && determinant != 0.0) {
        return Err(params
            .loc_of("to_world")
            .error("to_world is not invertible (a zero scale?)"));
    }
    let cutoff_angle = params.float_or("cutoff_angle", 20.0)?;
    if !(cutoff_angle > 0.0 && cutoff_angle <= 180.0) {
        return Err(params.loc_of("cutoff_angle").error(format!(
            "\"cutoff_angle\" must be in (0, 180] degrees, got {cutoff_angle}"
        )));
    }
    let beam_width = params.float_or("beam_width", cutoff_angle * 0.75)?;
    if !(beam_width >= 0.0 && beam_width.is_finite()) {
        return Err(params.loc_of("beam_width").error(format!(
            "\"beam_width\" must be a non-negative angle in degrees, got {beam_width}"
        )));
    }
    Ok(EmitterDesc::Spot {
        position: (to_world.transform_point3(DVec3::ZERO) - origin).as_vec3(),
        axes: axes.as_mat3(),
        intensity: params
            .color("intensity", ColorKind::Emission, 1.0)?
            .as_vec3(),
        cutoff_angle: cutoff_angle as f32,
        beam_width: beam_width as f32,
        sampling_weight: sampling_weight(params)?,
    })
}

/// `directional`: travelling along `direction` or along `to_world` applied to +z (not both).
fn directional(params: &mut Params, _origin: DVec3) -> Result<EmitterDesc> {
    let direction = params.point("direction")?;
    let to_world = params.transform("to_world")?;
    let (direction, name) = match (direction, to_world) {
        (Some(_), Some(_)) => {
            return Err(params
                .loc_of("to_world")
                .error("give either \"direction\" or \"to_world\", not both"));
        }
        (Some(d), None) => (d, "direction"),
        (None, Some(m)) => (m.transform_vector3(DVec3::Z), "to_world"),
        (None, None) => (DVec3::Z, "direction"),
    };
    let Some(direction) = direction.try_normalize() else {
        return Err(params
            .loc_of(name)
            .error("a directional light needs a non-zero direction"));
    };
    Ok(EmitterDesc::Directional {
        direction: direction.as_vec3(),
        irradiance: params
            .color("irradiance", ColorKind::Emission, 1.0)?
            .as_vec3(),
        sampling_weight: sampling_weight(params)?,
    })
}

/// Mitsuba's `sampling_weight` of every emitter: positive and finite, default 1.
fn sampling_weight(params: &mut Params) -> Result<f32> {
    let weight = params.float_or("sampling_weight", 1.0)?;
    if !(weight > 0.0 && (weight as f32).is_finite()) {
        return Err(params.loc_of("sampling_weight").error(format!(
            "\"sampling_weight\" must be positive and finite, got {weight}"
        )));
    }
    Ok(weight as f32)
}
