//! A constant environment (Mitsuba's `constant` emitter): the same radiance from every direction.

use crate::light::{Emitter, Kind};
use crate::sample::{LightSample, mean_rgb};
use glam::{Vec2, Vec3};
use sampling::warp::{sample_uniform_sphere, uniform_sphere_pdf};
use std::f32::consts::PI;

/// Radiance arriving from infinitely far away, equal in every direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConstantEnvironment {
    /// Radiance, W m⁻² sr⁻¹ per channel.
    pub radiance: Vec3,
    /// Radius of a sphere bounding the scene (world units), used only to estimate power.
    pub scene_radius: f32,
}

impl ConstantEnvironment {
    /// A direction uniform over the sphere of directions (density 1 / 4π per steradian).
    #[inline]
    pub fn sample_li(&self, p: Vec3, u: Vec2) -> Option<LightSample> {
        let wi = sample_uniform_sphere(u);
        Some(LightSample {
            radiance: self.radiance,
            wi,
            distance: f32::INFINITY,
            pdf_solid_angle: uniform_sphere_pdf(),
            p_light: p + wi,
            p_light_error: Vec3::ZERO,
            n_light: Vec3::ZERO,
            is_delta: false,
        })
    }

    /// Density per steradian of [`Self::sample_li`] choosing any direction: 1 / 4π.
    pub fn pdf_li(&self) -> f32 {
        uniform_sphere_pdf()
    }

    /// Power reaching the scene (W, mean over channels): radiance · π · π r² of the bounding disc.
    pub fn power(&self) -> f32 {
        mean_rgb(self.radiance) * PI * PI * self.scene_radius * self.scene_radius
    }
}

impl Emitter for ConstantEnvironment {
    const KIND: Kind = Kind::Environment;

    #[inline]
    fn sample_li(&self, p: Vec3, u: Vec2, _time: f32) -> Option<LightSample> {
        ConstantEnvironment::sample_li(self, p, u)
    }

    #[inline]
    fn radiance_from_direction(&self, _w: Vec3) -> Vec3 {
        self.radiance
    }

    #[inline]
    fn pdf_li_environment(&self, _w: Vec3) -> f32 {
        self.pdf_li()
    }

    /// π times the mean radiance: the irradiance from a whole hemisphere.
    fn irradiance_estimate(&self, _p: Vec3, _n: Vec3) -> f32 {
        PI * mean_rgb(self.radiance)
    }

    fn power(&self) -> f32 {
        ConstantEnvironment::power(self)
    }
}
