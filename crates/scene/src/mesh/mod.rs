//! Triangle meshes: built-in shapes, OBJ, PLY and Mitsuba serialized readers, and placement into
//! world space.

pub(crate) mod canonical;
pub(crate) mod normals;
pub(crate) mod obj;
pub(crate) mod place;
pub(crate) mod ply;
pub(crate) mod serialized;
