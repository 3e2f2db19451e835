//! Mitsuba's `roughdielectric`: a rough interface between two dielectrics (frosted glass), the
//! microfacet model of Walter et al. 2007 for reflection and refraction, sampled through the
//! normals visible from `wo`.

use crate::bsdf::{BsdfSample, Model};
use crate::error::{MaterialError, relative_ior};
use crate::flags::BsdfFlags;
use crate::fresnel::{fresnel_dielectric, reflect_about, refract_about};
use crate::microfacet::Microfacet;
use crate::rough_conductor::LOBE_WEIGHT_FLOOR;
use glam::{Vec2, Vec3};

/// A rough dielectric interface with relative index η = int_ior / ext_ior; the inside is below
/// the surface (−z) and light may arrive from either side. With the generalised half vector m
/// (the microfacet normal that turns `wo` into `wi`, on the upper side) and η_o the ratio of the
/// index on the far side of `wi` to that on `wo`'s side:
///
/// - reflection: f = F(wo·m) D(m) G(wo, wi, m) / (4 |cos θo| |cos θi|) · `specular_reflectance`;
/// - refraction: f = (1 − F(wo·m)) D(m) G(wo, wi, m) |wo·m| |wi·m| /
///   (|cos θo| |cos θi| (wo·m + η_o wi·m)²) · `specular_transmittance`, the η_o² of Walter's
///   formula cancelled by radiance's 1/η_o² on crossing (Mitsuba's `TransportMode::Radiance`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughDielectric {
    distribution: Microfacet,
    eta: f32,
    specular_reflectance: Vec3,
    specular_transmittance: Vec3,
}

/// The generalised half vector of a pair of directions and what the two lobes share.
struct HalfVector {
    /// The microfacet normal, upper side.
    m: Vec3,
    /// Whether `wo` and `wi` are on the same side (reflection).
    reflect: bool,
    /// η_o: the index beyond `wi`'s side over `wo`'s, for refraction.
    eta: f32,
}

impl RoughDielectric {
    /// An interface with microfacet `distribution`, interior index `int_ior` and exterior index
    /// `ext_ior` (finite and positive, else an error), with RGB multipliers on the reflected and
    /// refracted light (Mitsuba's `specular_reflectance` and `specular_transmittance`).
    pub fn new(
        distribution: Microfacet,
        int_ior: f32,
        ext_ior: f32,
        specular_reflectance: Vec3,
        specular_transmittance: Vec3,
    ) -> Result<Self, MaterialError> {
        Ok(Self {
            distribution,
            eta: relative_ior(int_ior, ext_ior)?,
            specular_reflectance,
            specular_transmittance,
        })
    }

    /// The microfacet distribution.
    pub fn distribution(&self) -> Microfacet {
        self.distribution
    }

    /// Reflectance and transmittance multipliers at normal incidence, RGB, as for the smooth
    /// dielectric: F₀ · `specular_reflectance` + (1 − F₀) · `specular_transmittance`.
    pub fn normal_albedo(&self) -> Vec3 {
        let f0 = fresnel_dielectric(1.0, self.eta).reflectance;
        f0 * self.specular_reflectance + (1.0 - f0) * self.specular_transmittance
    }

    /// The half vector of `wo` and `wi`, `None` when either lies in the tangent plane or the
    /// pair has none (`wo + η_o wi` = 0).
    fn half_vector(&self, wo: Vec3, wi: Vec3) -> Option<HalfVector> {
        if wo.z == 0.0 || wi.z == 0.0 {
            return None;
        }
        let reflect = wo.z * wi.z > 0.0;
        let eta = if wo.z > 0.0 { self.eta } else { 1.0 / self.eta };
        let m = (wo + wi * if reflect { 1.0 } else { eta }).normalize_or_zero();
        if m == Vec3::ZERO {
            return None;
        }
        let m = if m.z < 0.0 { -m } else { m };
        Some(HalfVector { m, reflect, eta })
    }

    /// f(wo, wi) per steradian for directions on either side.
    #[inline]
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        self.eval_with_pdf(wo, wi).0
    }

    /// Density per steradian with which [`Self::sample`] produces `wi` from `wo`: the visible
    /// normal density of m (with the exact G1), the lobe's Fresnel probability and the Jacobian
    /// of m ↦ wi (1 / (4 wi·m) for reflection, η_o² |wi·m| / (wo·m + η_o wi·m)² for refraction).
    #[inline]
    pub fn pdf_solid_angle(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.eval_with_pdf(wo, wi).1
    }

    /// [`Self::eval`] and [`Self::pdf_solid_angle`] together, sharing the half vector, D and F.
    pub fn eval_with_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        let Some(half) = self.half_vector(wo, wi) else {
            return (Vec3::ZERO, 0.0);
        };
        let m = half.m;
        let (wo_m, wi_m) = (wo.dot(m), wi.dot(m));
        // The microfacet must face both directions from their own sides.
        if wo_m * wo.z <= 0.0 || wi_m * wi.z <= 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let d = self.distribution.d(m);
        if d == 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let g = self.distribution.g(wo, wi, m);
        let fresnel = fresnel_dielectric(wo_m, self.eta).reflectance;
        let cosines = (wo.z * wi.z).abs();
        let (f, lobe_probability, jacobian) = if half.reflect {
            (
                self.specular_reflectance * (fresnel * d * g / (4.0 * cosines)),
                fresnel,
                1.0 / (4.0 * wi_m.abs()),
            )
        } else {
            let denominator = wo_m + half.eta * wi_m;
            let denominator2 = denominator * denominator;
            (
                self.specular_transmittance
                    * ((1.0 - fresnel) * d * g * (wo_m * wi_m).abs() / (cosines * denominator2)),
                1.0 - fresnel,
                half.eta * half.eta * wi_m.abs() / denominator2,
            )
        };
        let wo_up = if wo.z > 0.0 { wo } else { -wo };
        let pdf_m = self.distribution.visible_normal_pdf(wo_up, m);
        let pdf = pdf_m * lobe_probability * jacobian;
        if pdf.is_finite() && f.is_finite() {
            (f, pdf)
        } else {
            (Vec3::ZERO, 0.0)
        }
    }

    /// For choosing among lights by resampling: a cheap positive estimate of f · cos θi, sr⁻¹,
    /// D(m) times the Jacobian of m ↦ wi times |wo·m| / |cos θo| (f · cos θi without F and G),
    /// plus [`LOBE_WEIGHT_FLOOR`]; the floor alone where the pair has no valid half vector.
    pub fn lobe_weight(&self, wo: Vec3, wi: Vec3) -> f32 {
        let Some(half) = self.half_vector(wo, wi) else {
            return LOBE_WEIGHT_FLOOR;
        };
        let m = half.m;
        let (wo_m, wi_m) = (wo.dot(m), wi.dot(m));
        let jacobian = if half.reflect {
            1.0 / (4.0 * wi_m.abs())
        } else {
            let denominator = wo_m + half.eta * wi_m;
            half.eta * half.eta * wi_m.abs() / (denominator * denominator)
        };
        let weight = self.distribution.d(m) * jacobian * wo_m.abs() / wo.z.abs();
        if weight.is_finite() {
            weight + LOBE_WEIGHT_FLOOR
        } else {
            LOBE_WEIGHT_FLOOR
        }
    }

    /// Samples a microfacet normal visible from `wo` (either side) by `u_dir`, then reflects off
    /// it with probability F(wo·m) (when `u_lobe` < F) and refracts through it otherwise. `None`
    /// for `wo` in the tangent plane, or when the new direction leaves on the wrong side of the
    /// macro-surface (which the model counts as absorbed, as Mitsuba's G1 = 0 does).
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u_dir: Vec2) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let wo_up = if wo.z > 0.0 { wo } else { -wo };
        let (m, _) = self.distribution.sample_visible_normal(wo_up, u_dir)?;
        let fresnel = fresnel_dielectric(wo.dot(m), self.eta);
        let reflected = u_lobe < fresnel.reflectance;
        let (wi, eta) = if reflected {
            (reflect_about(wo, m), 1.0)
        } else {
            (
                refract_about(wo, m, fresnel.cos_theta_t, fresnel.eta_ti),
                fresnel.eta_it,
            )
        };
        if (wi.z * wo.z > 0.0) != reflected {
            return None;
        }
        let (f, pdf) = self.eval_with_pdf(wo, wi);
        (pdf > 0.0).then_some(BsdfSample {
            f,
            wi,
            pdf_solid_angle: pdf,
            is_delta: false,
            eta,
            is_null: false,
        })
    }
}

impl Model for RoughDielectric {
    #[inline]
    fn flags(&self) -> BsdfFlags {
        let anisotropic = if self.distribution().is_anisotropic() {
            BsdfFlags::ANISOTROPIC
        } else {
            BsdfFlags::EMPTY
        };
        BsdfFlags::GLOSSY | BsdfFlags::TRANSMISSION | BsdfFlags::LOBE_CHOICE | anisotropic
    }

    #[inline]
    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        RoughDielectric::eval(self, wo, wi)
    }

    #[inline]
    fn pdf_solid_angle(&self, wo: Vec3, wi: Vec3) -> f32 {
        RoughDielectric::pdf_solid_angle(self, wo, wi)
    }

    #[inline]
    fn eval_with_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        RoughDielectric::eval_with_pdf(self, wo, wi)
    }

    #[inline]
    fn lobe_weight(&self, wo: Vec3, wi: Vec3) -> Option<f32> {
        Some(RoughDielectric::lobe_weight(self, wo, wi))
    }

    #[inline]
    fn sample(&self, wo: Vec3, u_lobe: f32, u_dir: Vec2) -> Option<BsdfSample> {
        RoughDielectric::sample(self, wo, u_lobe, u_dir)
    }

    fn albedo_hint(&self) -> Vec3 {
        self.normal_albedo()
    }
}
