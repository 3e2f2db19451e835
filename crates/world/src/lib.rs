//! The runtime scene that light transport traces: a [`World`] holds the geometry (one
//! acceleration structure), the materials with their textures and the emitters in flat arrays
//! indexed by shape, and answers the queries an integrator asks of it (closest hit, occlusion,
//! emission, background).
//!
//! It sits between the building blocks and their users: `sampling` ← `geometry` ← `materials`,
//! `lights` ← `world` ← `scene` (which loads a file into a world) and `integrators` (which trace
//! it) ← `render`. Besides the world it holds what both sides share: the rays a camera sends
//! ([`CameraRay`]) and how a point connects to it ([`CameraConnection`]), and the tallies
//! through which integrators report the rays they trace ([`RayTally`], [`RayCounters`],
//! [`RayLog`]).

mod camera;
mod counters;
mod ray_log;
mod world;

pub use camera::{CameraConnection, CameraRay, CameraTraits};
pub use counters::{RayCounters, RayTally};
pub use ray_log::{RayLog, ShadowRay};
pub use world::{
    BsdfSlot, Checkerboard, MaterialId, MaterialTexture, SurfaceHit, World, shadow_ray,
};
