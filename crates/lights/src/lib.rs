//! Emitters and the choice between them.
//!
//! Every light answers three questions for a shading point: sample a direction towards it
//! ([`Light::sample_li`]), give the density of a direction found some other way
//! ([`Light::pdf_li_surface`] and [`Light::pdf_li_environment`], per steradian), and say how much power it emits ([`Light::power`], used
//! to pick lights). Emission seen by a ray that hits an emitter is [`Light::radiance_towards`] for
//! surface lights and [`Light::radiance_from_direction`] for the environment.
//!
//! Conventions follow Mitsuba 3: area emitters are one-sided and emit on the side their
//! geometric normal points to; a point light has intensity in W/sr (a spot light on its axis); a
//! directional light has irradiance in W/m²; a constant environment emits the same radiance from
//! every direction, an environment map the radiance of a latitude-longitude image.
//!
//! The lights form a closed set, declared once by the `light_set!` list in `light.rs`: one line
//! per light names its [`Light`] variant and the struct it holds, which implements the
//! crate-private `Emitter` trait in its own file (the trait's defaults fit a light without a
//! surface). Adding a light is that file, its line in the list, its XML parameters in the scene
//! crate's `plugins/emitter.rs` (with its description in `desc/material.rs`), and its case in the
//! scene crate's `tests/light_set.rs`, which fails until every kind of [`Light::KINDS`] has one.

mod area_sample;
mod directional;
mod emission;
mod environment;
mod environment_map;
mod light;
mod mesh_area;
mod moving;
mod point;
mod sample;
mod selection;
mod sphere_area;
mod spot;

pub use directional::DirectionalLight;
pub use emission::EmissionSample;
pub use environment::ConstantEnvironment;
pub use environment_map::{EnvironmentMap, EnvironmentMapError};
pub use light::Light;
pub use mesh_area::MeshAreaLight;
pub use moving::MovingLight;
pub use point::PointLight;
pub use sample::{LightSample, mean_rgb};
pub use selection::{LightSelection, LightSelector};
pub use sphere_area::SphereAreaLight;
pub use spot::SpotLight;

/// Converts a density per unit area at a surface point into a density per steradian seen from a
/// point `distance` away, where `cos_at_light` is the cosine between the surface normal and the
/// direction back to the viewer. Zero when the surface is seen edge-on.
#[inline]
pub fn pdf_area_to_solid_angle(pdf_area: f32, distance: f32, cos_at_light: f32) -> f32 {
    let cos = cos_at_light.abs();
    if cos <= 0.0 {
        0.0
    } else {
        pdf_area * distance * distance / cos
    }
}
