//! `<integrator type="path">` (and `volpath`, `volpathmis`, which are the path tracer in scenes
//! without participating media, the only scenes Strata reads, but for passes through null lobes,
//! which are not path vertices to them; and the differentiable variants' `prb` and
//! `prbvolpath`, whose images are `path`'s and `volpath`'s) and `<integrator type="direct">`,
//! which all ask for Strata's `auto` preset; and Strata's presets by name
//! (`<integrator type="mis">`, parsed by [`IntegratorPreset`]'s `FromStr`), which take `path`'s
//! parameters.

use super::{no_children, unknown_type};
use crate::desc::{DirectDesc, IntegratorDesc, IntegratorPreset};
use crate::error::Result;
use crate::limits::MAX_DIRECT_SAMPLES;
use crate::params::Params;
use crate::xml::tree::{Child, ObjectNode};

/// Mitsuba's default Russian roulette start depth.
const DEFAULT_RR_DEPTH: i64 = 5;

/// The default `max_depth` of Mitsuba's path replay integrators (`prb`, `prbvolpath`); the
/// others default to -1, unbounded.
const PRB_DEFAULT_MAX_DEPTH: i64 = 6;

/// Interprets an `<integrator>` element. Mitsuba's `moment` (which adds the second moment of
/// its nested integrator's samples as extra image channels, for variance estimates) renders its
/// nested integrator's image, which is what Strata renders for it.
pub(crate) fn integrator(node: &ObjectNode) -> Result<IntegratorDesc> {
    if node.plugin == "moment" {
        Params::new(node).finish()?;
        return match node.children.as_slice() {
            [Child::Object(nested)] if nested.tag == "integrator" => integrator(nested),
            _ => Err(node
                .loc
                .error("moment needs exactly one nested <integrator>")),
        };
    }
    no_children(node)?;
    let mut params = Params::new(node);
    let plugin = node.plugin.as_str();
    let mitsuba_path = matches!(
        plugin,
        "path" | "volpath" | "volpathmis" | "prb" | "prbvolpath"
    );
    let desc = match plugin {
        "direct" => IntegratorDesc {
            preset: IntegratorPreset::Auto,
            direct: Some(direct_samples(&mut params, node)?),
            max_depth: 2,
            rr_depth: DEFAULT_RR_DEPTH as u32,
            hide_emitters: params.boolean_or("hide_emitters", false)?,
            skip_null_vertices: false,
        },
        _ => {
            let preset = match plugin.parse::<IntegratorPreset>() {
                _ if mitsuba_path => IntegratorPreset::Auto,
                Ok(preset) => preset,
                Err(_) => {
                    let mut supported = vec![
                        "path",
                        "volpath",
                        "volpathmis",
                        "prb",
                        "prbvolpath",
                        "direct",
                        "moment",
                    ];
                    supported.extend(IntegratorPreset::ALL.map(IntegratorPreset::name));
                    return Err(unknown_type(node, &supported));
                }
            };
            IntegratorDesc {
                preset,
                direct: None,
                max_depth: {
                    let default = if plugin.starts_with("prb") {
                        PRB_DEFAULT_MAX_DEPTH
                    } else {
                        -1
                    };
                    params.integer_in("max_depth", default, -1, i64::from(i32::MAX))? as i32
                },
                rr_depth: params.integer_in("rr_depth", DEFAULT_RR_DEPTH, 1, i64::from(u32::MAX))?
                    as u32,
                hide_emitters: params.boolean_or("hide_emitters", false)?,
                skip_null_vertices: plugin.contains("volpath"),
            }
        }
    };
    params.finish()?;
    Ok(desc)
}

/// The `direct` integrator's sample counts as Mitsuba reads them: `shading_samples` (default 1)
/// sets both, `emitter_samples` and `bsdf_samples` each (not together with `shading_samples`),
/// and at least one sample in all.
fn direct_samples(params: &mut Params, node: &ObjectNode) -> Result<DirectDesc> {
    if params.has("shading_samples") {
        for name in ["emitter_samples", "bsdf_samples"] {
            if params.has(name) {
                return Err(params.loc_of(name).error(format!(
                    "give either \"shading_samples\" or \"{name}\", not both"
                )));
            }
        }
    }
    let shading = params.integer_in("shading_samples", 1, 0, MAX_DIRECT_SAMPLES)?;
    let emitter_samples = params.integer_in("emitter_samples", shading, 0, MAX_DIRECT_SAMPLES)?;
    let bsdf_samples = params.integer_in("bsdf_samples", shading, 0, MAX_DIRECT_SAMPLES)?;
    if emitter_samples + bsdf_samples == 0 {
        return Err(node
            .loc
            .error("the direct integrator needs at least one emitter or BSDF sample"));
    }
    Ok(DirectDesc {
        emitter_samples: emitter_samples as u32,
        bsdf_samples: bsdf_samples as u32,
    })
}
