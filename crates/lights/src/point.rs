//! Isotropic point lights (Mitsuba's `point` emitter).

use crate::light::{Emitter, Kind};
use crate::sample::{LightSample, mean_rgb};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// A point emitting `intensity` (W/sr, RGB) equally in all directions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLight {
    /// Position in world space.
    pub position: Vec3,
    /// Radiant intensity, W/sr per channel.
    pub intensity: Vec3,
}

impl PointLight {
    /// The only direction towards the light, with `intensity / distance²`; `None` at the light itself.
    #[inline]
    pub fn sample_li(&self, p: Vec3) -> Option<LightSample> {
        let to_light = self.position - p;
        let distance_squared = to_light.length_squared();
        if !(distance_squared.is_finite() && distance_squared > 0.0) {
            return None;
        }
        let distance = distance_squared.sqrt();
        Some(LightSample {
            radiance: self.intensity / distance_squared,
            wi: to_light / distance,
            distance,
            pdf_solid_angle: 1.0,
            p_light: self.position,
            p_light_error: Vec3::ZERO,
            n_light: Vec3::ZERO,
            is_delta: true,
        })
    }

    /// Total emitted power (W, mean over channels): 4π · intensity.
    pub fn power(&self) -> f32 {
        4.0 * PI * mean_rgb(self.intensity)
    }
}

impl Emitter for PointLight {
    const KIND: Kind = Kind::Delta;

    #[inline]
    fn sample_li(&self, p: Vec3, _u: Vec2, _time: f32) -> Option<LightSample> {
        PointLight::sample_li(self, p)
    }

    fn bounding_sphere(&self) -> Option<(Vec3, f32)> {
        Some((self.position, 0.0))
    }

    fn power(&self) -> f32 {
        PointLight::power(self)
    }
}
