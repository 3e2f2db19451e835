//! The closed set of emitter types as one enum, declared once by `light_set!`.

use crate::{
    ConstantEnvironment, DirectionalLight, EmissionSample, EnvironmentMap, LightSample,
    MeshAreaLight, MovingLight, PointLight, SphereAreaLight, SpotLight,
};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// What kind of emitter a light of the set is, which decides how rays and estimators meet it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    /// An emitting surface: rays hit it, and light tracing starts paths on it.
    Area,
    /// A point or a direction that no randomly sampled ray can hit (point, spot, directional).
    Delta,
    /// Light from infinitely far away, which rays that escape the scene see.
    Environment,
}

/// What each light of the set provides, with one signature for all, so that [`Light`]'s methods
/// can forward to it (see `light_set!`). The defaults fit a light without a surface: it emits
/// nothing towards a ray that hits something, has no surface density and starts no light paths.
pub(crate) trait Emitter {
    /// Whether this is an area, delta or environment light ([`Light::is_area`],
    /// [`Light::is_delta`], [`Light::is_environment`]).
    const KIND: Kind;

    /// [`Light::sample_li`].
    fn sample_li(&self, p: Vec3, u: Vec2, time: f32) -> Option<LightSample>;

    /// [`Light::sample_emission`].
    #[inline]
    fn sample_emission(&self, _u_point: Vec2, _u_dir: Vec2, _time: f32) -> Option<EmissionSample> {
        None
    }

    /// [`Light::radiance_towards`].
    #[inline]
    fn radiance_towards(&self, _ng: Vec3, _w: Vec3) -> Vec3 {
        Vec3::ZERO
    }

    /// [`Light::radiance_from_direction`].
    #[inline]
    fn radiance_from_direction(&self, _w: Vec3) -> Vec3 {
        Vec3::ZERO
    }

    /// [`Light::pdf_li_surface`].
    #[inline]
    fn pdf_li_surface(&self, _p: Vec3, _p_light: Vec3, _n_light: Vec3, _time: f32) -> f32 {
        0.0
    }

    /// [`Light::pdf_li_environment`].
    #[inline]
    fn pdf_li_environment(&self, _w: Vec3) -> f32 {
        0.0
    }

    /// [`Light::pdf_emission_area`].
    #[inline]
    fn pdf_emission_area(&self, _n_light: Vec3, _time: f32) -> f32 {
        0.0
    }

    /// [`Light::bounding_sphere`].
    fn bounding_sphere(&self) -> Option<(Vec3, f32)> {
        None
    }

    /// [`Light::towards`]: the vector to the bounding sphere's centre.
    fn towards(&self, p: Vec3) -> Option<Vec3> {
        self.bounding_sphere().map(|(centre, _)| centre - p)
    }

    /// [`Light::irradiance_estimate`]: by default power / (4π max(d², r²)) for the light's
    /// bounding sphere, times a bound on |cos θ| over it; zero without a bounding sphere.
    fn irradiance_estimate(&self, p: Vec3, n: Vec3) -> f32 {
        let Some((center, radius)) = self.bounding_sphere() else {
            return 0.0;
        };
        let to_center = center - p;
        let d2 = to_center.length_squared();
        let r2 = radius * radius;
        if d2 <= r2 {
            return self.power() / (4.0 * PI * r2.max(f32::MIN_POSITIVE));
        }
        let cos_center = to_center.dot(n).abs() / d2.sqrt();
        let sin_max = (r2 / d2).sqrt();
        self.power() / (4.0 * PI * d2) * (cos_center + sin_max).min(1.0)
    }

    /// [`Light::power`].
    fn power(&self) -> f32;
}

/// The radiance of a one-sided area emitter seen from the unit direction `w` at a point with
/// geometric normal `ng`: `radiance` on the side `ng` points to, zero on the other.
#[inline]
pub(crate) fn one_sided(radiance: Vec3, ng: Vec3, w: Vec3) -> Vec3 {
    if ng.dot(w) > 0.0 {
        radiance
    } else {
        Vec3::ZERO
    }
}

/// Declares the closed set of lights once: each line names a variant and the struct it holds
/// (which implements [`Emitter`] in its own file). Generates the [`Light`] enum, a `From` for
/// each struct, [`Light::KINDS`] and [`Light`]'s methods that forward to the variant's
/// [`Emitter`].
macro_rules! light_set {
    ($($(#[$doc:meta])* $variant:ident($ty:ident),)*) => {
        /// Any emitter in a scene.
        #[derive(Clone, Debug)]
        pub enum Light {
            $($(#[$doc])* $variant($ty),)*
        }

        $(impl From<$ty> for Light {
            fn from(light: $ty) -> Self {
                Self::$variant(light)
            }
        })*

        impl Light {
            /// The name of every variant, in the order of the set (what [`Self::kind`] returns).
            pub const KINDS: &'static [&'static str] = &[$(stringify!($variant),)*];

            /// The name of this light's variant, one of [`Self::KINDS`].
            pub fn kind(&self) -> &'static str {
                match self {
                    $(Self::$variant(_) => stringify!($variant),)*
                }
            }

            /// A direction from the shading point `p` towards the light, with `u` uniform in
            /// [0, 1)². `None` when the sample carries no light (e.g. a back-facing point). A
            /// moving light is sampled where it is at `time`, a fraction of the shutter interval
            /// ([`geometry::Ray::time`]).
            #[inline]
            pub fn sample_li(&self, p: Vec3, u: Vec2, time: f32) -> Option<LightSample> {
                match self {
                    $(Self::$variant(l) => Emitter::sample_li(l, p, u, time),)*
                }
            }

            /// Light leaving an area emitter's surface (see [`EmissionSample`]), with `u_point`
            /// and `u_dir` uniform in [0, 1)²; `None` for delta lights and the environment, which
            /// light tracing leaves to the path tracer. A moving light emits where it is at
            /// `time`.
            #[inline]
            pub fn sample_emission(
                &self,
                u_point: Vec2,
                u_dir: Vec2,
                time: f32,
            ) -> Option<EmissionSample> {
                match self {
                    $(Self::$variant(l) => Emitter::sample_emission(l, u_point, u_dir, time),)*
                }
            }

            /// Radiance (W m⁻² sr⁻¹, RGB) leaving a point of this light's surface with geometric
            /// normal `ng` towards the unit direction `w`: zero behind a one-sided emitter, and
            /// for lights without a surface.
            #[inline]
            pub fn radiance_towards(&self, ng: Vec3, w: Vec3) -> Vec3 {
                match self {
                    $(Self::$variant(l) => Emitter::radiance_towards(l, ng, w),)*
                }
            }

            /// Radiance (W m⁻² sr⁻¹, RGB) arriving along a ray that escapes the scene in the unit
            /// direction `w` (pointing away from the scene): the environment's radiance, zero for
            /// every other light.
            #[inline]
            pub fn radiance_from_direction(&self, w: Vec3) -> Vec3 {
                match self {
                    $(Self::$variant(l) => Emitter::radiance_from_direction(l, w),)*
                }
            }

            /// Density per steradian with which [`Self::sample_li`] from `p` would have chosen
            /// the point `p_light` with geometric normal `n_light` on this light's surface. Zero
            /// for lights without a surface (delta lights, the environment). A moving light's
            /// surface is where it is at `time`.
            #[inline]
            pub fn pdf_li_surface(&self, p: Vec3, p_light: Vec3, n_light: Vec3, time: f32) -> f32 {
                match self {
                    $(Self::$variant(l) => Emitter::pdf_li_surface(l, p, p_light, n_light, time),)*
                }
            }

            /// Density per steradian with which [`Self::sample_li`] picks the unit direction `w`
            /// that escapes the scene: the environment's density, zero for every other light.
            #[inline]
            pub fn pdf_li_environment(&self, w: Vec3) -> f32 {
                match self {
                    $(Self::$variant(l) => Emitter::pdf_li_environment(l, w),)*
                }
            }

            /// Density per unit area (world units⁻²) with which [`Self::sample_emission`] at
            /// `time` picks a point of the light's surface whose geometric normal is `n_light`:
            /// 1 / area, as it picks points uniformly by area. Zero for lights without a
            /// surface.
            #[inline]
            pub fn pdf_emission_area(&self, n_light: Vec3, time: f32) -> f32 {
                match self {
                    $(Self::$variant(l) => Emitter::pdf_emission_area(l, n_light, time),)*
                }
            }

            /// Whether the light is an emitting surface (on a mesh or a sphere, moving or not),
            /// which rays can hit and light tracing starts paths on.
            #[inline]
            pub fn is_area(&self) -> bool {
                match self {
                    $(Self::$variant(_) => <$ty as Emitter>::KIND == Kind::Area,)*
                }
            }

            /// Whether the light is an environment (constant or a map), which rays that escape
            /// the scene see.
            #[inline]
            pub fn is_environment(&self) -> bool {
                match self {
                    $(Self::$variant(_) => <$ty as Emitter>::KIND == Kind::Environment,)*
                }
            }

            /// True for lights that a randomly sampled ray can never hit (point, spot and
            /// directional lights).
            #[inline]
            pub fn is_delta(&self) -> bool {
                match self {
                    $(Self::$variant(_) => <$ty as Emitter>::KIND == Kind::Delta,)*
                }
            }

            /// A sphere (centre, radius; world units) holding the light's emitting surface or
            /// point (radius 0); `None` for the environment and directional lights, which lie at
            /// infinity.
            pub fn bounding_sphere(&self) -> Option<(Vec3, f32)> {
                match self {
                    $(Self::$variant(l) => Emitter::bounding_sphere(l),)*
                }
            }

            /// A vector from `p` towards the light, of any length: to the centre of its
            /// [`bounding sphere`](Self::bounding_sphere), or a directional light's direction
            /// towards it; `None` for the environment, which surrounds `p`.
            pub fn towards(&self, p: Vec3) -> Option<Vec3> {
                match self {
                    $(Self::$variant(l) => Emitter::towards(l, p),)*
                }
            }

            /// Irradiance (W m⁻², mean over channels) that the light could deliver at most,
            /// roughly, to a surface at `p` with unit normal `n`, either side: power /
            /// (4π max(d², r²)) for a light inside a sphere of radius r at distance d, times a
            /// bound on |cos θ| over that sphere; π times the (mean) radiance for the
            /// environment; for spot and directional lights the irradiance itself (falloff and
            /// |cos θ| included). Zero only where the light cannot reach `p`'s tangent plane from
            /// either side; the target of resampled light selection.
            pub fn irradiance_estimate(&self, p: Vec3, n: Vec3) -> f32 {
                match self {
                    $(Self::$variant(l) => Emitter::irradiance_estimate(l, p, n),)*
                }
            }

            /// Emitted power, W (mean over channels); the weight of power-proportional selection.
            pub fn power(&self) -> f32 {
                match self {
                    $(Self::$variant(l) => Emitter::power(l),)*
                }
            }
        }
    };
}

impl Light {
    /// Whether light sampling leaves this light to BSDF samples where they continue a path and
    /// MIS weighs them: a constant environment (or a map with nothing above its mean), whose
    /// radiance is the same from every direction, so a BSDF sample already follows the whole
    /// integrand but the visibility, while its light samples are uniform over the sphere (half
    /// of them below the surface) and take light choices and shadow rays from the other lights
    /// (pbrt-v4's path tracer does the same).
    pub fn left_to_bsdf_samples(&self) -> bool {
        match self {
            Light::Environment(_) => true,
            Light::EnvironmentMap(map) => !map.has_compensated(),
            _ => false,
        }
    }

    /// The light as light sampling samples it where BSDF samples continue a path and MIS weighs
    /// them, where that differs from the light itself: an environment map's
    /// [compensated](EnvironmentMap::compensated) copy. `None` for every other light, and for
    /// those [left to BSDF samples](Self::left_to_bsdf_samples).
    pub fn compensated(&self) -> Option<Light> {
        match self {
            Light::EnvironmentMap(map) => map.compensated().map(Light::EnvironmentMap),
            _ => None,
        }
    }
}

light_set! {
    /// Area emitter on a triangle mesh.
    Mesh(MeshAreaLight),
    /// Area emitter on an analytic sphere.
    Sphere(SphereAreaLight),
    /// Point light (a delta light).
    Point(PointLight),
    /// Spot light: a point light with an angular falloff (a delta light).
    Spot(SpotLight),
    /// Parallel light from infinitely far away (a delta light).
    Directional(DirectionalLight),
    /// Constant environment.
    Environment(ConstantEnvironment),
    /// Environment map: radiance from infinitely far away, varying with direction.
    EnvironmentMap(EnvironmentMap),
    /// An area light on a shape that moves during the shutter.
    Moving(MovingLight),
}
