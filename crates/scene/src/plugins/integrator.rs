//! `<integrator type="path">` and `<integrator type="direct">`.

use super::{no_children, unknown_type};
use crate::desc::{IntegratorDesc, IntegratorKind};
use crate::error::Result;
use crate::params::Params;
use crate::xml::tree::ObjectNode;

/// Mitsuba's default Russian roulette start depth.
const DEFAULT_RR_DEPTH: i64 = 5;

/// Interprets an `<integrator>` element.
pub(crate) fn integrator(node: &ObjectNode) -> Result<IntegratorDesc> {
    no_children(node)?;
    let mut params = Params::new(node);
    let desc = match node.plugin.as_str() {
        "path" => IntegratorDesc {
            kind: IntegratorKind::Path,
            max_depth: params.integer_in("max_depth", -1, -1, i64::from(i32::MAX))? as i32,
            rr_depth: params.integer_in("rr_depth", DEFAULT_RR_DEPTH, 1, i64::from(u32::MAX))?
                as u32,
            hide_emitters: params.boolean_or("hide_emitters", false)?,
        },
        "direct" => IntegratorDesc {
            kind: IntegratorKind::Direct,
            max_depth: 2,
            rr_depth: DEFAULT_RR_DEPTH as u32,
            hide_emitters: params.boolean_or("hide_emitters", false)?,
        },
        _ => return Err(unknown_type(node, &["path", "direct"])),
    };
    params.finish()?;
    Ok(desc)
}
