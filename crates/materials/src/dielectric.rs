//! Mitsuba's `dielectric`: a smooth interface between two dielectrics (glass, water), which
//! reflects and refracts by the exact unpolarised Fresnel equations.

use crate::bsdf::{BsdfSample, DeltaLobes, Model};
use crate::error::{MaterialError, relative_ior};
use crate::flags::BsdfFlags;
use crate::fresnel::{fresnel_dielectric, reflect, refract};
use glam::{Vec2, Vec3};

/// A smooth dielectric interface with relative index η = int_ior / ext_ior. The inside is below
/// the surface (−z); light may arrive from either side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dielectric {
    eta: f32,
    specular_reflectance: Vec3,
    specular_transmittance: Vec3,
}

impl Dielectric {
    /// Mitsuba's default `int_ior`: BK7 glass.
    pub const DEFAULT_INT_IOR: f32 = 1.5046;
    /// Mitsuba's default `ext_ior`: air.
    pub const DEFAULT_EXT_IOR: f32 = 1.000_277;

    /// An interface with interior index `int_ior` and exterior index `ext_ior` (both finite and
    /// positive, else an error), with RGB multipliers on the reflected and refracted light
    /// (Mitsuba's `specular_reflectance` and `specular_transmittance`, default 1; they are
    /// not physical and may break energy conservation when above 1).
    pub fn new(
        int_ior: f32,
        ext_ior: f32,
        specular_reflectance: Vec3,
        specular_transmittance: Vec3,
    ) -> Result<Self, MaterialError> {
        Ok(Self {
            eta: relative_ior(int_ior, ext_ior)?,
            specular_reflectance,
            specular_transmittance,
        })
    }

    /// The relative index of refraction η = int_ior / ext_ior.
    pub fn eta(&self) -> f32 {
        self.eta
    }

    /// Reflectance and transmittance multipliers at normal incidence, RGB: F₀ · R + (1 − F₀) · T
    /// with F₀ = ((η − 1)/(η + 1))², ignoring the 1/η² radiance scale of refraction.
    pub fn normal_albedo(&self) -> Vec3 {
        let f0 = fresnel_dielectric(1.0, self.eta).reflectance;
        f0 * self.specular_reflectance + (1.0 - f0) * self.specular_transmittance
    }

    /// Chooses reflection with probability F (when `u_lobe < F`) and refraction otherwise, for
    /// `wo` on either side. `None` for `wo` in the tangent plane or a degenerate choice.
    ///
    /// `pdf_solid_angle` is the lobe's probability (F or 1 − F) and `f` is chosen so that the
    /// weight `f · |cos θi| / pdf` is Mitsuba's: `specular_reflectance` for reflection and
    /// `specular_transmittance · η_ti²` for refraction, where η_ti = 1/`eta` is the inverse of
    /// the relative index crossed (radiance is compressed into the denser medium's smaller solid
    /// angle). Mitsuba picks reflection when `u ≤ F`; `<` here never picks a lobe of probability 0.
    pub fn sample(&self, wo: Vec3, u_lobe: f32) -> Option<BsdfSample> {
        let fresnel = fresnel_dielectric(wo.z, self.eta);
        let r = fresnel.reflectance;
        let (wi, pdf, weight, eta) = if u_lobe < r {
            (reflect(wo), r, self.specular_reflectance, 1.0)
        } else {
            let scale = fresnel.eta_ti * fresnel.eta_ti;
            (
                refract(wo, fresnel.cos_theta_t, fresnel.eta_ti),
                1.0 - r,
                self.specular_transmittance * scale,
                fresnel.eta_it,
            )
        };
        let cos_i = wi.z.abs();
        (pdf > 0.0 && cos_i > 0.0).then(|| BsdfSample {
            f: weight * (pdf / cos_i),
            wi,
            pdf_solid_angle: pdf,
            is_delta: true,
            eta,
            is_null: false,
        })
    }
}

impl Model for Dielectric {
    #[inline]
    fn flags(&self) -> BsdfFlags {
        BsdfFlags::DELTA | BsdfFlags::TRANSMISSION | BsdfFlags::LOBE_CHOICE
    }

    #[inline]
    fn sample(&self, wo: Vec3, u_lobe: f32, _u_dir: Vec2) -> Option<BsdfSample> {
        Dielectric::sample(self, wo, u_lobe)
    }

    fn sample_delta(&self, wo: Vec3, u_lobe: f32) -> Option<BsdfSample> {
        Dielectric::sample(self, wo, u_lobe)
    }

    fn delta_lobes(&self, wo: Vec3) -> DeltaLobes {
        // `sample` reflects for u_lobe below the reflectance R and refracts above it.
        let r = fresnel_dielectric(wo.z, self.eta).reflectance;
        let refracts = r < 1.0;
        [
            (r > 0.0)
                .then(|| Dielectric::sample(self, wo, 0.0))
                .flatten(),
            refracts
                .then(|| Dielectric::sample(self, wo, r.max(0.0)))
                .flatten(),
        ]
    }

    fn albedo_hint(&self) -> Vec3 {
        self.normal_albedo()
    }
}
