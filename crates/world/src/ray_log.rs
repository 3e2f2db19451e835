//! Recording every ray a render traces, so that tracing the same rays alone can be timed (the
//! ray-casting limit of a render: `cargo xtask raycast-limit`).

use crate::{RayCounters, RayTally};
use geometry::Ray;

/// An occlusion ray as traced: the ray and the end of the segment it tests (world units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowRay {
    /// The ray, from the shading point towards the light.
    pub ray: Ray,
    /// Occluders count for `0 < t < t_max`.
    pub t_max: f32,
}

/// Every ray traced, in the order traced, besides their counts.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RayLog {
    /// Counts of both kinds, as [`RayCounters`] would have them.
    pub counters: RayCounters,
    /// Closest-hit rays (traced with `t_max` = ∞).
    pub closest: Vec<Ray>,
    /// Occlusion rays.
    pub shadow: Vec<ShadowRay>,
}

impl RayLog {
    /// Moves the rays of `other` to the end of this log and adds its counts.
    pub fn append(&mut self, other: &mut RayLog) {
        self.counters.add(other.counters);
        other.counters = RayCounters::default();
        self.closest.append(&mut other.closest);
        self.shadow.append(&mut other.shadow);
    }
}

impl RayTally for RayLog {
    fn closest_ray(&mut self, ray: &Ray) {
        self.counters.closest_ray(ray);
        self.closest.push(*ray);
    }

    fn shadow_ray(&mut self, ray: &Ray, t_max: f32) {
        self.counters.shadow_ray(ray, t_max);
        self.shadow.push(ShadowRay { ray: *ray, t_max });
    }

    fn connection_ray(&mut self, ray: &Ray, t_max: f32) {
        self.counters.connection_ray(ray, t_max);
        self.shadow.push(ShadowRay { ray: *ray, t_max });
    }

    fn counts(&self) -> RayCounters {
        self.counters
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn records_rays_in_order_and_appends() {
        let a = Ray::new(Vec3::ZERO, Vec3::X);
        let b = Ray::new(Vec3::ONE, Vec3::NEG_Y);
        let mut first = RayLog::default();
        first.closest_ray(&a);
        first.shadow_ray(&b, 2.5);
        let mut second = RayLog::default();
        second.closest_ray(&b);
        first.append(&mut second);
        assert_eq!(first.closest, vec![a, b]);
        assert_eq!(first.shadow, vec![ShadowRay { ray: b, t_max: 2.5 }]);
        assert_eq!(
            first.counters,
            RayCounters {
                rays: 2,
                shadow_rays: 1,
                connection_rays: 0,
            }
        );
        assert_eq!(second, RayLog::default());
    }
}
