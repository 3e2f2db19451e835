//! The closed set of emitter types, dispatched by enum.

use crate::{
    ConstantEnvironment, DirectionalLight, EmissionSample, EnvironmentMap, LightSample,
    MeshAreaLight, MovingLight, PointLight, SphereAreaLight, SpotLight, mean_rgb,
};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// Any emitter in a scene.
#[derive(Clone, Debug)]
pub enum Light {
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

impl Light {
    /// A direction from the shading point `p` towards the light, with `u` uniform in [0, 1)².
    /// `None` when the sample carries no light (e.g. a back-facing point). A moving light is
    /// sampled where it is at `time`, a fraction of the shutter interval ([`geometry::Ray::time`]).
    #[inline]
    pub fn sample_li(&self, p: Vec3, u: Vec2, time: f32) -> Option<LightSample> {
        match self {
            Light::Mesh(l) => l.sample_li(p, u),
            Light::Sphere(l) => l.sample_li(p, u),
            Light::Point(l) => l.sample_li(p),
            Light::Spot(l) => l.sample_li(p),
            Light::Directional(l) => Some(l.sample_li(p)),
            Light::Environment(l) => l.sample_li(p, u),
            Light::EnvironmentMap(l) => l.sample_li(p, u),
            Light::Moving(l) => l.sample_li(p, u, time),
        }
    }

    /// Light leaving an area emitter's surface (see [`EmissionSample`]), with `u_point` and
    /// `u_dir` uniform in [0, 1)²; `None` for delta lights and the environment, which light
    /// tracing leaves to the path tracer. A moving light emits where it is at `time`.
    #[inline]
    pub fn sample_emission(&self, u_point: Vec2, u_dir: Vec2, time: f32) -> Option<EmissionSample> {
        match self {
            Light::Mesh(l) => l.sample_emission(u_point, u_dir),
            Light::Sphere(l) => l.sample_emission(u_point, u_dir),
            Light::Moving(l) => l.sample_emission(u_point, u_dir, time),
            Light::Point(_)
            | Light::Spot(_)
            | Light::Directional(_)
            | Light::Environment(_)
            | Light::EnvironmentMap(_) => None,
        }
    }

    /// Radiance leaving a point of this light's surface with geometric normal `ng` towards the
    /// unit direction `w` (zero behind a one-sided emitter, and for lights without a surface).
    #[inline]
    pub fn radiance_towards(&self, ng: Vec3, w: Vec3) -> Vec3 {
        let radiance = match self {
            Light::Mesh(l) => l.radiance(),
            Light::Sphere(l) => l.radiance,
            Light::Moving(l) => l.radiance(),
            Light::Point(_)
            | Light::Spot(_)
            | Light::Directional(_)
            | Light::Environment(_)
            | Light::EnvironmentMap(_) => return Vec3::ZERO,
        };
        // Area emitters are one-sided: they emit on the side their geometric normal points to.
        if ng.dot(w) > 0.0 {
            radiance
        } else {
            Vec3::ZERO
        }
    }

    /// Radiance arriving along a ray that escapes the scene in the unit direction `w` (pointing
    /// away from the scene): the environment's radiance, zero for every other light.
    #[inline]
    pub fn radiance_from_direction(&self, w: Vec3) -> Vec3 {
        match self {
            Light::Environment(l) => l.radiance,
            Light::EnvironmentMap(l) => l.radiance(w),
            _ => Vec3::ZERO,
        }
    }

    /// Density per steradian with which [`Self::sample_li`] from `p` would have chosen the point
    /// `p_light` with geometric normal `n_light` on this light's surface. Zero for lights without
    /// a surface (delta lights, the environment). A moving light's surface is where it is at
    /// `time`.
    #[inline]
    pub fn pdf_li_surface(&self, p: Vec3, p_light: Vec3, n_light: Vec3, time: f32) -> f32 {
        match self {
            Light::Mesh(l) => l.pdf_li(p, p_light, n_light),
            Light::Sphere(l) => l.pdf_li(p, p_light, n_light),
            Light::Moving(l) => l.pdf_li(p, p_light, n_light, time),
            Light::Point(_)
            | Light::Spot(_)
            | Light::Directional(_)
            | Light::Environment(_)
            | Light::EnvironmentMap(_) => 0.0,
        }
    }

    /// Density per steradian with which [`Self::sample_li`] picks the unit direction `w` that
    /// escapes the scene: the environment's density, zero for every other light.
    #[inline]
    pub fn pdf_li_environment(&self, w: Vec3) -> f32 {
        match self {
            Light::Environment(l) => l.pdf_li(),
            Light::EnvironmentMap(l) => l.pdf_li(w),
            _ => 0.0,
        }
    }

    /// Whether the light is an environment (constant or a map), which rays that escape the
    /// scene see.
    #[inline]
    pub fn is_environment(&self) -> bool {
        matches!(self, Light::Environment(_) | Light::EnvironmentMap(_))
    }

    /// True for lights that a randomly sampled ray can never hit (point, spot and directional
    /// lights).
    #[inline]
    pub fn is_delta(&self) -> bool {
        matches!(
            self,
            Light::Point(_) | Light::Spot(_) | Light::Directional(_)
        )
    }

    /// A sphere (centre, radius; world units) holding the light's emitting surface or point
    /// (radius 0); `None` for the environment and directional lights, which lie at infinity.
    pub fn bounding_sphere(&self) -> Option<(Vec3, f32)> {
        match self {
            Light::Mesh(l) => Some(l.bounding_sphere()),
            Light::Sphere(l) => Some((l.center, l.radius)),
            Light::Moving(l) => Some(l.bounding_sphere()),
            Light::Point(l) => Some((l.position, 0.0)),
            Light::Spot(l) => Some((l.position(), 0.0)),
            Light::Directional(_) | Light::Environment(_) | Light::EnvironmentMap(_) => None,
        }
    }

    /// Irradiance (W m⁻², mean over channels) that the light could deliver at most, roughly, to a
    /// surface at `p` with unit normal `n`, either side: power / (4π max(d², r²)) for a light
    /// inside a sphere of radius r at distance d, times a bound on |cos θ| over that sphere; π
    /// times the (mean) radiance for the environment; for spot and directional lights the irradiance
    /// itself (falloff and |cos θ| included). Zero only where the light cannot reach `p`'s
    /// tangent plane from either side; the target of resampled light selection.
    pub fn irradiance_estimate(&self, p: Vec3, n: Vec3) -> f32 {
        match self {
            Light::Environment(l) => return PI * mean_rgb(l.radiance),
            Light::EnvironmentMap(l) => return PI * l.mean_radiance(),
            Light::Directional(l) => return l.irradiance() * l.towards_light().dot(n).abs(),
            Light::Spot(l) => {
                let cos = (l.position() - p).normalize_or_zero().dot(n).abs();
                return l.irradiance_facing(p) * cos;
            }
            _ => {}
        }
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

    /// Emitted power, W (mean over channels); the weight of power-proportional selection.
    pub fn power(&self) -> f32 {
        match self {
            Light::Mesh(l) => l.power(),
            Light::Sphere(l) => l.power(),
            Light::Point(l) => l.power(),
            Light::Spot(l) => l.power(),
            Light::Directional(l) => l.power(),
            Light::Environment(l) => l.power(),
            Light::EnvironmentMap(l) => l.power(),
            Light::Moving(l) => l.power(),
        }
    }
}
