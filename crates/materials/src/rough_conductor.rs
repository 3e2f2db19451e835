//! Mitsuba's `roughconductor`: a rough metal, the Cook–Torrance microfacet model with a
//! conductor Fresnel term, sampled through the normals visible from `wo`.

use crate::bsdf::{BsdfSample, Model};
use crate::flags::BsdfFlags;
use crate::fresnel::{ComplexIor, fresnel_conductor, reflect_about};
use crate::microfacet::Microfacet;
use glam::{Vec2, Vec3};

/// What [`RoughConductor::lobe_weight`] adds to every direction, sr⁻¹: about a third of a white
/// diffuse surface's f · cos θi at normal incidence (1/π ≈ 0.32), so that a light outside the
/// lobe is chosen rarely but not never.
pub const LOBE_WEIGHT_FLOOR: f32 = 0.1;

/// One-sided microfacet reflection f = F(wo·h) D(h) G1(wo, h) G1(wi, h) / (4 cos θo cos θi),
/// h = normalize(wo + wi), times `specular_reflectance`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughConductor {
    distribution: Microfacet,
    ior: ComplexIor,
    specular_reflectance: Vec3,
}

impl RoughConductor {
    /// A rough metal with microfacet `distribution`, complex index `ior`
    /// ([`ComplexIor::PERFECT_MIRROR`] for `material="none"`) and RGB `specular_reflectance`.
    pub fn new(distribution: Microfacet, ior: ComplexIor, specular_reflectance: Vec3) -> Self {
        Self {
            distribution,
            ior,
            specular_reflectance,
        }
    }

    /// The microfacet distribution.
    pub fn distribution(&self) -> Microfacet {
        self.distribution
    }

    /// Reflectance at normal incidence, per RGB channel: F(1) · specular_reflectance.
    pub fn normal_reflectance(&self) -> Vec3 {
        self.specular_reflectance * fresnel_conductor(1.0, self.ior)
    }

    /// f(wo, wi) per steradian, zero unless both directions are above the surface.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Vec3::ZERO;
        }
        let h = (wo + wi).normalize();
        self.eval_with_normal(wo, wi, h)
    }

    /// Density per steradian of [`Self::sample`]: D_wo(h) / (4 wo·h) = D(h) G1(wo, h) / (4 cos θo),
    /// with the exact Smith G1 (see the [`crate::microfacet`] module on Beckmann).
    pub fn pdf_solid_angle(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        let h = (wo + wi).normalize();
        if wo.dot(h) <= 0.0 || wi.dot(h) <= 0.0 {
            return 0.0;
        }
        self.distribution.visible_normal_pdf(wo, h) / (4.0 * wo.dot(h))
    }

    /// [`Self::eval`] and [`Self::pdf_solid_angle`] together, sharing the half vector and D(h):
    /// the same values as the two calls.
    pub fn eval_with_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let h = (wo + wi).normalize();
        let d = self.distribution.d(h);
        let pdf = if wo.dot(h) <= 0.0 || wi.dot(h) <= 0.0 {
            0.0
        } else {
            self.distribution.visible_normal_pdf_given_d(wo, h, d) / (4.0 * wo.dot(h))
        };
        (self.eval_given_d(wo, wi, h, d), pdf)
    }

    /// A cheap positive estimate of f · cos θi towards `wi`, sr⁻¹, for choosing among lights:
    /// D(h) / (4 cos θo), which leaves out of f · cos θi = F D G / (4 cos θo) the factors that
    /// vary little (F, G ≤ 1), plus [`LOBE_WEIGHT_FLOOR`] so that no direction gets zero; the
    /// floor alone when either direction is below the surface.
    pub fn lobe_weight(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return LOBE_WEIGHT_FLOOR;
        }
        self.distribution.d((wo + wi).normalize()) / (4.0 * wo.z) + LOBE_WEIGHT_FLOOR
    }

    /// Reflects `wo` about a visible microfacet normal sampled from `u_dir`. `None` when `wo` is
    /// not above the surface or the reflected direction falls below it.
    pub fn sample(&self, wo: Vec3, u_dir: Vec2) -> Option<BsdfSample> {
        let (m, pdf_m) = self.distribution.sample_visible_normal(wo, u_dir)?;
        let wi = reflect_about(wo, m);
        let wo_dot_m = wo.dot(m);
        if wi.z <= 0.0 || wo_dot_m <= 0.0 {
            return None;
        }
        let pdf = pdf_m / (4.0 * wo_dot_m);
        let f = self.eval_with_normal(wo, wi, m);
        (pdf.is_finite() && pdf > 0.0).then_some(BsdfSample {
            f,
            wi,
            pdf_solid_angle: pdf,
            is_delta: false,
            eta: 1.0,
            is_null: false,
        })
    }

    /// The model's value for directions above the surface and their half vector `h`.
    fn eval_with_normal(&self, wo: Vec3, wi: Vec3, h: Vec3) -> Vec3 {
        self.eval_given_d(wo, wi, h, self.distribution.d(h))
    }

    /// [`Self::eval_with_normal`] when `d` is already known to be `D(h)`.
    fn eval_given_d(&self, wo: Vec3, wi: Vec3, h: Vec3, d: f32) -> Vec3 {
        if d == 0.0 {
            return Vec3::ZERO;
        }
        let g = self.distribution.g(wo, wi, h);
        let fresnel = fresnel_conductor(wo.dot(h), self.ior);
        self.specular_reflectance * fresnel * (d * g / (4.0 * wo.z * wi.z))
    }
}

impl Model for RoughConductor {
    #[inline]
    fn flags(&self) -> BsdfFlags {
        let anisotropic = if self.distribution().is_anisotropic() {
            BsdfFlags::ANISOTROPIC
        } else {
            BsdfFlags::EMPTY
        };
        BsdfFlags::GLOSSY | anisotropic
    }

    #[inline]
    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        RoughConductor::eval(self, wo, wi)
    }

    #[inline]
    fn pdf_solid_angle(&self, wo: Vec3, wi: Vec3) -> f32 {
        RoughConductor::pdf_solid_angle(self, wo, wi)
    }

    #[inline]
    fn eval_with_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        RoughConductor::eval_with_pdf(self, wo, wi)
    }

    #[inline]
    fn lobe_weight(&self, wo: Vec3, wi: Vec3) -> Option<f32> {
        Some(RoughConductor::lobe_weight(self, wo, wi))
    }

    #[inline]
    fn sample(&self, wo: Vec3, _u_lobe: f32, u_dir: Vec2) -> Option<BsdfSample> {
        RoughConductor::sample(self, wo, u_dir)
    }

    fn albedo_hint(&self) -> Vec3 {
        self.normal_reflectance()
    }
}
