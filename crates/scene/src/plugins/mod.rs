//! Interpretation of plugin objects (`<integrator>`, `<sensor>`, `<shape>`, ...) into descriptions.

pub(crate) mod bsdf;
pub(crate) mod emitter;
pub(crate) mod instance;
pub(crate) mod integrator;
pub(crate) mod sensor;
pub(crate) mod shape;
pub(crate) mod texture;

use crate::error::{LoadError, Loc, Result};
use crate::xml::tree::{Child, ObjectNode};

/// The error for a plugin type this loader does not know.
pub(crate) fn unknown_type(node: &ObjectNode, supported: &[&str]) -> LoadError {
    node.loc.error(format!(
        "unknown {} type \"{}\" (supported: {})",
        node.tag,
        node.plugin,
        supported.join(", ")
    ))
}

/// Where a child element is.
pub(crate) fn child_loc(child: &Child) -> &Loc {
    match child {
        Child::Object(object) => &object.loc,
        Child::Ref(reference) => &reference.loc,
    }
}

/// The error for a child element that `parent` cannot hold; `allowed` describes what it can.
pub(crate) fn unexpected_child(parent: &ObjectNode, child: &Child, allowed: &str) -> LoadError {
    child_loc(child).error(format!(
        "{} cannot contain this element (allowed: {allowed})",
        parent.loc.element
    ))
}

/// Fails when `node` has any nested object or reference.
pub(crate) fn no_children(node: &ObjectNode) -> Result<()> {
    match node.children.first() {
        Some(child) => Err(unexpected_child(node, child, "no nested elements")),
        None => Ok(()),
    }
}
