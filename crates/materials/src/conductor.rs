//! Mitsuba's `conductor`: a smooth metal, a perfect mirror weighted by the conductor Fresnel term.

use crate::bsdf::{BsdfSample, Model};
use crate::flags::BsdfFlags;
use crate::fresnel::{ComplexIor, fresnel_conductor, reflect};
use glam::{Vec2, Vec3};

/// A one-sided perfect mirror with reflectance `specular_reflectance · F_conductor(cos θ)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conductor {
    ior: ComplexIor,
    specular_reflectance: Vec3,
}

impl Conductor {
    /// A mirror of complex index `ior` ([`ComplexIor::PERFECT_MIRROR`] for `material="none"`),
    /// scaled by RGB `specular_reflectance` (Mitsuba's default 1).
    pub fn new(ior: ComplexIor, specular_reflectance: Vec3) -> Self {
        Self {
            ior,
            specular_reflectance,
        }
    }

    /// Fraction of light reflected at `cos_theta` ∈ [0, 1] from the normal, per RGB channel.
    pub fn reflectance(&self, cos_theta: f32) -> Vec3 {
        self.specular_reflectance * fresnel_conductor(cos_theta, self.ior)
    }

    /// The mirror direction of `wo` (chosen with probability 1); `None` unless `wo.z > 0`.
    /// `f` is `reflectance / cos θi`, so the sample's weight f · cos θi / 1 is the reflectance.
    pub fn sample(&self, wo: Vec3) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let wi = reflect(wo);
        Some(BsdfSample {
            f: self.reflectance(wo.z) / wi.z,
            wi,
            pdf_solid_angle: 1.0,
            is_delta: true,
            eta: 1.0,
            is_null: false,
        })
    }
}

impl Model for Conductor {
    #[inline]
    fn flags(&self) -> BsdfFlags {
        BsdfFlags::DELTA
    }

    #[inline]
    fn sample(&self, wo: Vec3, _u_lobe: f32, _u_dir: Vec2) -> Option<BsdfSample> {
        Conductor::sample(self, wo)
    }

    fn sample_delta(&self, wo: Vec3, _u_lobe: f32) -> Option<BsdfSample> {
        Conductor::sample(self, wo)
    }

    fn albedo_hint(&self) -> Vec3 {
        self.reflectance(1.0)
    }
}
