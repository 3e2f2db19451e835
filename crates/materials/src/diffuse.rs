//! Mitsuba's `diffuse`: an ideal one-sided Lambertian reflector.

use crate::bsdf::{Bsdf, BsdfSample, Model};
use crate::flags::BsdfFlags;
use glam::{Vec2, Vec3};
use sampling::warp::{cosine_hemisphere_pdf, sample_cosine_hemisphere};
use std::f32::consts::FRAC_1_PI;

/// Lambertian reflection f = reflectance / π on the front side (+z); black from behind.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Diffuse {
    reflectance: Vec3,
}

impl Diffuse {
    /// A Lambertian surface with RGB `reflectance` (albedo; Mitsuba's default is 0.5).
    pub fn new(reflectance: Vec3) -> Self {
        Self { reflectance }
    }

    /// The RGB albedo: the fraction of light reflected, for any incident direction.
    pub fn reflectance(&self) -> Vec3 {
        self.reflectance
    }

    /// f(wo, wi) per steradian: reflectance / π when both directions are above the surface.
    #[inline]
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        if wo.z > 0.0 && wi.z > 0.0 {
            self.reflectance * FRAC_1_PI
        } else {
            Vec3::ZERO
        }
    }

    /// Density per steradian of [`Self::sample`]: cos θi / π when both directions are above.
    #[inline]
    pub fn pdf_solid_angle(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z > 0.0 && wi.z > 0.0 {
            cosine_hemisphere_pdf(wi.z)
        } else {
            0.0
        }
    }

    /// [`Self::eval`] and [`Self::pdf_solid_angle`] together.
    #[inline]
    pub fn eval_with_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        (self.eval(wo, wi), self.pdf_solid_angle(wo, wi))
    }

    /// A cosine-weighted direction from `u_dir`; `None` when `wo` is not above the surface.
    #[inline]
    pub fn sample(&self, wo: Vec3, u_dir: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let wi = sample_cosine_hemisphere(u_dir);
        let pdf = cosine_hemisphere_pdf(wi.z);
        (pdf > 0.0).then(|| BsdfSample {
            f: self.reflectance * FRAC_1_PI,
            wi,
            pdf_solid_angle: pdf,
            is_delta: false,
            eta: 1.0,
            is_null: false,
        })
    }
}

impl Model for Diffuse {
    #[inline]
    fn flags(&self) -> BsdfFlags {
        BsdfFlags::DIFFUSE
    }

    #[inline]
    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        Diffuse::eval(self, wo, wi)
    }

    #[inline]
    fn pdf_solid_angle(&self, wo: Vec3, wi: Vec3) -> f32 {
        Diffuse::pdf_solid_angle(self, wo, wi)
    }

    #[inline]
    fn eval_with_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        Diffuse::eval_with_pdf(self, wo, wi)
    }

    #[inline]
    fn sample(&self, wo: Vec3, _u_lobe: f32, u_dir: Vec2) -> Option<BsdfSample> {
        Diffuse::sample(self, wo, u_dir)
    }

    fn with_diffuse_reflectance(&self, reflectance: Vec3) -> Option<Bsdf> {
        Some(Diffuse::new(reflectance).into())
    }

    fn albedo_hint(&self) -> Vec3 {
        self.reflectance()
    }
}
