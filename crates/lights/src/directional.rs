//! Directional lights (Mitsuba's `directional` emitter): parallel light from infinitely far away,
//! like the sun without its disc.

use crate::light::{Emitter, Kind};
use crate::sample::{LightSample, mean_rgb};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// Light travelling along one direction with `irradiance` (W m⁻², RGB) on a surface facing it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionalLight {
    /// Unit direction in which the light travels (world space).
    direction: Vec3,
    irradiance: Vec3,
    /// Radius of a sphere around the scene's geometry, world units (for the power).
    scene_radius: f32,
}

impl DirectionalLight {
    /// Light travelling along `direction` (any non-zero length; `None` otherwise) with
    /// `irradiance` W m⁻² per channel, for a scene inside a sphere of `scene_radius`.
    pub fn new(direction: Vec3, irradiance: Vec3, scene_radius: f32) -> Option<Self> {
        let direction = direction.try_normalize()?;
        Some(Self {
            direction,
            irradiance,
            scene_radius,
        })
    }

    /// The unit direction towards the light (against the direction the light travels).
    pub fn towards_light(&self) -> Vec3 {
        -self.direction
    }

    /// The only direction towards the light, from any point, with the irradiance as the
    /// delta-light term (`pdf_solid_angle` 1) and an infinite distance: the shadow ray must
    /// escape the scene.
    #[inline]
    pub fn sample_li(&self, p: Vec3) -> LightSample {
        let wi = -self.direction;
        LightSample {
            radiance: self.irradiance,
            wi,
            distance: f32::INFINITY,
            pdf_solid_angle: 1.0,
            p_light: p + wi,
            p_light_error: Vec3::ZERO,
            n_light: Vec3::ZERO,
            is_delta: true,
        }
    }

    /// Irradiance on a surface facing the light, W m⁻² (mean over channels).
    pub fn irradiance(&self) -> f32 {
        mean_rgb(self.irradiance)
    }

    /// Power reaching the scene (W, mean over channels): irradiance times the cross-section
    /// π r² of the scene's bounding sphere, as Mitsuba's emitter counts it.
    pub fn power(&self) -> f32 {
        PI * self.scene_radius * self.scene_radius * mean_rgb(self.irradiance)
    }
}

impl Emitter for DirectionalLight {
    const KIND: Kind = Kind::Delta;

    #[inline]
    fn sample_li(&self, p: Vec3, _u: Vec2, _time: f32) -> Option<LightSample> {
        Some(DirectionalLight::sample_li(self, p))
    }

    fn towards(&self, _p: Vec3) -> Option<Vec3> {
        Some(self.towards_light())
    }

    /// The irradiance itself, times |cos θ| at a surface with normal `n`.
    fn irradiance_estimate(&self, _p: Vec3, n: Vec3) -> f32 {
        self.irradiance() * self.towards_light().dot(n).abs()
    }

    fn power(&self) -> f32 {
        DirectionalLight::power(self)
    }
}
