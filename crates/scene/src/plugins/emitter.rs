//! `<emitter>`: area (inside a shape), point and constant.

use glam::DVec3;

use super::{no_children, unknown_type};
use crate::desc::{AreaEmitterDesc, EmitterDesc};
use crate::error::Result;
use crate::params::{ColorKind, Params};
use crate::xml::tree::ObjectNode;

/// Emitter plugins accepted at the top level of a scene.
const SCENE_EMITTERS: [&str; 2] = ["point", "constant"];

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

/// Interprets an `<emitter>` at the top level of the scene.
pub(crate) fn scene_emitter(node: &ObjectNode) -> Result<EmitterDesc> {
    no_children(node)?;
    let mut params = Params::new(node);
    let emitter = match node.plugin.as_str() {
        "point" => {
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
            EmitterDesc::Point {
                position: position.as_vec3(),
                intensity: params
                    .color("intensity", ColorKind::Emission, 1.0)?
                    .as_vec3(),
                sampling_weight: sampling_weight(&mut params)?,
            }
        }
        "constant" => EmitterDesc::Constant {
            radiance: params
                .color("radiance", ColorKind::Emission, 1.0)?
                .as_vec3(),
            sampling_weight: sampling_weight(&mut params)?,
        },
        "area" => {
            return Err(node
                .loc
                .error("an area emitter must be nested inside the <shape> that emits"));
        }
        "envmap" => {
            return Err(node.loc.error(format!(
                "emitter type \"envmap\" is not supported yet (supported: {})",
                SCENE_EMITTERS.join(", ")
            )));
        }
        _ => {
            return Err(unknown_type(
                node,
                &["point", "constant", "area (inside a shape)"],
            ));
        }
    };
    params.finish()?;
    Ok(emitter)
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
