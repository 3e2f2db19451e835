//! Per-thread counts of the rays a render traces, and the trait through which the integrators
//! report every ray they trace.

use geometry::Ray;

/// Told about every ray an integrator traces through [`crate::World`]. Integrators are generic
/// over it, so a render that only counts ([`RayCounters`]) compiles to two additions per ray,
/// and one that records every ray ([`crate::RayLog`]) costs nothing when it is not used.
pub trait RayTally {
    /// A closest-hit ray (camera or bounce ray), traced with `t_max` = ∞.
    fn closest_ray(&mut self, ray: &Ray);
    /// An occlusion ray towards a light, traced for `0 < t < t_max` (world units; ∞ towards
    /// the environment).
    fn shadow_ray(&mut self, ray: &Ray, t_max: f32);
    /// An occlusion ray joining two path vertices (path reuse), traced for `0 < t < t_max`:
    /// counted as a shadow ray and, for `auto`'s costs, apart (it samples no light).
    fn connection_ray(&mut self, ray: &Ray, t_max: f32);
    /// The rays told so far.
    fn counts(&self) -> RayCounters;
}

/// Rays traced while estimating one or more samples.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RayCounters {
    /// Closest-hit rays (camera and bounce rays).
    pub rays: u64,
    /// Occlusion rays: towards lights, and the connections of `connection_rays`.
    pub shadow_rays: u64,
    /// Of the occlusion rays, those joining two path vertices (path reuse).
    pub connection_rays: u64,
}

impl RayCounters {
    /// Adds another set of counts to this one.
    pub fn add(&mut self, other: RayCounters) {
        self.rays += other.rays;
        self.shadow_rays += other.shadow_rays;
        self.connection_rays += other.connection_rays;
    }

    /// The rays counted since `earlier` counts of the same tally.
    pub fn since(self, earlier: RayCounters) -> RayCounters {
        RayCounters {
            rays: self.rays - earlier.rays,
            shadow_rays: self.shadow_rays - earlier.shadow_rays,
            connection_rays: self.connection_rays - earlier.connection_rays,
        }
    }
}

impl RayTally for RayCounters {
    #[inline(always)]
    fn closest_ray(&mut self, _ray: &Ray) {
        self.rays += 1;
    }

    #[inline(always)]
    fn shadow_ray(&mut self, _ray: &Ray, _t_max: f32) {
        self.shadow_rays += 1;
    }

    #[inline(always)]
    fn connection_ray(&mut self, _ray: &Ray, _t_max: f32) {
        self.shadow_rays += 1;
        self.connection_rays += 1;
    }

    #[inline(always)]
    fn counts(&self) -> RayCounters {
        *self
    }
}
