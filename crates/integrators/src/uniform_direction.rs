//! Direction sampling without importance: what the reference integrator always does and what
//! the path integrator does when BSDF importance sampling is switched off.

use glam::{Vec2, Vec3};
use materials::Bsdf;
use sampling::warp::{
    sample_uniform_hemisphere, sample_uniform_sphere, uniform_hemisphere_pdf, uniform_sphere_pdf,
};

/// A direction uniform over the hemisphere on the side of `wo` (the whole sphere when the BSDF
/// transmits), with its density per steradian.
#[inline]
pub fn sample_uniform_direction(bsdf: &Bsdf, wo: Vec3, u: Vec2) -> (Vec3, f32) {
    if bsdf.has_transmission() {
        return (sample_uniform_sphere(u), uniform_sphere_pdf());
    }
    let mut wi = sample_uniform_hemisphere(u);
    if wo.z < 0.0 {
        wi.z = -wi.z;
    }
    (wi, uniform_hemisphere_pdf())
}

/// Density per steradian with which [`sample_uniform_direction`] produces `wi` from `wo`.
#[inline]
pub fn uniform_direction_pdf(bsdf: &Bsdf, wo: Vec3, wi: Vec3) -> f32 {
    if bsdf.has_transmission() {
        uniform_sphere_pdf()
    } else if wo.z * wi.z > 0.0 {
        uniform_hemisphere_pdf()
    } else {
        0.0
    }
}
