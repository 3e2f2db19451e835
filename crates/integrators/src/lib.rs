//! Light transport over a [`World`]: the reference path tracer (the oracle every other
//! configuration is tested against) and the path tracer with every variance-reduction technique
//! as a switch.

mod camera_ray;
mod counters;
mod delta_lights;
mod light_selection;
mod light_tracer;
mod next_direction;
mod optional_draw;
pub mod path;
pub mod path_reuse;
mod ray_log;
pub mod reference;
mod settings;
mod uniform_direction;
mod world;

pub use camera_ray::CameraRay;
pub use counters::{RayCounters, RayTally};
pub use light_tracer::{CameraConnection, LightTracer};
pub use path::PathIntegrator;
pub use ray_log::{RayLog, ShadowRay};
pub use settings::{
    DirectSamples, LightSelectionMode, Mis, PathReuse, PathSettings, RussianRoulette,
};
pub use world::{BsdfSlot, Checkerboard, MaterialId, MaterialTexture, SurfaceHit, World};
