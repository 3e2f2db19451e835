//! Area emitters on spheres (Mitsuba's `area` emitter attached to a `sphere` shape), sampled by
//! the solid angle of the cap visible from the shading point.

use crate::area_sample::{area_pdf_towards, area_sample_towards};
use crate::emission::{EmissionSample, lambertian_emission};
use crate::light::{Emitter, Kind, one_sided};
use crate::sample::{LightSample, mean_rgb};
use glam::{Vec2, Vec3};
use sampling::Frame;
use sampling::warp::{sample_uniform_sphere, sin_cos_turn, uniform_sphere_pdf};
use std::f32::consts::{PI, TAU};

/// Below this sin²θ_max (about 1.5°) cone angles are computed by series expansion, since
/// 1 − cos θ_max cancels catastrophically in f32 for small or distant spheres.
const SMALL_CONE_SIN2: f32 = 0.000_685_23;

/// Relative tolerance on the squared distance below which a point counts as on the sphere.
const SURFACE_TOLERANCE: f32 = 1e-3;

/// A sphere emitting constant radiance outwards (inwards when its normals are flipped).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereAreaLight {
    /// Centre in world space.
    pub center: Vec3,
    /// Radius, world units.
    pub radius: f32,
    /// True when the emitting side faces inwards (Mitsuba's `flip_normals`).
    pub flip_normals: bool,
    /// Emitted radiance, W m⁻² sr⁻¹ (RGB).
    pub radiance: Vec3,
}

impl SphereAreaLight {
    /// From outside: a direction uniform in the cone of the visible cap (pbrt-v4's method with a
    /// series expansion for small cones). From inside or on the sphere: a point uniform by area.
    #[inline]
    pub fn sample_li(&self, p: Vec3, u: Vec2) -> Option<LightSample> {
        if self.samples_by_area(p) {
            return self.sample_area(p, u);
        }
        let to_center = self.center - p;
        let dc2 = to_center.length_squared();
        let r2 = self.radius * self.radius;
        if self.flip_normals {
            return None;
        }
        let dc = dc2.sqrt();
        let sin2_max = r2 / dc2;
        let sin_max = sin2_max.sqrt();
        let (cos_theta, sin2_theta, one_minus_cos_max) = if sin2_max < SMALL_CONE_SIN2 {
            let sin2 = sin2_max * u.x;
            ((1.0 - sin2).sqrt(), sin2, 0.5 * sin2_max)
        } else {
            let cos_max = (1.0 - sin2_max).max(0.0).sqrt();
            let cos_theta = 1.0 - u.x * (1.0 - cos_max);
            (
                cos_theta,
                (1.0 - cos_theta * cos_theta).max(0.0),
                1.0 - cos_max,
            )
        };
        // Angle at the centre between the axis (towards p) and the sampled surface point.
        let cos_alpha =
            sin2_theta / sin_max + cos_theta * (1.0 - sin2_theta / sin2_max).max(0.0).sqrt();
        let sin_alpha = (1.0 - cos_alpha * cos_alpha).max(0.0).sqrt();
        let (sin_phi, cos_phi) = sin_cos_turn(u.y);
        let axis = Frame::from_normal(-to_center / dc);
        let n_light = axis
            .to_world(Vec3::new(
                sin_alpha * cos_phi,
                sin_alpha * sin_phi,
                cos_alpha,
            ))
            .normalize();
        let p_light = self.center + self.radius * n_light;
        let p_light_error = geometry::sphere_point_error(self.center, self.radius);
        let to_light = p_light - p;
        let distance = to_light.length();
        if distance.is_nan() || distance <= 0.0 {
            return None;
        }
        let pdf_solid_angle = 1.0 / (TAU * one_minus_cos_max);
        if !pdf_solid_angle.is_finite() {
            return None;
        }
        Some(LightSample {
            radiance: self.radiance,
            wi: to_light / distance,
            distance,
            pdf_solid_angle,
            p_light,
            p_light_error,
            n_light,
            is_delta: false,
        })
    }

    /// Light leaving the sphere: a point uniform by area (`u_point`) and a cosine-distributed
    /// direction about its emitting normal (`u_dir`).
    #[inline]
    pub fn sample_emission(&self, u_point: Vec2, u_dir: Vec2) -> Option<EmissionSample> {
        let outward = sample_uniform_sphere(u_point);
        let n = if self.flip_normals { -outward } else { outward };
        let area = 4.0 * PI * self.radius * self.radius;
        lambertian_emission(
            self.center + self.radius * outward,
            geometry::sphere_point_error(self.center, self.radius),
            n,
            self.radiance,
            area,
            u_dir,
        )
    }

    fn sample_area(&self, p: Vec3, u: Vec2) -> Option<LightSample> {
        let outward = sample_uniform_sphere(u);
        let p_light = self.center + self.radius * outward;
        let p_light_error = geometry::sphere_point_error(self.center, self.radius);
        let n_light = if self.flip_normals { -outward } else { outward };
        area_sample_towards(
            p,
            p_light,
            p_light_error,
            n_light,
            self.pdf_area(),
            self.radiance,
        )
    }

    /// Density per steradian with which [`Self::sample_li`] from `p` picks the point `p_light`
    /// with geometric normal `n_light` on the sphere.
    pub fn pdf_li(&self, p: Vec3, p_light: Vec3, n_light: Vec3) -> f32 {
        if self.samples_by_area(p) {
            return area_pdf_towards(p, p_light, n_light, self.pdf_area());
        }
        if self.flip_normals {
            return 0.0;
        }
        let r2 = self.radius * self.radius;
        let sin2_max = r2 / (self.center - p).length_squared();
        let one_minus_cos_max = if sin2_max < SMALL_CONE_SIN2 {
            0.5 * sin2_max
        } else {
            1.0 - (1.0 - sin2_max).max(0.0).sqrt()
        };
        1.0 / (TAU * one_minus_cos_max)
    }

    /// True when points are sampled uniformly by area rather than by cone: from inside the sphere
    /// and from its surface (within rounding: a shading point on the sphere itself may land a
    /// hair outside, where the cone would degenerate to a hemisphere).
    #[inline]
    fn samples_by_area(&self, p: Vec3) -> bool {
        let r2 = self.radius * self.radius;
        (self.center - p).length_squared() <= r2 * (1.0 + SURFACE_TOLERANCE)
    }

    /// Density per unit area of a point uniform on the sphere: 1 / (4π r²).
    pub fn pdf_area(&self) -> f32 {
        uniform_sphere_pdf() / (self.radius * self.radius)
    }

    /// Emitted power (W, mean over channels): π · 4π r² · radiance.
    pub fn power(&self) -> f32 {
        PI * 4.0 * PI * self.radius * self.radius * mean_rgb(self.radiance)
    }
}

impl Emitter for SphereAreaLight {
    const KIND: Kind = Kind::Area;

    #[inline]
    fn sample_li(&self, p: Vec3, u: Vec2, _time: f32) -> Option<LightSample> {
        SphereAreaLight::sample_li(self, p, u)
    }

    #[inline]
    fn sample_emission(&self, u_point: Vec2, u_dir: Vec2, _time: f32) -> Option<EmissionSample> {
        SphereAreaLight::sample_emission(self, u_point, u_dir)
    }

    #[inline]
    fn radiance_towards(&self, ng: Vec3, w: Vec3) -> Vec3 {
        one_sided(self.radiance, ng, w)
    }

    #[inline]
    fn pdf_li_surface(&self, p: Vec3, p_light: Vec3, n_light: Vec3, _time: f32) -> f32 {
        self.pdf_li(p, p_light, n_light)
    }

    #[inline]
    fn pdf_emission_area(&self, _n_light: Vec3, _time: f32) -> f32 {
        self.pdf_area()
    }

    fn bounding_sphere(&self) -> Option<(Vec3, f32)> {
        Some((self.center, self.radius))
    }

    fn power(&self) -> f32 {
        SphereAreaLight::power(self)
    }
}
