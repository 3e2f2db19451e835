//! Turning a point sampled by area on an emitting surface into a sample by solid angle, and the
//! inverse question: the solid-angle density of a given surface point.

use crate::pdf_area_to_solid_angle;
use crate::sample::LightSample;
use glam::Vec3;

/// The light sample for the surface point `p_light` (coordinate error bound `p_light_error`,
/// unit normal `n_light`, emitting towards it), chosen with density `pdf_area` per unit area,
/// seen from `p`. `None` when the point faces away from `p`, coincides with it, or the density
/// is not finite.
#[inline]
pub(crate) fn area_sample_towards(
    p: Vec3,
    p_light: Vec3,
    p_light_error: Vec3,
    n_light: Vec3,
    pdf_area: f32,
    radiance: Vec3,
) -> Option<LightSample> {
    let to_light = p_light - p;
    let distance = to_light.length();
    if distance.is_nan() || distance <= 0.0 {
        return None;
    }
    let wi = to_light / distance;
    let cos_at_light = -n_light.dot(wi);
    if cos_at_light <= 0.0 {
        return None;
    }
    let pdf_solid_angle = pdf_area_to_solid_angle(pdf_area, distance, cos_at_light);
    if !(pdf_solid_angle.is_finite() && pdf_solid_angle > 0.0) {
        return None;
    }
    Some(LightSample {
        radiance,
        wi,
        distance,
        pdf_solid_angle,
        p_light,
        p_light_error,
        n_light,
        is_delta: false,
    })
}

/// Density per steradian, seen from `p`, of the surface point `p_light` (unit normal `n_light`)
/// chosen with density `pdf_area` per unit area; zero behind the surface.
#[inline]
pub(crate) fn area_pdf_towards(p: Vec3, p_light: Vec3, n_light: Vec3, pdf_area: f32) -> f32 {
    let to_light = p_light - p;
    let distance = to_light.length();
    if distance.is_nan() || distance <= 0.0 {
        return 0.0;
    }
    let cos_at_light = -n_light.dot(to_light / distance);
    if cos_at_light <= 0.0 {
        return 0.0;
    }
    pdf_area_to_solid_angle(pdf_area, distance, cos_at_light)
}
