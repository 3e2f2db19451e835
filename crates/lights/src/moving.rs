//! An area light on a moving shape: sampled where the shape is at the ray's time.
//!
//! The emitter is kept in its shape's object space. A sample from a world-space point `p` at
//! time `t` is drawn in object space from `p` carried there, then carried back by the shape's
//! transform at `t` ([`geometry::Placement`]). Densities change variables through the area
//! measure: a point sampled with density `p_A` per object-space area has density
//! `p_A / J` per world-space area, `J = dA_world / dA_object` the transform's area scale at that
//! point (Nanson's formula), and `p_A / J · d² / cos θ` per steradian seen from `p`. Any affine
//! transform keeps the estimate exact, a stretch that changes during the shutter included.

use geometry::{Aabb, Motion};
use glam::{Vec2, Vec3};
use sampling::Frame;
use sampling::warp::sample_cosine_hemisphere;

use crate::area_sample::{area_pdf_towards, area_sample_towards};
use crate::light::{Emitter, Kind, one_sided};
use crate::{EmissionSample, Light, LightSample, MeshAreaLight, SphereAreaLight};

/// An area light (a mesh or sphere emitter in object space) moving with its shape.
#[derive(Clone, Debug)]
pub struct MovingLight {
    local: LocalLight,
    motion: Motion,
    /// A sphere (centre, radius; world units) holding the light at every time of the shutter.
    bounds: (Vec3, f32),
}

impl MovingLight {
    /// The area light `local` (object space, a [`Light::Mesh`] or [`Light::Sphere`]; object-space
    /// bounds `local_bounds`) moving by `motion`; `None` for any other light.
    pub fn new(local: Light, motion: Motion, local_bounds: &Aabb) -> Option<Self> {
        let local = match local {
            Light::Mesh(l) => LocalLight::Mesh(l),
            Light::Sphere(l) => LocalLight::Sphere(l),
            _ => return None,
        };
        let swept = motion.bounds(local_bounds);
        Some(Self {
            local,
            motion,
            bounds: (swept.center(), 0.5 * swept.diagonal().length()),
        })
    }

    /// A point on the light where it is at `time` (a fraction of the shutter interval), seen
    /// from `p`, with `u` ∈ [0, 1)² as the light in object space uses it.
    #[inline]
    pub fn sample_li(&self, p: Vec3, u: Vec2, time: f32) -> Option<LightSample> {
        let placement = self.motion.at(time);
        let s = self.local.sample_li(placement.point_to_object(p), u)?;
        let pdf_area = s.pdf_solid_angle * (-s.n_light.dot(s.wi)) / (s.distance * s.distance);
        let p_light = placement.point_to_world(s.p_light);
        let n_light = placement.normal_to_world(s.n_light);
        area_sample_towards(
            p,
            p_light,
            placement.error_to_world(s.p_light, s.p_light_error, p_light),
            n_light,
            pdf_area / placement.area_scale(n_light),
            s.radiance,
        )
    }

    /// Density per steradian with which [`Self::sample_li`] from `p` at `time` picks the point
    /// `p_light` (world-space geometric normal `n_light`).
    #[inline]
    pub fn pdf_li(&self, p: Vec3, p_light: Vec3, n_light: Vec3, time: f32) -> f32 {
        let placement = self.motion.at(time);
        let (p_l, light_l) = (
            placement.point_to_object(p),
            placement.point_to_object(p_light),
        );
        let n_l = placement.normal_to_object(n_light);
        let pdf = self.local.pdf_li(p_l, light_l, n_l);
        let to_light = light_l - p_l;
        let d2 = to_light.length_squared();
        if !(pdf > 0.0 && d2 > 0.0) {
            return 0.0;
        }
        let pdf_area = pdf * n_l.dot(to_light).abs() / (d2 * d2.sqrt());
        area_pdf_towards(
            p,
            p_light,
            n_light,
            pdf_area / placement.area_scale(n_light),
        )
    }

    /// Light leaving the light where it is at `time`: a point as the object-space light picks
    /// it (`u_point`) and a cosine-distributed direction about its world-space normal (`u_dir`).
    #[inline]
    pub fn sample_emission(&self, u_point: Vec2, u_dir: Vec2, time: f32) -> Option<EmissionSample> {
        let local = self.local.sample_emission(u_point, u_dir)?;
        let placement = self.motion.at(time);
        let p = placement.point_to_world(local.p);
        let n = placement.normal_to_world(local.n);
        let dir = sample_cosine_hemisphere(u_dir);
        if dir.z <= 0.0 || n == Vec3::ZERO {
            return None;
        }
        Some(EmissionSample {
            p,
            p_error: placement.error_to_world(local.p, local.p_error, p),
            n,
            dir: Frame::from_normal(n).to_world(dir).normalize(),
            // Lₑ π / pdf_area: the world-space density is the object-space one over J.
            weight: local.weight * placement.area_scale(n),
        })
    }

    /// Radiance leaving the light's surface on its emitting side (the side test is the
    /// caller's, as for a static light).
    #[inline]
    pub fn radiance(&self) -> Vec3 {
        match &self.local {
            LocalLight::Mesh(l) => l.radiance(),
            LocalLight::Sphere(l) => l.radiance,
        }
    }

    /// A sphere (centre, radius; world units) holding the light during the whole shutter.
    pub fn bounding_sphere(&self) -> (Vec3, f32) {
        self.bounds
    }

    /// Emitted power (W, mean over channels) at the middle of the shutter: the object-space
    /// light's, its area scaled as a uniform stretch of the same volume change would (only
    /// light selection uses it, where any positive weight is unbiased).
    pub fn power(&self) -> f32 {
        let volume = self.motion.at(0.5).volume_scale();
        self.local.power() * volume.powf(2.0 / 3.0)
    }
}

impl Emitter for MovingLight {
    const KIND: Kind = Kind::Area;

    #[inline]
    fn sample_li(&self, p: Vec3, u: Vec2, time: f32) -> Option<LightSample> {
        MovingLight::sample_li(self, p, u, time)
    }

    #[inline]
    fn sample_emission(&self, u_point: Vec2, u_dir: Vec2, time: f32) -> Option<EmissionSample> {
        MovingLight::sample_emission(self, u_point, u_dir, time)
    }

    #[inline]
    fn radiance_towards(&self, ng: Vec3, w: Vec3) -> Vec3 {
        one_sided(self.radiance(), ng, w)
    }

    #[inline]
    fn pdf_li_surface(&self, p: Vec3, p_light: Vec3, n_light: Vec3, time: f32) -> f32 {
        self.pdf_li(p, p_light, n_light, time)
    }

    #[inline]
    fn pdf_emission_area(&self, n_light: Vec3, time: f32) -> f32 {
        let local = match &self.local {
            LocalLight::Mesh(l) => 1.0 / l.area(),
            LocalLight::Sphere(l) => l.pdf_area(),
        };
        local / self.motion.at(time).area_scale(n_light)
    }

    fn bounding_sphere(&self) -> Option<(Vec3, f32)> {
        Some(self.bounds)
    }

    fn power(&self) -> f32 {
        MovingLight::power(self)
    }
}

/// The area lights a shape can carry, in its object space. A set of its own rather than a boxed
/// [`Light`]: [`Light`]'s dispatch calling itself through a moving light would keep the
/// compiler from inlining it into the path loop (10% of a static scene's samples per second).
#[derive(Clone, Debug)]
enum LocalLight {
    Mesh(MeshAreaLight),
    Sphere(SphereAreaLight),
}

impl LocalLight {
    #[inline]
    fn sample_li(&self, p: Vec3, u: Vec2) -> Option<LightSample> {
        match self {
            LocalLight::Mesh(l) => l.sample_li(p, u),
            LocalLight::Sphere(l) => l.sample_li(p, u),
        }
    }

    #[inline]
    fn pdf_li(&self, p: Vec3, p_light: Vec3, n_light: Vec3) -> f32 {
        match self {
            LocalLight::Mesh(l) => l.pdf_li(p, p_light, n_light),
            LocalLight::Sphere(l) => l.pdf_li(p, p_light, n_light),
        }
    }

    #[inline]
    fn sample_emission(&self, u_point: Vec2, u_dir: Vec2) -> Option<EmissionSample> {
        match self {
            LocalLight::Mesh(l) => l.sample_emission(u_point, u_dir),
            LocalLight::Sphere(l) => l.sample_emission(u_point, u_dir),
        }
    }

    fn power(&self) -> f32 {
        match self {
            LocalLight::Mesh(l) => l.power(),
            LocalLight::Sphere(l) => l.power(),
        }
    }
}
