//! Light transport over a [`World`](world::World): the reference path tracer (the oracle every other
//! configuration is tested against) and the path tracer with every variance-reduction technique
//! as a switch.

mod caster_cones;
mod caustic_mis;
mod direct;
mod light_selection;
mod light_tracer;
mod next_direction;
mod optional_draw;
pub mod path;
pub mod path_reuse;
pub mod reference;
mod settings;
mod uniform_direction;

pub use light_selection::every::MAX_EVERY_LIGHT;
pub use light_tracer::{CameraSplat, LightTracer};
pub use path::PathIntegrator;
pub use settings::{DirectSamples, LightTracing, Mis, PathReuse, PathSettings, RussianRoulette};

/// How [`PathSettings::light_selection`] chooses a light (defined in `lights`, re-exported here
/// with the settings it is one of).
pub use lights::LightSelection;
