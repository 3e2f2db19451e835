//! Mitsuba's `roughplastic`: a diffuse base under a rough dielectric coating, whose
//! microfacets reflect a glossy lobe and let the rest reach the base.

use crate::bsdf::{Bsdf, BsdfSample, Model};
use crate::error::{MaterialError, relative_ior};
use crate::flags::BsdfFlags;
use crate::fresnel::{fresnel_dielectric, reflect_about};
use crate::microfacet::Microfacet;
use crate::plastic::{Coating, specular_sampling_weight};
use glam::{Vec2, Vec3};
use sampling::warp::{cosine_hemisphere_pdf, sample_cosine_hemisphere};
use std::f32::consts::FRAC_1_PI;
use std::sync::Arc;

/// Entries of the coating's transmittance table over cos θ ∈ [0, 1] (Mitsuba's 64).
const TRANSMITTANCE_ENTRIES: usize = 64;

/// Gauss–Legendre points per axis of the visible-normal integrals: Mitsuba's 32 from outside
/// (η > 1); from inside, where total internal reflection cuts the integrand, 64 where Mitsuba
/// takes 128 (R_int within 0.05% of 128's for Beckmann and GGX at α 0.05 and 0.3, for a
/// quarter of the time: 75 ms per Beckmann material).
const QUADRATURE_OUTSIDE: usize = 32;
const QUADRATURE_INSIDE: usize = 64;

/// A rough dielectric coating with relative index η = int_ior / ext_ior and microfacet
/// `distribution` over a Lambertian base, one-sided (black from behind), with two lobes:
///
/// - glossy: the coating's microfacet reflection F(wo·h) D(h) G(wo, wi, h) / (4 cos θo cos θi)
///   · `specular_reflectance`, h = normalize(wo + wi);
/// - diffuse: f = ρ′ / π · T(θo) T(θi) / η², where T(θ) is the fraction of light from θ that
///   the rough interface lets in (its table, interpolated linearly as Mitsuba's), and
///   ρ′ = ρ / (1 − R_int) (or with `nonlinear` ρ / (1 − ρ R_int)), R_int being the fraction of
///   diffuse light from inside that the interface reflects back: 2 ∫ R(μ, 1/η) μ dμ.
///
/// Sampling chooses the glossy lobe with probability proportional to (1 − T(θo)) · w and the
/// diffuse one to T(θo) (1 − w), w as for [`crate::Plastic`]; the pdf is the mixture's.
#[derive(Clone, Debug, PartialEq)]
pub struct RoughPlastic {
    distribution: Microfacet,
    eta: f32,
    inv_eta_sqr: f32,
    /// ρ′: the base's reflectance with the coating's internal reflections summed, RGB.
    base_through_coating: Vec3,
    /// With R_int, the coating's reflectance for diffuse light from inside, as Mitsuba estimates it.
    coating: Coating,
    specular_reflectance: Vec3,
    specular_sampling_weight: f32,
    /// T at cos θ = i / (entries − 1), shared by the copies [`Self::with_diffuse_reflectance`]
    /// makes.
    /// (A fixed-size array, so that the `Arc` is one pointer and the BSDF stays 64 bytes.)
    external_transmittance: Arc<[f32; TRANSMITTANCE_ENTRIES]>,
}

impl RoughPlastic {
    /// A rough coating of `distribution`, interior index `int_ior` over exterior index
    /// `ext_ior` (finite and positive, else an error) on a base of RGB albedo
    /// `diffuse_reflectance`, with an RGB multiplier on the glossy reflection and Mitsuba's
    /// `nonlinear` switch. Builds the coating's tables: about 330,000 visible normals.
    pub fn new(
        distribution: Microfacet,
        int_ior: f32,
        ext_ior: f32,
        diffuse_reflectance: Vec3,
        specular_reflectance: Vec3,
        nonlinear: bool,
    ) -> Result<Self, MaterialError> {
        let eta = relative_ior(int_ior, ext_ior)?;
        let direction = |i: usize| {
            let mu = (i as f32 / (TRANSMITTANCE_ENTRIES - 1) as f32).max(1e-6);
            Vec3::new((1.0 - mu * mu).sqrt(), 0.0, mu)
        };
        let external_transmittance = Arc::new(std::array::from_fn(|i| {
            distribution.interface_albedo(direction(i), eta, false, QUADRATURE_OUTSIDE)
        }));
        // 2 ∫ R μ dμ as Mitsuba estimates it, twice the mean of R μ over the table's cosines:
        // 1.5–2% below the trapezoidal rule's value (which a smooth coating's exact diffuse
        // Fresnel reflectance confirms), taken for the images to agree with Mitsuba's.
        let internal_reflectance = 2.0
            * (0..TRANSMITTANCE_ENTRIES)
                .map(|i| {
                    let w = direction(i);
                    distribution.interface_albedo(w, 1.0 / eta, true, QUADRATURE_INSIDE) * w.z
                })
                .sum::<f32>()
            / TRANSMITTANCE_ENTRIES as f32;
        let coating = Coating {
            internal_reflectance,
            nonlinear,
        };
        Ok(Self {
            distribution,
            eta,
            inv_eta_sqr: 1.0 / (eta * eta),
            base_through_coating: coating.base_through(diffuse_reflectance),
            coating,
            specular_reflectance,
            specular_sampling_weight: specular_sampling_weight(
                diffuse_reflectance,
                specular_reflectance,
            ),
            external_transmittance,
        })
    }

    /// The same coating over a base of RGB albedo `diffuse_reflectance`, keeping this one's
    /// lobe-sampling weight and sharing its tables (no allocation): how a textured base is
    /// shaded, Mitsuba computing the weight once from the texture's mean.
    pub fn with_diffuse_reflectance(&self, diffuse_reflectance: Vec3) -> Self {
        Self {
            base_through_coating: self.coating.base_through(diffuse_reflectance),
            ..self.clone()
        }
    }

    /// R_int: the fraction of diffuse (cosine-distributed) light from inside the coating that
    /// its rough interface reflects back, as Mitsuba estimates it.
    pub fn internal_reflectance(&self) -> f32 {
        self.coating.internal_reflectance
    }

    /// T(θ) for `cos_theta` ∈ [0, 1]: the fraction of light arriving from outside at θ that the
    /// coating lets in, from its table interpolated linearly.
    pub fn transmittance(&self, cos_theta: f32) -> f32 {
        let x = cos_theta.clamp(0.0, 1.0) * (TRANSMITTANCE_ENTRIES - 1) as f32;
        let i = (x as usize).min(TRANSMITTANCE_ENTRIES - 2);
        let t = x - i as f32;
        let table = &self.external_transmittance;
        table[i] + t * (table[i + 1] - table[i])
    }

    /// The probability of sampling the glossy lobe given T(θo).
    fn glossy_probability(&self, transmittance_o: f32) -> f32 {
        let glossy = (1.0 - transmittance_o) * self.specular_sampling_weight;
        let diffuse = transmittance_o * (1.0 - self.specular_sampling_weight);
        let total = glossy + diffuse;
        if total > 0.0 { glossy / total } else { 0.0 }
    }

    /// Reflectance multipliers at normal incidence for heuristics, RGB:
    /// (1 − T(0°)) · `specular_reflectance` + T(0°) · ρ′.
    pub fn normal_albedo(&self) -> Vec3 {
        let t = self.transmittance(1.0);
        (1.0 - t) * self.specular_reflectance + t * self.base_through_coating
    }

    /// f(wo, wi) per steradian, both lobes; 0 unless both directions are above the surface.
    #[inline]
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        self.eval_with_pdf(wo, wi).0
    }

    /// Density per steradian with which [`Self::sample`] produces `wi`: the lobes' densities
    /// weighted by their probabilities.
    #[inline]
    pub fn pdf_solid_angle(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.eval_with_pdf(wo, wi).1
    }

    /// [`Self::eval`] and [`Self::pdf_solid_angle`] together, sharing h, D and T(θo).
    pub fn eval_with_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let transmittance_o = self.transmittance(wo.z);
        let transmittance_i = self.transmittance(wi.z);
        let glossy_probability = self.glossy_probability(transmittance_o);
        let diffuse = self.base_through_coating
            * (FRAC_1_PI * self.inv_eta_sqr * transmittance_o * transmittance_i);
        let mut f = diffuse;
        let mut pdf = (1.0 - glossy_probability) * cosine_hemisphere_pdf(wi.z);
        let h = (wo + wi).normalize_or_zero();
        let d = self.distribution.d(h);
        if d > 0.0 {
            let g = self.distribution.g(wo, wi, h);
            let fresnel = fresnel_dielectric(wo.dot(h), self.eta).reflectance;
            f += self.specular_reflectance * (fresnel * d * g / (4.0 * wo.z * wi.z));
            if wo.dot(h) > 0.0 && wi.dot(h) > 0.0 {
                pdf += glossy_probability * self.distribution.visible_normal_pdf(wo, h)
                    / (4.0 * wo.dot(h));
            }
        }
        (f, pdf)
    }

    /// The glossy lobe when `u_lobe` < its probability (a visible normal from `u_dir`, `wo`
    /// reflected about it), else a cosine-weighted direction from `u_dir`; `f` and the pdf are
    /// both lobes' ([`Self::eval_with_pdf`]). `None` unless `wo` is above the surface and the
    /// direction too.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u_dir: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let glossy_probability = self.glossy_probability(self.transmittance(wo.z));
        let wi = if u_lobe < glossy_probability {
            let (m, _) = self.distribution.sample_visible_normal(wo, u_dir)?;
            reflect_about(wo, m)
        } else {
            sample_cosine_hemisphere(u_dir)
        };
        let (f, pdf) = self.eval_with_pdf(wo, wi);
        (pdf > 0.0 && pdf.is_finite()).then_some(BsdfSample {
            f,
            wi,
            pdf_solid_angle: pdf,
            is_delta: false,
            eta: 1.0,
            is_null: false,
        })
    }

    /// For choosing among lights by resampling: the glossy lobe's D(h) / (4 cos θo) plus the
    /// diffuse lobe's T(θo) ρ′ cos θi / π (mean over RGB) plus [`crate::LOBE_WEIGHT_FLOOR`],
    /// sr⁻¹: f · cos θi without F, G and the factors near 1.
    pub fn lobe_weight(&self, wo: Vec3, wi: Vec3) -> f32 {
        let floor = crate::LOBE_WEIGHT_FLOOR;
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return floor;
        }
        let glossy = self.distribution.d((wo + wi).normalize_or_zero()) / (4.0 * wo.z);
        let diffuse = self.transmittance(wo.z) * self.base_through_coating.element_sum()
            / (3.0 * std::f32::consts::PI);
        let weight = glossy + diffuse * wi.z;
        if weight.is_finite() {
            weight + floor
        } else {
            floor
        }
    }
}

impl Model for RoughPlastic {
    #[inline]
    fn flags(&self) -> BsdfFlags {
        BsdfFlags::DIFFUSE | BsdfFlags::GLOSSY | BsdfFlags::LOBE_CHOICE
    }

    #[inline]
    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        RoughPlastic::eval(self, wo, wi)
    }

    #[inline]
    fn pdf_solid_angle(&self, wo: Vec3, wi: Vec3) -> f32 {
        RoughPlastic::pdf_solid_angle(self, wo, wi)
    }

    #[inline]
    fn eval_with_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        RoughPlastic::eval_with_pdf(self, wo, wi)
    }

    #[inline]
    fn lobe_weight(&self, wo: Vec3, wi: Vec3) -> Option<f32> {
        Some(RoughPlastic::lobe_weight(self, wo, wi))
    }

    #[inline]
    fn sample(&self, wo: Vec3, u_lobe: f32, u_dir: Vec2) -> Option<BsdfSample> {
        RoughPlastic::sample(self, wo, u_lobe, u_dir)
    }

    fn with_diffuse_reflectance(&self, reflectance: Vec3) -> Option<Bsdf> {
        Some(RoughPlastic::with_diffuse_reflectance(self, reflectance).into())
    }

    fn albedo_hint(&self) -> Vec3 {
        self.normal_albedo()
    }
}
