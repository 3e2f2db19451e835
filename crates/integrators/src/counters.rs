//! Per-thread counts of the rays a render traces.

/// Rays traced while estimating one or more samples.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RayCounters {
    /// Closest-hit rays (camera and bounce rays).
    pub rays: u64,
    /// Occlusion rays towards lights.
    pub shadow_rays: u64,
}

impl RayCounters {
    /// Adds another set of counts to this one.
    pub fn add(&mut self, other: RayCounters) {
        self.rays += other.rays;
        self.shadow_rays += other.shadow_rays;
    }
}
