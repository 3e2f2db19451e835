//! Mitsuba's `plastic`: a diffuse base under a smooth dielectric coating (polypropylene in air
//! by default), which reflects specularly by Fresnel and lets the rest reach the base, whose
//! light leaves through the coating after any number of internal reflections.

use crate::bsdf::{Bsdf, BsdfSample, DeltaLobes, Model};
use crate::error::{MaterialError, relative_ior};
use crate::flags::BsdfFlags;
use crate::fresnel::{diffuse_fresnel_reflectance, fresnel_dielectric, reflect};
use glam::{Vec2, Vec3};
use sampling::warp::{cosine_hemisphere_pdf, sample_cosine_hemisphere};
use std::f32::consts::FRAC_1_PI;

/// A smooth dielectric layer with relative index η = int_ior / ext_ior over a Lambertian base,
/// one-sided (black from behind), with two lobes:
///
/// - specular: a mirror reflecting F(θo) · `specular_reflectance` (a delta lobe);
/// - diffuse: f = ρ′ / π · (1 − F(θo)) (1 − F(θi)) / η², where the base's reflectance ρ seen
///   through the coating, its internal reflections summed, is ρ′ = ρ / (1 − F_dr,int), or
///   with `nonlinear` ρ′ = ρ / (1 − ρ F_dr,int), F_dr,int being the coating's diffuse Fresnel
///   reflectance from inside ([`diffuse_fresnel_reflectance`] of 1/η).
///
/// Sampling chooses the specular lobe with probability proportional to F(θo) · w and the
/// diffuse one to (1 − F(θo)) (1 − w), where w = s / (s + d) from the means s of
/// `specular_reflectance` and d of ρ over RGB (Mitsuba's `specular_sampling_weight`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plastic {
    eta: f32,
    /// 1 / η², the radiance scale of leaving the coating.
    inv_eta_sqr: f32,
    /// ρ′: the base's reflectance with the coating's internal reflections summed, RGB.
    base_through_coating: Vec3,
    /// With F_dr,int, the coating's diffuse Fresnel reflectance from inside.
    coating: Coating,
    specular_reflectance: Vec3,
    specular_sampling_weight: f32,
}

impl Plastic {
    /// A coating of interior index `int_ior` over exterior index `ext_ior` (finite and positive,
    /// else an error) on a base of RGB albedo `diffuse_reflectance` (Mitsuba's default 0.5),
    /// with an RGB multiplier on the specular reflection (`specular_reflectance`, default 1)
    /// and Mitsuba's `nonlinear` switch (internal scattering darkens and saturates the base's
    /// colour, off by default).
    pub fn new(
        int_ior: f32,
        ext_ior: f32,
        diffuse_reflectance: Vec3,
        specular_reflectance: Vec3,
        nonlinear: bool,
    ) -> Result<Self, MaterialError> {
        let eta = relative_ior(int_ior, ext_ior)?;
        let internal = diffuse_fresnel_reflectance(1.0 / eta);
        let coating = Coating {
            internal_reflectance: internal,
            nonlinear,
        };
        Ok(Self {
            eta,
            inv_eta_sqr: 1.0 / (eta * eta),
            base_through_coating: coating.base_through(diffuse_reflectance),
            coating,
            specular_reflectance,
            specular_sampling_weight: specular_sampling_weight(
                diffuse_reflectance,
                specular_reflectance,
            ),
        })
    }

    /// The same coating over a base of RGB albedo `diffuse_reflectance`, keeping this one's
    /// lobe-sampling weight: how a textured base is shaded, Mitsuba computing the weight once
    /// from the texture's mean.
    pub fn with_diffuse_reflectance(&self, diffuse_reflectance: Vec3) -> Self {
        Self {
            base_through_coating: self.coating.base_through(diffuse_reflectance),
            ..*self
        }
    }

    /// Fresnel reflectance of the coating for light arriving at `cos_theta` ≥ 0 from outside.
    fn fresnel(&self, cos_theta: f32) -> f32 {
        fresnel_dielectric(cos_theta, self.eta).reflectance
    }

    /// The probability that [`Self::sample`] picks the specular lobe, given F(θo).
    fn specular_probability(&self, fresnel_o: f32) -> f32 {
        let specular = fresnel_o * self.specular_sampling_weight;
        let diffuse = (1.0 - fresnel_o) * (1.0 - self.specular_sampling_weight);
        let total = specular + diffuse;
        if total > 0.0 { specular / total } else { 0.0 }
    }

    /// The diffuse lobe's f(wo, wi) per steradian given F(θo), both directions above.
    fn diffuse_lobe(&self, fresnel_o: f32, cos_i: f32) -> Vec3 {
        let fresnel_i = self.fresnel(cos_i);
        self.base_through_coating
            * (FRAC_1_PI * self.inv_eta_sqr * (1.0 - fresnel_o) * (1.0 - fresnel_i))
    }

    /// Reflectance multipliers at normal incidence for heuristics, RGB:
    /// F₀ · `specular_reflectance` + (1 − F₀) · ρ′.
    pub fn normal_albedo(&self) -> Vec3 {
        let f0 = self.fresnel(1.0);
        f0 * self.specular_reflectance + (1.0 - f0) * self.base_through_coating
    }

    /// f(wo, wi) per steradian of the diffuse lobe (the specular one is a delta); 0 unless both
    /// directions are above the surface.
    #[inline]
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        if wo.z > 0.0 && wi.z > 0.0 {
            self.diffuse_lobe(self.fresnel(wo.z), wi.z)
        } else {
            Vec3::ZERO
        }
    }

    /// Density per steradian with which [`Self::sample`] produces `wi` by its diffuse lobe: the
    /// lobe's probability times cos θi / π.
    #[inline]
    pub fn pdf_solid_angle(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.eval_with_pdf(wo, wi).1
    }

    /// [`Self::eval`] and [`Self::pdf_solid_angle`] together, sharing F(θo).
    #[inline]
    pub fn eval_with_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        if wo.z > 0.0 && wi.z > 0.0 {
            let fresnel_o = self.fresnel(wo.z);
            let diffuse_probability = 1.0 - self.specular_probability(fresnel_o);
            (
                self.diffuse_lobe(fresnel_o, wi.z),
                diffuse_probability * cosine_hemisphere_pdf(wi.z),
            )
        } else {
            (Vec3::ZERO, 0.0)
        }
    }

    /// The specular lobe alone: the mirror direction with probability 1 and weight
    /// F(θo) · `specular_reflectance`. `None` unless `wo` is above the surface.
    pub fn sample_specular(&self, wo: Vec3) -> Option<BsdfSample> {
        (wo.z > 0.0).then(|| self.specular_sample(wo, self.fresnel(wo.z), 1.0))
    }

    /// The mirror direction chosen with probability `probability`, weighted so that
    /// `f · cos θi / pdf` is F(θo) · `specular_reflectance` / `probability`.
    fn specular_sample(&self, wo: Vec3, fresnel_o: f32, probability: f32) -> BsdfSample {
        BsdfSample {
            f: self.specular_reflectance * (fresnel_o / wo.z),
            wi: reflect(wo),
            pdf_solid_angle: probability,
            is_delta: true,
            eta: 1.0,
            is_null: false,
        }
    }

    /// The specular lobe when `u_lobe` < its probability (Mitsuba's choice), else a cosine-
    /// weighted direction from `u_dir` by the diffuse lobe. `None` unless `wo` is above the
    /// surface.
    #[inline]
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u_dir: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let fresnel_o = self.fresnel(wo.z);
        let specular_probability = self.specular_probability(fresnel_o);
        if u_lobe < specular_probability {
            return Some(self.specular_sample(wo, fresnel_o, specular_probability));
        }
        let wi = sample_cosine_hemisphere(u_dir);
        let pdf = (1.0 - specular_probability) * cosine_hemisphere_pdf(wi.z);
        (pdf > 0.0).then(|| BsdfSample {
            f: self.diffuse_lobe(fresnel_o, wi.z),
            wi,
            pdf_solid_angle: pdf,
            is_delta: false,
            eta: 1.0,
            is_null: false,
        })
    }
}

/// Mitsuba's `specular_sampling_weight` of a coated diffuse material: the mean of the specular
/// multiplier over RGB divided by the sum of that mean and the base's mean albedo; ½ for a
/// black material (Mitsuba's 0/0, where either choice is right).
pub(crate) fn specular_sampling_weight(
    diffuse_reflectance: Vec3,
    specular_reflectance: Vec3,
) -> f32 {
    let specular_mean = specular_reflectance.element_sum() / 3.0;
    let diffuse_mean = diffuse_reflectance.element_sum() / 3.0;
    let means = diffuse_mean + specular_mean;
    if means > 0.0 {
        specular_mean / means
    } else {
        0.5
    }
}

/// How a coating shows the base under it: its reflectance R_int for diffuse light from inside and
/// Mitsuba's `nonlinear` switch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Coating {
    /// R_int, the fraction of diffuse light from inside that the coating reflects back.
    pub(crate) internal_reflectance: f32,
    /// Whether internal scattering darkens and saturates the base's colour.
    pub(crate) nonlinear: bool,
}

impl Coating {
    /// A base of RGB albedo `diffuse_reflectance` with the coating's internal reflections
    /// summed: ρ / (1 − R_int), or with `nonlinear` ρ / (1 − ρ R_int).
    pub(crate) fn base_through(&self, diffuse_reflectance: Vec3) -> Vec3 {
        if self.nonlinear {
            diffuse_reflectance / (Vec3::ONE - diffuse_reflectance * self.internal_reflectance)
        } else {
            diffuse_reflectance / (1.0 - self.internal_reflectance)
        }
    }
}

impl Model for Plastic {
    #[inline]
    fn flags(&self) -> BsdfFlags {
        BsdfFlags::DIFFUSE | BsdfFlags::DELTA | BsdfFlags::MIXED | BsdfFlags::LOBE_CHOICE
    }

    #[inline]
    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        Plastic::eval(self, wo, wi)
    }

    #[inline]
    fn pdf_solid_angle(&self, wo: Vec3, wi: Vec3) -> f32 {
        Plastic::pdf_solid_angle(self, wo, wi)
    }

    #[inline]
    fn eval_with_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        Plastic::eval_with_pdf(self, wo, wi)
    }

    #[inline]
    fn sample(&self, wo: Vec3, u_lobe: f32, u_dir: Vec2) -> Option<BsdfSample> {
        Plastic::sample(self, wo, u_lobe, u_dir)
    }

    fn sample_delta(&self, wo: Vec3, _u_lobe: f32) -> Option<BsdfSample> {
        self.sample_specular(wo)
    }

    fn delta_lobes(&self, wo: Vec3) -> DeltaLobes {
        if wo.z <= 0.0 {
            return [None, None];
        }
        let fresnel_o = self.fresnel(wo.z);
        let probability = self.specular_probability(fresnel_o);
        let coat = (probability > 0.0).then(|| self.specular_sample(wo, fresnel_o, probability));
        [coat, None]
    }

    fn with_diffuse_reflectance(&self, reflectance: Vec3) -> Option<Bsdf> {
        Some(Plastic::with_diffuse_reflectance(self, reflectance).into())
    }

    fn albedo_hint(&self) -> Vec3 {
        self.normal_albedo()
    }
}
