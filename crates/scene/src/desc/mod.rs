//! The scene description produced by the loader: plain data in the camera's frame, Mitsuba
//! defaults filled in.

mod material;
mod render;
mod shape;

use std::path::PathBuf;

pub use material::{AreaEmitterDesc, BsdfDesc, EmitterDesc, MicrofacetDistribution, Roughness};
pub use render::{
    DirectDesc, FilmDesc, FilterDesc, FovAxis, IntegratorDesc, IntegratorPreset, SamplerDesc,
    SensorDesc, ThinLensDesc, UnknownIntegrator,
};
pub use shape::{Geometry, MeshDesc, ShapeDesc, SphereDesc};

/// Everything a Mitsuba 3 scene file says, in the scene frame: world space translated so that
/// the camera sits at the origin ([`SensorDesc::position`] is where it sits in world space).
///
/// The loader subtracts the camera's position from every position in double precision, before
/// rounding to `f32`: a scene 1e6 units from the world's origin keeps the precision of one at
/// the origin, where a world-space `f32` position would be off by up to 0.03.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneDesc {
    /// The scene file this came from.
    pub source: PathBuf,
    /// The `<integrator>`.
    pub integrator: IntegratorDesc,
    /// The camera (the scene's single `<sensor>`).
    pub sensor: SensorDesc,
    /// The sensor's film (Mitsuba's default `hdrfilm` when absent).
    pub film: FilmDesc,
    /// The sensor's sampler (Mitsuba's default `independent` with 4 samples when absent).
    pub sampler: SamplerDesc,
    /// Shapes in document order.
    pub shapes: Vec<ShapeDesc>,
    /// BSDFs referenced by [`ShapeDesc::bsdf`]: top-level ones in document order, then inline ones,
    /// and Mitsuba's default diffuse BSDF if some shape names none.
    pub bsdfs: Vec<BsdfDesc>,
    /// Lights not attached to shapes (point and constant), in document order.
    pub emitters: Vec<EmitterDesc>,
}
