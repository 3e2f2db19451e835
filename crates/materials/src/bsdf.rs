//! The closed set of BSDFs as one enum, and what sampling one returns.

use crate::blend::Blend;
use crate::conductor::Conductor;
use crate::dielectric::Dielectric;
use crate::diffuse::Diffuse;
use crate::plastic::Plastic;
use crate::rough_conductor::RoughConductor;
use crate::rough_dielectric::RoughDielectric;
use crate::rough_plastic::RoughPlastic;
use crate::thin_dielectric::ThinDielectric;
use crate::two_sided::TwoSided;
use glam::{Vec2, Vec3};

/// A direction drawn by [`Bsdf::sample`], with what an estimator needs to weight it.
///
/// The estimator weight is always `f * wi.z.abs() / pdf_solid_angle`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BsdfSample {
    /// For a non-delta lobe: the BSDF value f(wo, wi) per steradian, RGB, without the cosine,
    /// equal to [`Bsdf::eval`]. For a delta lobe: the lobe's reflectance or transmittance divided
    /// by |cos θi| and multiplied by `pdf_solid_angle` (pbrt's convention), so the weight above
    /// is the lobe's throughput divided by the probability of having chosen it.
    pub f: Vec3,
    /// The sampled direction, unit length, pointing away from the surface (local frame).
    pub wi: Vec3,
    /// For a non-delta lobe: density per steradian of `wi`, equal to [`Bsdf::pdf_solid_angle`].
    /// For a delta lobe: the discrete probability of having chosen this lobe (in (0, 1]).
    pub pdf_solid_angle: f32,
    /// Whether `wi` came from a delta lobe (perfect mirror or refraction).
    pub is_delta: bool,
    /// Whether `wi` continues straight on through the surface (`wi = −wo`, no refraction): a
    /// thin dielectric's transmission, Mitsuba's null lobe (its `null` and `mask` are read as
    /// thin slabs of index 1). Mitsuba's volumetric path tracers do not count such a pass as a
    /// path vertex.
    pub is_null: bool,
    /// The relative index of refraction crossed: η (inside over outside) when entering a
    /// dielectric, 1/η when leaving it, 1 for reflection.
    pub eta: f32,
}

/// What each BSDF of the set provides, with one signature for all, so that [`Bsdf`]'s methods
/// can forward to it (see `bsdf_set!`). The defaults fit a BSDF made of delta lobes only, which
/// `eval` and `pdf_solid_angle` never see, and one without a diffuse albedo to replace.
pub(crate) trait Model {
    /// [`Bsdf::eval`].
    #[inline]
    fn eval(&self, _wo: Vec3, _wi: Vec3) -> Vec3 {
        Vec3::ZERO
    }

    /// [`Bsdf::pdf_solid_angle`].
    #[inline]
    fn pdf_solid_angle(&self, _wo: Vec3, _wi: Vec3) -> f32 {
        0.0
    }

    /// [`Bsdf::eval_with_pdf`].
    #[inline]
    fn eval_with_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        (self.eval(wo, wi), self.pdf_solid_angle(wo, wi))
    }

    /// [`Bsdf::lobe_weight`].
    #[inline]
    fn lobe_weight(&self, _wo: Vec3, _wi: Vec3) -> Option<f32> {
        None
    }

    /// [`Bsdf::sample`].
    fn sample(&self, wo: Vec3, u_lobe: f32, u_dir: Vec2) -> Option<BsdfSample>;

    /// [`Bsdf::sample_delta`].
    fn sample_delta(&self, _wo: Vec3, _u_lobe: f32) -> Option<BsdfSample> {
        None
    }

    /// [`Bsdf::with_diffuse_reflectance`].
    fn with_diffuse_reflectance(&self, _reflectance: Vec3) -> Option<Bsdf> {
        None
    }

    /// [`Bsdf::albedo_hint`].
    fn albedo_hint(&self) -> Vec3;
}

/// Declares the closed set of BSDFs once: each line names a variant and the struct it holds
/// (which implements [`Model`] in its own file). Generates the [`Bsdf`] enum, a `From` for each
/// struct, and [`Bsdf`]'s methods that forward to the variant's [`Model`].
macro_rules! bsdf_set {
    ($($(#[$doc:meta])* $variant:ident($ty:ident),)*) => {
        /// Any of Strata's BSDFs, in the local shading frame (see the crate documentation).
        #[derive(Clone, Debug, PartialEq)]
        pub enum Bsdf {
            $($(#[$doc])* $variant($ty),)*
        }

        $(impl From<$ty> for Bsdf {
            fn from(b: $ty) -> Self {
                Self::$variant(b)
            }
        })*

        impl Bsdf {
            /// f(wo, wi) per steradian, RGB, without the cosine factor; 0 for delta lobes.
            #[inline]
            pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
                match self {
                    $(Self::$variant(b) => Model::eval(b, wo, wi),)*
                }
            }

            /// Density per steradian with which [`Self::sample`] produces `wi` from `wo`; 0 for
            /// delta lobes (whose samples have no density).
            #[inline]
            pub fn pdf_solid_angle(&self, wo: Vec3, wi: Vec3) -> f32 {
                match self {
                    $(Self::$variant(b) => Model::pdf_solid_angle(b, wo, wi),)*
                }
            }

            /// [`Self::eval`] and [`Self::pdf_solid_angle`] in one call, which shares the work the
            /// two have in common (a rough conductor's half vector and D): the same values as the
            /// two calls.
            #[inline]
            pub fn eval_with_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
                match self {
                    $(Self::$variant(b) => Model::eval_with_pdf(b, wo, wi),)*
                }
            }

            /// For choosing among lights by resampling: a cheap positive estimate of f · cos θi
            /// towards `wi`, sr⁻¹ (a rough conductor's [`RoughConductor::lobe_weight`]), or `None`
            /// for BSDFs whose reflection varies little with the direction (diffuse) or has no
            /// density (delta lobes), where the light's irradiance alone should decide.
            #[inline]
            pub fn lobe_weight(&self, wo: Vec3, wi: Vec3) -> Option<f32> {
                match self {
                    $(Self::$variant(b) => Model::lobe_weight(b, wo, wi),)*
                }
            }

            /// Importance-samples a direction `wi` for `wo`. `u_lobe` ∈ [0, 1) chooses among lobes
            /// (the dielectric's reflection or refraction), `u_dir` ∈ [0, 1)² the direction within
            /// the lobe. `None` when there is no valid direction (e.g. `wo` behind a one-sided
            /// BSDF, or a rough reflection that lands below the surface), which the estimator
            /// counts as zero.
            #[inline]
            pub fn sample(&self, wo: Vec3, u_lobe: f32, u_dir: Vec2) -> Option<BsdfSample> {
                match self {
                    $(Self::$variant(b) => Model::sample(b, wo, u_lobe, u_dir),)*
                }
            }

            /// Samples the delta lobes alone, for strategies that find the other lobes by
            /// directions of their own: as [`Self::sample`] for a BSDF whose lobes are all deltas,
            /// the specular lobe of a [`Plastic`] with probability 1 (its weight
            /// F · `specular_reflectance`), `None` for a BSDF without delta lobes. A [`TwoSided`]
            /// samples the side `wo` sees.
            pub fn sample_delta(&self, wo: Vec3, u_lobe: f32) -> Option<BsdfSample> {
                match self {
                    $(Self::$variant(b) => Model::sample_delta(b, wo, u_lobe),)*
                }
            }

            /// This BSDF with its diffuse albedo replaced by the RGB `reflectance` (a texture's
            /// value at a hit): a [`Diffuse`] with that reflectance, a [`Plastic`] or
            /// [`RoughPlastic`] with that base ([`Plastic::with_diffuse_reflectance`]), a
            /// [`TwoSided`] with both sides so (which allocates them; integrators resolve a
            /// surface's own two-sided BSDF to its side first); `None` for BSDFs that have no
            /// diffuse albedo to replace.
            pub fn with_diffuse_reflectance(&self, reflectance: Vec3) -> Option<Self> {
                match self {
                    $(Self::$variant(b) => Model::with_diffuse_reflectance(b, reflectance),)*
                }
            }

            /// A rough RGB albedo for heuristics (Russian roulette, choosing techniques), not for
            /// shading: the diffuse reflectance; for conductors the reflectance at normal
            /// incidence (`specular_reflectance` × Fresnel at cos θ = 1, ignoring microfacet
            /// shadowing); for a dielectric F₀ · `specular_reflectance` + (1 − F₀) ·
            /// `specular_transmittance`; for a plastic F₀ · `specular_reflectance` + (1 − F₀) · its
            /// base seen through the coating; for a [`TwoSided`] the mean of its two sides.
            pub fn albedo_hint(&self) -> Vec3 {
                match self {
                    $(Self::$variant(b) => Model::albedo_hint(b),)*
                }
            }
        }
    };
}

bsdf_set! {
    /// Lambertian reflection (Mitsuba's `diffuse`).
    Diffuse(Diffuse),
    /// Smooth metal, a perfect mirror (Mitsuba's `conductor`).
    Conductor(Conductor),
    /// Rough metal, a microfacet model (Mitsuba's `roughconductor`).
    RoughConductor(RoughConductor),
    /// Smooth glass-like interface (Mitsuba's `dielectric`).
    Dielectric(Dielectric),
    /// Rough glass-like interface, a microfacet model (Mitsuba's `roughdielectric`).
    RoughDielectric(RoughDielectric),
    /// A thin pane of glass, reflecting and letting light straight through (Mitsuba's
    /// `thindielectric`).
    ThinDielectric(ThinDielectric),
    /// A diffuse base under a smooth dielectric coating (Mitsuba's `plastic`): a delta lobe
    /// and a diffuse one.
    Plastic(Plastic),
    /// A diffuse base under a rough dielectric coating (Mitsuba's `roughplastic`): a glossy
    /// lobe and a diffuse one.
    RoughPlastic(RoughPlastic),
    /// A reflecting BSDF seen the same from both sides (Mitsuba's `twosided`).
    TwoSided(TwoSided),
    /// Two BSDFs blended by a constant weight (Mitsuba's `blendbsdf`).
    Blend(Blend),
}

impl Bsdf {
    /// Whether the BSDF has a glossy lobe, whose reflection depends strongly on the direction
    /// without being a delta (a rough conductor, dielectric or plastic, or a twosided with one on
    /// either side): where
    /// [`Self::lobe_weight`] is given.
    pub fn is_glossy(&self) -> bool {
        match self {
            Self::RoughConductor(_) | Self::RoughDielectric(_) | Self::RoughPlastic(_) => true,
            Self::TwoSided(b) => b.front().is_glossy() || b.back().is_glossy(),
            Self::Blend(b) => b.first().is_glossy() || b.second().is_glossy(),
            Self::Diffuse(_)
            | Self::Conductor(_)
            | Self::Dielectric(_)
            | Self::ThinDielectric(_)
            | Self::Plastic(_) => false,
        }
    }

    /// Whether the BSDF (or a BSDF it holds) has anisotropic roughness, so that it depends on
    /// how the shading frame is turned about the normal: the frame must then follow the
    /// surface's parameterisation (its first tangent along ∂p/∂u, as Mitsuba's), which the
    /// isotropic BSDFs do not need.
    pub fn is_anisotropic(&self) -> bool {
        match self {
            Self::RoughConductor(b) => b.distribution().is_anisotropic(),
            Self::RoughDielectric(b) => b.distribution().is_anisotropic(),
            Self::TwoSided(b) => b.front().is_anisotropic() || b.back().is_anisotropic(),
            Self::Blend(b) => b.first().is_anisotropic() || b.second().is_anisotropic(),
            Self::Diffuse(_)
            | Self::Conductor(_)
            | Self::Dielectric(_)
            | Self::ThinDielectric(_)
            | Self::Plastic(_)
            | Self::RoughPlastic(_) => false,
        }
    }
    /// Whether the BSDF has delta lobes and lobes with a density at once (a [`Plastic`], or a
    /// [`TwoSided`] with one on either side): strategies that sample directions without the
    /// BSDF's help must then reach its delta lobes by [`Self::sample_delta`].
    #[inline]
    pub fn is_mixed(&self) -> bool {
        match self {
            Self::Plastic(_) => true,
            Self::TwoSided(b) => b.front().is_mixed() || b.back().is_mixed(),
            Self::Blend(b) => self.has_delta_lobe() && !b.is_delta(),
            Self::Diffuse(_)
            | Self::Conductor(_)
            | Self::RoughConductor(_)
            | Self::Dielectric(_)
            | Self::RoughDielectric(_)
            | Self::RoughPlastic(_)
            | Self::ThinDielectric(_) => false,
        }
    }

    /// Whether every lobe is a delta (mirror, smooth dielectric): then `eval` and
    /// `pdf_solid_angle` are always 0 and light sampling at this surface is pointless. A
    /// [`TwoSided`] is delta only when both sides are; integrators resolve it to the side a ray
    /// sees ([`TwoSided::facing`]) before asking.
    #[inline]
    pub fn is_delta(&self) -> bool {
        match self {
            Self::Conductor(_) | Self::Dielectric(_) | Self::ThinDielectric(_) => true,
            Self::Diffuse(_)
            | Self::RoughConductor(_)
            | Self::RoughDielectric(_)
            | Self::RoughPlastic(_)
            | Self::Plastic(_) => false,
            Self::TwoSided(b) => b.is_delta(),
            Self::Blend(b) => b.is_delta(),
        }
    }

    /// Whether at least one lobe is a delta, so some samples have `is_delta` set. Equal to
    /// [`Self::is_delta`] except for a [`TwoSided`] with a delta BSDF on one side only.
    #[inline]
    pub fn has_delta_lobe(&self) -> bool {
        match self {
            Self::TwoSided(b) => b.front().has_delta_lobe() || b.back().has_delta_lobe(),
            Self::Blend(b) => b.first().has_delta_lobe() || b.second().has_delta_lobe(),
            Self::Plastic(_) => true,
            _ => self.is_delta(),
        }
    }

    /// Whether some sample can have `is_null` set ([`BsdfSample::is_null`]): a thin dielectric,
    /// alone or in a blend.
    #[inline]
    pub fn has_null_lobe(&self) -> bool {
        match self {
            Self::ThinDielectric(_) => true,
            Self::TwoSided(b) => b.front().has_null_lobe() || b.back().has_null_lobe(),
            Self::Blend(b) => b.first().has_null_lobe() || b.second().has_null_lobe(),
            _ => false,
        }
    }

    /// Whether [`Self::sample`] uses its `u_lobe` number (to choose between reflection and
    /// refraction); the other BSDFs ignore it.
    #[inline]
    pub fn uses_lobe_choice(&self) -> bool {
        match self {
            Self::Dielectric(_)
            | Self::RoughDielectric(_)
            | Self::ThinDielectric(_)
            | Self::Plastic(_)
            | Self::RoughPlastic(_) => true,
            Self::Diffuse(_) | Self::Conductor(_) | Self::RoughConductor(_) => false,
            Self::TwoSided(b) => b.front().uses_lobe_choice() || b.back().uses_lobe_choice(),
            Self::Blend(_) => true,
        }
    }

    /// Whether light can pass to the other side of the surface (a dielectric, thin, rough or
    /// smooth).
    pub fn has_transmission(&self) -> bool {
        match self {
            Self::Dielectric(_) | Self::RoughDielectric(_) | Self::ThinDielectric(_) => true,
            Self::Diffuse(_)
            | Self::Conductor(_)
            | Self::RoughConductor(_)
            | Self::Plastic(_)
            | Self::RoughPlastic(_) => false,
            Self::TwoSided(b) => b.front().has_transmission() || b.back().has_transmission(),
            Self::Blend(b) => b.first().has_transmission() || b.second().has_transmission(),
        }
    }
    /// A [`Blend`] with a texture's values at a hit ([`Blend::with_textures`]: its weight and
    /// either BSDF's diffuse reflectance); `None` for other BSDFs, or when a BSDF given a
    /// reflectance has none.
    pub fn with_blend_textures(
        &self,
        weight: Option<f32>,
        reflectances: [Option<Vec3>; 2],
    ) -> Option<Self> {
        match self {
            Self::Blend(b) => b.with_textures(weight, reflectances).map(Self::Blend),
            _ => None,
        }
    }
}
