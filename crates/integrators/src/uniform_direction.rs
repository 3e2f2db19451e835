//! Direction sampling without importance: what the reference integrator always does and what
//! the path integrator does when BSDF importance sampling is switched off.

use crate::next_direction::NextDirection;
use glam::{Vec2, Vec3};
use materials::{Bsdf, BsdfFlags};
use sampling::warp::{
    sample_uniform_hemisphere, sample_uniform_sphere, uniform_hemisphere_pdf, uniform_sphere_pdf,
};

/// The probability with which [`sample_without_importance`] takes a mixed BSDF's delta lobes
/// rather than a uniform direction ([`BsdfFlags::MIXED`]: a plastic's mirror and its diffuse
/// base), which no uniform direction can find.
const DELTA_LOBE_SHARE: f32 = 0.5;

/// The next direction of a walk that uses no importance sampling: a delta BSDF's own sample,
/// otherwise a direction by [`sample_uniform_direction`], and for a mixed BSDF either, by
/// `u_lobe`, its delta lobes (with probability ½, by [`Bsdf::sample_delta`]) or a uniform
/// direction. `None` when the chosen strategy finds no direction (the estimate is then 0).
#[inline]
pub fn sample_without_importance(
    bsdf: &Bsdf,
    wo: Vec3,
    u_lobe: f32,
    u_dir: Vec2,
) -> Option<NextDirection> {
    if bsdf.flags().is_delta() {
        return bsdf.sample(wo, u_lobe, u_dir).map(NextDirection::from);
    }
    let uniform_share = if bsdf.flags().contains(BsdfFlags::MIXED) {
        if u_lobe < DELTA_LOBE_SHARE {
            let mut step = NextDirection::from(bsdf.sample_delta(wo, u_lobe / DELTA_LOBE_SHARE)?);
            step.weight /= DELTA_LOBE_SHARE;
            step.pdf_solid_angle *= DELTA_LOBE_SHARE;
            return Some(step);
        }
        1.0 - DELTA_LOBE_SHARE
    } else {
        1.0
    };
    let (wi, pdf_direction) = sample_uniform_direction(bsdf, wo, u_dir);
    let pdf_solid_angle = uniform_share * pdf_direction;
    let f = bsdf.eval(wo, wi);
    Some(NextDirection {
        wi,
        weight: f * wi.z.abs() / pdf_solid_angle,
        pdf_solid_angle,
        is_delta: false,
        is_null: false,
        eta: 1.0,
    })
}

/// A direction uniform over the hemisphere on the side of `wo` (the whole sphere when the BSDF
/// transmits), with its density per steradian.
#[inline]
fn sample_uniform_direction(bsdf: &Bsdf, wo: Vec3, u: Vec2) -> (Vec3, f32) {
    if bsdf.flags().contains(BsdfFlags::TRANSMISSION) {
        return (sample_uniform_sphere(u), uniform_sphere_pdf());
    }
    let mut wi = sample_uniform_hemisphere(u);
    if wo.z < 0.0 {
        wi.z = -wi.z;
    }
    (wi, uniform_hemisphere_pdf())
}

/// Density per steradian with which [`sample_without_importance`] produces the non-delta
/// direction `wi` from `wo`.
#[inline]
pub fn uniform_direction_pdf(bsdf: &Bsdf, wo: Vec3, wi: Vec3) -> f32 {
    let uniform_share = if bsdf.flags().contains(BsdfFlags::MIXED) {
        1.0 - DELTA_LOBE_SHARE
    } else {
        1.0
    };
    let pdf = if bsdf.flags().contains(BsdfFlags::TRANSMISSION) {
        uniform_sphere_pdf()
    } else if wo.z * wi.z > 0.0 {
        uniform_hemisphere_pdf()
    } else {
        0.0
    };
    uniform_share * pdf
}
