//! The closed set of BSDFs as one enum, and what sampling one returns.

use crate::blend::Blend;
use crate::bump_map::BumpMap;
use crate::conductor::Conductor;
use crate::dielectric::Dielectric;
use crate::diffuse::Diffuse;
use crate::flags::BsdfFlags;
use crate::normal_map::NormalMap;
use crate::perturbed::SurfacePoint;
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

/// The delta lobes a BSDF chooses among ([`Bsdf::delta_lobes`]): up to two samples.
pub type DeltaLobes = [Option<BsdfSample>; 2];

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

    /// [`Bsdf::delta_lobes`].
    fn delta_lobes(&self, _wo: Vec3) -> DeltaLobes {
        [None, None]
    }

    /// [`Bsdf::with_diffuse_reflectance`].
    fn with_diffuse_reflectance(&self, _reflectance: Vec3) -> Option<Bsdf> {
        None
    }

    /// [`Bsdf::at_surface`].
    fn at_surface(&self, _point: &SurfacePoint) -> Option<Bsdf> {
        None
    }

    /// [`Bsdf::albedo_hint`].
    fn albedo_hint(&self) -> Vec3;

    /// [`Bsdf::flags`].
    fn flags(&self) -> BsdfFlags;
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

            /// Each delta lobe among which [`Self::sample`] chooses, as the sample it gives when
            /// it chooses that lobe (`pdf_solid_angle` the probability of the choice, so that
            /// `f · |cos θi|` is the lobe's whole throughput): a [`Dielectric`]'s reflection and
            /// refraction, a [`Plastic`]'s specular coat. None for BSDFs that choose no delta
            /// lobe against another lobe (a mirror's one lobe is always taken), and for blends
            /// and thin dielectrics, which leave the choice to `sample`. At most one lobe per
            /// side of the surface. A [`TwoSided`] gives the side `wo` sees.
            pub fn delta_lobes(&self, wo: Vec3) -> DeltaLobes {
                match self {
                    $(Self::$variant(b) => Model::delta_lobes(b, wo),)*
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

            /// The BSDF at the surface point `point`, for a BSDF with [`BsdfFlags::AT_SURFACE`] (a
            /// [`NormalMap`] or [`BumpMap`] with its frame perturbed there); `None` for a BSDF that
            /// is the same everywhere, or one made of others (a [`TwoSided`] is resolved to its
            /// side first, and the loader keeps adapters out of blends).
            pub fn at_surface(&self, point: &SurfacePoint) -> Option<Self> {
                match self {
                    $(Self::$variant(b) => Model::at_surface(b, point),)*
                }
            }

            /// The kinds of lobes the BSDF has and what its sampling needs ([`BsdfFlags`]).
            #[inline]
            pub fn flags(&self) -> BsdfFlags {
                match self {
                    $(Self::$variant(b) => Model::flags(b),)*
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
    /// A BSDF under a normal map (Mitsuba's `normalmap`).
    NormalMap(NormalMap),
    /// A BSDF under a bump map (Mitsuba's `bumpmap`).
    BumpMap(BumpMap),
}

impl Bsdf {
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
