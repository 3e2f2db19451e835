//! The XML layer: attributes, values, transforms and the object tree.

pub(crate) mod attrs;
pub(crate) mod comments;
pub(crate) mod transform;
pub(crate) mod tree;
pub(crate) mod values;
