//! Fresnel reflectance of smooth interfaces (unpolarised light) and mirror/refraction directions
//! in the local frame, following Mitsuba 3's `fresnel.h`.

use glam::Vec3;

/// A complex index of refraction η + iκ per RGB channel, relative to the outside medium.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ComplexIor {
    /// Real part η (Mitsuba's `eta`), per channel.
    pub eta: Vec3,
    /// Imaginary part κ, the extinction coefficient (Mitsuba's `k`), per channel.
    pub k: Vec3,
}

impl ComplexIor {
    /// Mitsuba's `material="none"`: η = 0, κ = 1, for which [`fresnel_conductor`] is exactly 1
    /// at every angle (a perfect mirror).
    pub const PERFECT_MIRROR: Self = Self {
        eta: Vec3::ZERO,
        k: Vec3::ONE,
    };

    /// The index η + iκ, per channel.
    pub fn new(eta: Vec3, k: Vec3) -> Self {
        Self { eta, k }
    }
}

/// What [`fresnel_dielectric`] returns, named as in Mitsuba's `fresnel()`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DielectricFresnel {
    /// Unpolarised Fresnel reflectance F in [0, 1]; 1 under total internal reflection.
    pub reflectance: f32,
    /// Signed cosine of the refracted direction: opposite in sign to the incident cosine,
    /// 0 under total internal reflection.
    pub cos_theta_t: f32,
    /// Relative index in the direction of travel: η when arriving from outside (cos θi ≥ 0), 1/η
    /// from inside. This is what a ray crossing the interface crosses.
    pub eta_it: f32,
    /// 1 / `eta_it`: the factor on the tangential components of the refracted direction, and the
    /// square root of the radiance scale on refraction.
    pub eta_ti: f32,
}

/// Unpolarised Fresnel reflectance of a smooth dielectric interface with relative index `eta`
/// (inside over outside; > 1 when the normal points to the less dense side), for light arriving
/// at `cos_theta_i` (negative from inside). Exactly 0 when `eta` is 1, 1 at grazing incidence.
pub fn fresnel_dielectric(cos_theta_i: f32, eta: f32) -> DielectricFresnel {
    let outside = cos_theta_i >= 0.0;
    let (eta_it, eta_ti) = if outside {
        (eta, 1.0 / eta)
    } else {
        (1.0 / eta, eta)
    };

    // Snell's law for the squared cosine of the transmitted direction; negative means TIR.
    let cos_theta_t_sqr = 1.0 - (1.0 - cos_theta_i * cos_theta_i) * eta_ti * eta_ti;
    let cos_i = cos_theta_i.abs();
    let cos_t = cos_theta_t_sqr.max(0.0).sqrt();

    let index_matched = eta == 1.0;
    let reflectance = if index_matched {
        0.0
    } else if cos_i == 0.0 {
        1.0
    } else {
        let a_s = (cos_i - eta_it * cos_t) / (cos_i + eta_it * cos_t);
        let a_p = (cos_t - eta_it * cos_i) / (cos_t + eta_it * cos_i);
        0.5 * (a_s * a_s + a_p * a_p)
    };

    DielectricFresnel {
        reflectance,
        cos_theta_t: if cos_theta_i >= 0.0 { -cos_t } else { cos_t },
        eta_it,
        eta_ti,
    }
}

/// Unpolarised Fresnel reflectance per RGB channel of a conductor with complex index `ior`, for
/// light arriving from outside at `cos_theta_i` ∈ [0, 1] (Mitsuba's `fresnel_conductor`, after
/// Moeller, "Optics", 1988).
pub fn fresnel_conductor(cos_theta_i: f32, ior: ComplexIor) -> Vec3 {
    let cos2 = cos_theta_i * cos_theta_i;
    let sin2 = 1.0 - cos2;
    let sin4 = sin2 * sin2;
    let (eta, k) = (ior.eta, ior.k);

    let temp_1 = eta * eta - k * k - Vec3::splat(sin2);
    let a2_plus_b2 = safe_sqrt3(temp_1 * temp_1 + 4.0 * k * k * eta * eta);
    let a = safe_sqrt3(0.5 * (a2_plus_b2 + temp_1));

    let term_1 = a2_plus_b2 + Vec3::splat(cos2);
    let term_2 = 2.0 * cos_theta_i * a;
    let r_s = (term_1 - term_2) / (term_1 + term_2);

    let term_3 = a2_plus_b2 * cos2 + Vec3::splat(sin4);
    let term_4 = term_2 * sin2;
    let r_p = r_s * (term_3 - term_4) / (term_3 + term_4);

    0.5 * (r_s + r_p)
}

/// Diffuse Fresnel reflectance of a smooth interface with relative index `eta` (the side the
/// light comes from has index 1): the fraction of light arriving with a cosine-weighted
/// (Lambertian) distribution of directions that the interface reflects,
/// F_dr(η) = ∫₀¹ F(μ, η) 2μ dμ. Mitsuba's `fresnel_diffuse_reflectance` gives the same quantity
/// by fitted polynomials (within 0.1–0.6% for η ∈ [1, 2]); here it is integrated (Simpson's rule
/// in double precision) where the integrand is smooth, for η ≥ 1, and for η < 1, where total
/// internal reflection puts a kink in it, taken from the reciprocity of diffuse transmittance,
/// 1 − F_dr(1/η) = η² (1 − F_dr(η)). Accurate to about 1e-7; meant for set-up, not per sample.
/// `eta` must be finite and positive.
pub fn diffuse_fresnel_reflectance(eta: f32) -> f32 {
    let eta = f64::from(eta);
    if eta == 1.0 {
        0.0
    } else if eta > 1.0 {
        external_diffuse_reflectance(eta) as f32
    } else {
        (1.0 - (1.0 - external_diffuse_reflectance(1.0 / eta)) * eta * eta) as f32
    }
}

/// F_dr(η) for η ≥ 1 by composite Simpson's rule over μ = cos θ.
fn external_diffuse_reflectance(eta: f64) -> f64 {
    const INTERVALS: usize = 512;
    let fresnel = |mu: f64| {
        let cos_t = (1.0 - (1.0 - mu * mu) / (eta * eta)).sqrt();
        let r_s = (mu - eta * cos_t) / (mu + eta * cos_t);
        let r_p = (cos_t - eta * mu) / (cos_t + eta * mu);
        0.5 * (r_s * r_s + r_p * r_p)
    };
    let h = 1.0 / INTERVALS as f64;
    let sum: f64 = (0..=INTERVALS)
        .map(|i| {
            let mu = i as f64 * h;
            let simpson_weight = match i {
                0 => 1.0,
                i if i == INTERVALS => 1.0,
                i if i % 2 == 1 => 4.0,
                _ => 2.0,
            };
            simpson_weight * fresnel(mu) * 2.0 * mu
        })
        .sum();
    sum * h / 3.0
}

/// Mirror reflection of `w` about the local normal +z.
#[inline]
pub fn reflect(w: Vec3) -> Vec3 {
    Vec3::new(-w.x, -w.y, w.z)
}

/// Mirror reflection of `w` about the unit vector `m` (both on the same side give a result on it).
#[inline]
pub fn reflect_about(w: Vec3, m: Vec3) -> Vec3 {
    2.0 * w.dot(m) * m - w
}

/// Refraction of `w` through the local interface (normal +z), given `cos_theta_t` and `eta_ti`
/// from [`fresnel_dielectric`]; the result is a unit vector on the other side.
#[inline]
pub fn refract(w: Vec3, cos_theta_t: f32, eta_ti: f32) -> Vec3 {
    Vec3::new(-eta_ti * w.x, -eta_ti * w.y, cos_theta_t)
}

/// Refraction of `w` through a microfacet with unit normal `m` (either side), given
/// `cos_theta_t` and `eta_ti` from [`fresnel_dielectric`] of `w · m`: the unit vector on the
/// other side of the facet (Mitsuba's `refract(wi, m, cos_theta_t, eta_ti)`).
#[inline]
pub fn refract_about(w: Vec3, m: Vec3, cos_theta_t: f32, eta_ti: f32) -> Vec3 {
    m * (w.dot(m) * eta_ti + cos_theta_t) - w * eta_ti
}

/// Componentwise `sqrt` that treats tiny negative rounding error as zero.
#[inline]
fn safe_sqrt3(v: Vec3) -> Vec3 {
    v.max(Vec3::ZERO).map(f32::sqrt)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Mitsuba's `fresnel_diffuse_reflectance`: Egan and Hilgeman's fit for η < 1, d'Eon and
    /// Irving's for η ≥ 1, transcribed as an independent check.
    fn mitsuba_fit(eta: f32) -> f32 {
        let inv = 1.0 / eta;
        if eta < 1.0 {
            0.0636 * inv + eta * (eta * -1.4399 + 0.7099) + 0.6681
        } else {
            let c = [0.919317, -3.4793, 6.75335, -7.80989, 4.98554, -1.36881];
            c.iter().rev().fold(0.0, |acc, &c| acc * inv + c)
        }
    }

    #[test]
    fn diffuse_fresnel_reflectance_within_mitsuba_fits_stated_error() {
        // The fits' stated maximum relative errors: 0.1% for η in [1, 2] (d'Eon and Irving) and
        // 0.6% for 1/η in [1.5, 2] (Egan and Hilgeman, 0.1% below 1.5).
        for (eta, tolerance) in [
            (1.1_f32, 1e-3),
            (1.33, 1e-3),
            (1.49, 1e-3),
            (1.5, 1e-3),
            (2.0, 1e-3),
            (1.0 / 1.2, 1e-3),
            (1.0 / 1.49, 1e-3),
            (1.0 / 1.8, 6e-3),
        ] {
            let exact = diffuse_fresnel_reflectance(eta);
            let fit = mitsuba_fit(eta);
            assert!(
                ((exact - fit) / fit).abs() < tolerance,
                "eta {eta}: integrated {exact}, fit {fit}"
            );
        }
    }

    #[test]
    fn diffuse_fresnel_reflectance_equals_brute_force_integral() {
        // A midpoint rule over the single-precision Fresnel reflectance, total internal
        // reflection's kink included, for both sides of the interface.
        const N: usize = 200_000;
        for eta in [1.49_f32, 1.0 / 1.49, 2.4, 1.0 / 2.4] {
            let brute: f64 = (0..N)
                .map(|i| {
                    let mu = (i as f64 + 0.5) / N as f64;
                    f64::from(fresnel_dielectric(mu as f32, eta).reflectance) * 2.0 * mu / N as f64
                })
                .sum();
            let exact = diffuse_fresnel_reflectance(eta);
            assert!(
                (f64::from(exact) - brute).abs() < 2e-5,
                "eta {eta}: {exact} against {brute}"
            );
        }
        assert_eq!(diffuse_fresnel_reflectance(1.0), 0.0);
    }

    #[test]
    fn dielectric_normal_incidence_matches_closed_form() {
        for eta in [1.2_f32, 1.5, 2.4, 1.0 / 1.5] {
            let expected = ((eta - 1.0) / (eta + 1.0)).powi(2);
            let from_outside = fresnel_dielectric(1.0, eta);
            let from_inside = fresnel_dielectric(-1.0, eta);
            assert!(
                (from_outside.reflectance - expected).abs() < 1e-6,
                "eta {eta}"
            );
            assert!(
                (from_inside.reflectance - expected).abs() < 1e-6,
                "eta {eta}"
            );
            assert_eq!(from_outside.cos_theta_t, -1.0);
            assert_eq!(from_inside.cos_theta_t, 1.0);
        }
    }

    #[test]
    fn dielectric_total_internal_reflection_beyond_critical_angle() {
        let eta = 1.5_f32;
        let critical_sin = 1.0 / eta;
        let critical_cos = (1.0 - critical_sin * critical_sin).sqrt();
        // From inside (cos < 0), slightly more grazing than the critical angle.
        let beyond = fresnel_dielectric(-(critical_cos - 1e-3), eta);
        assert_eq!(beyond.reflectance, 1.0);
        assert_eq!(beyond.cos_theta_t, 0.0);
        let before = fresnel_dielectric(-(critical_cos + 1e-3), eta);
        assert!(before.reflectance < 1.0);
        assert!(before.cos_theta_t > 0.0);
    }

    #[test]
    fn dielectric_snell_law_holds_for_refracted_direction() {
        let eta = 1.33_f32;
        for cos_i in [0.9_f32, 0.5, 0.1, -0.95, -0.8] {
            let sin_i = (1.0 - cos_i * cos_i).sqrt();
            let w = Vec3::new(sin_i, 0.0, cos_i);
            let fr = fresnel_dielectric(cos_i, eta);
            let t = refract(w, fr.cos_theta_t, fr.eta_ti);
            assert!((t.length() - 1.0).abs() < 1e-5, "not unit: {t}");
            // n_i sin θi = n_t sin θt, with sin θt = |t.x| and n_t / n_i = eta_it.
            assert!((sin_i - fr.eta_it * t.x.abs()).abs() < 1e-5);
            assert!(
                t.z * cos_i < 0.0,
                "refracted direction must cross the surface"
            );
        }
    }

    #[test]
    fn dielectric_index_matched_and_grazing_special_cases() {
        assert_eq!(fresnel_dielectric(0.3, 1.0).reflectance, 0.0);
        assert_eq!(fresnel_dielectric(0.0, 1.5).reflectance, 1.0);
        assert!(fresnel_dielectric(1.0, 1.0001).reflectance < 1e-8);
    }

    #[test]
    fn conductor_perfect_mirror_is_one_everywhere() {
        for i in 0..=20 {
            let cos = i as f32 / 20.0;
            let f = fresnel_conductor(cos, ComplexIor::PERFECT_MIRROR);
            assert!((f - Vec3::ONE).abs().max_element() < 1e-6, "cos {cos}: {f}");
        }
    }

    #[test]
    fn conductor_with_zero_extinction_equals_dielectric() {
        let eta = 1.7_f32;
        let ior = ComplexIor::new(Vec3::splat(eta), Vec3::ZERO);
        for i in 1..=20 {
            let cos = i as f32 / 20.0;
            let conductor = fresnel_conductor(cos, ior).x;
            let dielectric = fresnel_dielectric(cos, eta).reflectance;
            assert!(
                (conductor - dielectric).abs() < 1e-5,
                "cos {cos}: {conductor} vs {dielectric}"
            );
        }
    }

    #[test]
    fn conductor_normal_incidence_matches_closed_form() {
        // Gold-like values: R = ((η − 1)² + κ²) / ((η + 1)² + κ²) at normal incidence.
        let eta = Vec3::new(0.143, 0.374, 1.442);
        let k = Vec3::new(3.983, 2.385, 1.603);
        let expected = ((eta - 1.0) * (eta - 1.0) + k * k) / ((eta + 1.0) * (eta + 1.0) + k * k);
        let f = fresnel_conductor(1.0, ComplexIor::new(eta, k));
        assert!(
            (f - expected).abs().max_element() < 1e-5,
            "{f} vs {expected}"
        );
        assert!(fresnel_conductor(0.0, ComplexIor::new(eta, k)).min_element() > 0.999);
    }
}
