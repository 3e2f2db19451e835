//! Mitsuba's `blendbsdf`: a linear blend of two BSDFs by a constant weight.

use crate::bsdf::{Bsdf, BsdfSample, Model};
use crate::error::MaterialError;
use crate::flags::BsdfFlags;
use crate::rough_conductor::LOBE_WEIGHT_FLOOR;
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;
use std::sync::Arc;

/// f = (1 − w) f₀ + w f₁ for a weight w in [0, 1]: the first BSDF at w = 0, the second at 1.
///
/// Sampling picks the second BSDF with probability w (when `u_lobe` < w, the rest of `u_lobe`
/// passed on) and samples it; a sample of a density lobe gets the blend's value and the
/// mixture density (1 − w) p₀ + w p₁ (one-sample MIS, as Mitsuba's), a delta sample keeps its
/// weight, which is the chosen BSDF's.
#[derive(Clone, Debug, PartialEq)]
pub struct Blend {
    /// Shared by the copies [`Self::with_textures`] makes.
    first: Arc<Bsdf>,
    second: Arc<Bsdf>,
    weight: f32,
    /// The union of both BSDFs' flags, with [`BsdfFlags::MIXED`] when the blend has delta and
    /// density lobes and [`BsdfFlags::LOBE_CHOICE`] always (it chooses between its BSDFs).
    flags: BsdfFlags,
}

impl Blend {
    /// `first` and `second` blended by `weight` (Mitsuba's `weight`, in [0, 1], else an error).
    pub fn new(first: Bsdf, second: Bsdf, weight: f32) -> Result<Self, MaterialError> {
        if !(0.0..=1.0).contains(&weight) {
            return Err(MaterialError::InvalidBlendWeight { value: weight });
        }
        Ok(Self {
            flags: blend_flags(first.flags() | second.flags()),
            first: Arc::new(first),
            second: Arc::new(second),
            weight,
        })
    }

    /// The blend with a texture's values at a hit: `weight` (clamped to [0, 1], as Mitsuba clamps
    /// a texture's weight) in place of its own unless `None`, and each BSDF with the diffuse
    /// reflectance given for it ([`Bsdf::with_diffuse_reflectance`]), RGB in [0, 1]; `None` when
    /// a BSDF given one has no diffuse reflectance. The BSDFs given none are shared (no
    /// allocation); each one given a reflectance is allocated anew.
    pub fn with_textures(
        &self,
        weight: Option<f32>,
        reflectances: [Option<Vec3>; 2],
    ) -> Option<Self> {
        let part = |bsdf: &Arc<Bsdf>, reflectance: Option<Vec3>| match reflectance {
            None => Some(Arc::clone(bsdf)),
            Some(reflectance) => bsdf.with_diffuse_reflectance(reflectance).map(Arc::new),
        };
        Some(Self {
            first: part(&self.first, reflectances[0])?,
            second: part(&self.second, reflectances[1])?,
            weight: weight.map_or(self.weight, |w| w.clamp(0.0, 1.0)),
            flags: self.flags,
        })
    }

    /// The BSDF at weight 0.
    pub fn first(&self) -> &Bsdf {
        &self.first
    }

    /// The BSDF at weight 1.
    pub fn second(&self) -> &Bsdf {
        &self.second
    }

    /// The weight of the second BSDF.
    pub fn weight(&self) -> f32 {
        self.weight
    }

    /// (1 − w) f₀ + w f₁ per steradian.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        self.first.eval(wo, wi) * (1.0 - self.weight) + self.second.eval(wo, wi) * self.weight
    }

    /// (1 − w) p₀ + w p₁ per steradian: the density of [`Self::sample`]'s non-delta samples.
    pub fn pdf_solid_angle(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.eval_with_pdf(wo, wi).1
    }

    /// [`Self::eval`] and [`Self::pdf_solid_angle`] together.
    pub fn eval_with_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        let (f0, p0) = self.first.eval_with_pdf(wo, wi);
        let (f1, p1) = self.second.eval_with_pdf(wo, wi);
        let w = self.weight;
        (f0 * (1.0 - w) + f1 * w, p0 * (1.0 - w) + p1 * w)
    }

    /// A cheap positive estimate of f · cos θi, sr⁻¹, for resampled light choice: the blend of
    /// the two BSDFs' lobe weights, a BSDF without one counted as Lambertian with its albedo
    /// hint (plus [`LOBE_WEIGHT_FLOOR`]).
    pub fn lobe_weight(&self, wo: Vec3, wi: Vec3) -> f32 {
        let estimate = |b: &Bsdf| {
            b.lobe_weight(wo, wi).unwrap_or_else(|| {
                b.albedo_hint().element_sum() / 3.0 * FRAC_1_PI * wi.z.abs() + LOBE_WEIGHT_FLOOR
            })
        };
        estimate(&self.first) * (1.0 - self.weight) + estimate(&self.second) * self.weight
    }

    /// Which BSDF `u_lobe` chooses, its probability and `u_lobe` rescaled to [0, 1) within it.
    fn choose(&self, u_lobe: f32) -> (&Bsdf, f32, f32) {
        let w = self.weight;
        if u_lobe < w {
            (&self.second, w, (u_lobe / w).min(ONE_MINUS_EPSILON))
        } else {
            (
                &self.first,
                1.0 - w,
                ((u_lobe - w) / (1.0 - w)).min(ONE_MINUS_EPSILON),
            )
        }
    }

    /// Samples the BSDF `u_lobe` chooses; see the type's documentation for the weights.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u_dir: Vec2) -> Option<BsdfSample> {
        let (chosen, probability, u_rest) = self.choose(u_lobe);
        let mut sample = chosen.sample(wo, u_rest, u_dir)?;
        if sample.is_delta {
            // The blend's delta lobe is `probability` times the chosen one's.
            sample.f *= probability;
            sample.pdf_solid_angle *= probability;
            return Some(sample);
        }
        let (f, pdf) = self.eval_with_pdf(wo, sample.wi);
        (pdf > 0.0).then_some(BsdfSample {
            f,
            pdf_solid_angle: pdf,
            ..sample
        })
    }

    /// The delta lobes alone ([`Bsdf::sample_delta`]): of the BSDF that has them, or of the one
    /// `u_lobe` chooses when both have, weighted by its share of the blend.
    pub fn sample_delta(&self, wo: Vec3, u_lobe: f32) -> Option<BsdfSample> {
        let has_delta = |b: &Bsdf| b.flags().contains(BsdfFlags::DELTA);
        let (first, second) = (has_delta(&self.first), has_delta(&self.second));
        let (chosen, share, probability, u_rest) = match (first, second) {
            (true, true) => {
                let (chosen, probability, u_rest) = self.choose(u_lobe);
                (chosen, probability, probability, u_rest)
            }
            (true, false) => (&*self.first, 1.0 - self.weight, 1.0, u_lobe),
            (false, true) => (&*self.second, self.weight, 1.0, u_lobe),
            (false, false) => return None,
        };
        let mut sample = chosen.sample_delta(wo, u_rest)?;
        sample.f *= share;
        sample.pdf_solid_angle *= probability;
        Some(sample)
    }
}

/// A blend's flags from the union of its BSDFs' `parts`: mixed when it has delta and density
/// lobes, and always choosing a lobe.
fn blend_flags(parts: BsdfFlags) -> BsdfFlags {
    let mixed = if parts.contains(BsdfFlags::DELTA) && !parts.is_delta() {
        BsdfFlags::MIXED
    } else {
        BsdfFlags::EMPTY
    };
    parts | mixed | BsdfFlags::LOBE_CHOICE
}

/// The largest `f32` below 1.
const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

impl Model for Blend {
    #[inline]
    fn flags(&self) -> BsdfFlags {
        self.flags
    }

    #[inline]
    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        Blend::eval(self, wo, wi)
    }

    #[inline]
    fn pdf_solid_angle(&self, wo: Vec3, wi: Vec3) -> f32 {
        Blend::pdf_solid_angle(self, wo, wi)
    }

    #[inline]
    fn eval_with_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        Blend::eval_with_pdf(self, wo, wi)
    }

    #[inline]
    fn lobe_weight(&self, wo: Vec3, wi: Vec3) -> Option<f32> {
        let glossy = self.flags.contains(BsdfFlags::GLOSSY);
        glossy.then(|| Blend::lobe_weight(self, wo, wi))
    }

    #[inline]
    fn sample(&self, wo: Vec3, u_lobe: f32, u_dir: Vec2) -> Option<BsdfSample> {
        Blend::sample(self, wo, u_lobe, u_dir)
    }

    fn sample_delta(&self, wo: Vec3, u_lobe: f32) -> Option<BsdfSample> {
        Blend::sample_delta(self, wo, u_lobe)
    }

    fn albedo_hint(&self) -> Vec3 {
        self.first.albedo_hint() * (1.0 - self.weight) + self.second.albedo_hint() * self.weight
    }
}
