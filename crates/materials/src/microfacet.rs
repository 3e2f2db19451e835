//! Isotropic microfacet distributions (Beckmann and GGX) with Smith shadowing-masking and
//! visible-normal sampling, following Mitsuba 3's `microfacet.h`.
//!
//! All directions are in the local frame (+z is the macro-surface normal). The distribution of
//! normals D(m) is a density per steradian of microfacet normal, normalised so that
//! ∫ D(m) cos θm dωm = 1. The distribution of normals visible from `wo` is
//! D_wo(m) = G1(wo, m) max(0, wo·m) D(m) / cos θo, also normalised to 1 over dωm when G1 is the
//! exact Smith masking function.
//!
//! One deliberate difference from Mitsuba: for Beckmann, Mitsuba's G1 is a rational fit (< 0.35 %
//! error) used both in the BSDF value and in the pdf, while its sampler draws from the exact
//! visible-normal distribution, so its pdf is off by the fit's error (0.3 % seen at 85° incidence,
//! α = 0.8). Here the BSDF value keeps Mitsuba's fit ([`Microfacet::smith_g1`]) but the pdf uses
//! the exact G1, so that the pdf is the sampler's true density.

use crate::error::MaterialError;
use crate::special::{erf, erfc, erfinv};
use glam::{Vec2, Vec3};
use sampling::warp::sample_concentric_disk;
use std::f32::consts::{FRAC_2_SQRT_PI, PI};

/// Which normal distribution function a rough surface uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MicrofacetKind {
    /// Beckmann's distribution of Gaussian random surfaces: Mitsuba's default.
    Beckmann,
    /// GGX / Trowbridge–Reitz, with longer tails.
    Ggx,
}

/// A microfacet distribution of kind `kind` with roughness `alpha_u` along the shading frame's
/// first tangent (local x) and `alpha_v` along its second (local y): Mitsuba's `alpha_u` and
/// `alpha_v`, the RMS slopes for Beckmann, the width parameters for GGX. Isotropic when the two
/// are equal (Mitsuba's `alpha`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Microfacet {
    kind: MicrofacetKind,
    alpha_u: f32,
    alpha_v: f32,
}

/// The largest `f32` below 1, keeping arguments of `erfinv` finite.
const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

/// Densities below this (times cos θm) are flushed to zero, as in Mitsuba.
const MIN_DENSITY: f32 = 1e-20;

impl Microfacet {
    /// The smallest roughness: Mitsuba clamps `alpha` to at least this value.
    pub const MIN_ALPHA: f32 = 1e-4;

    /// A distribution of `kind` with roughness `alpha`, clamped below to [`Self::MIN_ALPHA`] like
    /// Mitsuba's; an error if `alpha` is NaN or infinite.
    pub fn new(kind: MicrofacetKind, alpha: f32) -> Result<Self, MaterialError> {
        Self::anisotropic(kind, alpha, alpha)
    }

    /// An anisotropic distribution of `kind` with roughness `alpha_u` along the first tangent
    /// and `alpha_v` along the second, each clamped below to [`Self::MIN_ALPHA`] like Mitsuba's;
    /// an error if either is NaN or infinite.
    pub fn anisotropic(
        kind: MicrofacetKind,
        alpha_u: f32,
        alpha_v: f32,
    ) -> Result<Self, MaterialError> {
        for value in [alpha_u, alpha_v] {
            if !value.is_finite() {
                return Err(MaterialError::InvalidRoughness { value });
            }
        }
        Ok(Self {
            kind,
            alpha_u: alpha_u.max(Self::MIN_ALPHA),
            alpha_v: alpha_v.max(Self::MIN_ALPHA),
        })
    }

    /// The distribution's kind.
    pub fn kind(&self) -> MicrofacetKind {
        self.kind
    }

    /// The roughness along the first and second tangent after clamping (dimensionless).
    pub fn alpha(&self) -> Vec2 {
        Vec2::new(self.alpha_u, self.alpha_v)
    }

    /// Whether the roughness differs between the two tangent directions, so that the
    /// distribution depends on how the shading frame is turned about its normal.
    pub fn is_anisotropic(&self) -> bool {
        self.alpha_u != self.alpha_v
    }

    /// D(m): density of microfacet normals per steradian at the unit normal `m`, zero for
    /// normals below the horizon.
    pub fn d(&self, m: Vec3) -> f32 {
        let cos_theta = m.z;
        let cos2 = cos_theta * cos_theta;
        let alpha2 = self.alpha_u * self.alpha_v;
        let (sx, sy) = (m.x / self.alpha_u, m.y / self.alpha_v);
        let result = match self.kind {
            MicrofacetKind::Beckmann => {
                (-(sx * sx + sy * sy) / cos2).exp() / (PI * alpha2 * cos2 * cos2)
            }
            MicrofacetKind::Ggx => {
                let denom = sx * sx + sy * sy + cos2;
                1.0 / (PI * alpha2 * denom * denom)
            }
        };
        // Comparisons with NaN are false, so 0/0 at the horizon also gives zero.
        if result * cos_theta > MIN_DENSITY {
            result
        } else {
            0.0
        }
    }

    /// Smith's masking function G1(v, m) in [0, 1]: the fraction of microfacets with normal `m`
    /// visible from direction `v`; zero when `v` sees the back of `m`.
    ///
    /// Exact for GGX; for Beckmann it is Mitsuba's rational approximation (< 0.35 % error).
    pub fn smith_g1(&self, v: Vec3, m: Vec3) -> f32 {
        if v.dot(m) * v.z <= 0.0 {
            return 0.0;
        }
        let xy_alpha2 = self.projected_alpha2(v);
        if xy_alpha2 == 0.0 {
            return 1.0;
        }
        let tan_theta_alpha2 = xy_alpha2 / (v.z * v.z);
        match self.kind {
            MicrofacetKind::Beckmann => {
                let a = 1.0 / tan_theta_alpha2.sqrt();
                if a >= 1.6 {
                    1.0
                } else {
                    let a2 = a * a;
                    (3.535 * a + 2.181 * a2) / (1.0 + 2.276 * a + 2.577 * a2)
                }
            }
            MicrofacetKind::Ggx => 2.0 / (1.0 + (1.0 + tan_theta_alpha2).sqrt()),
        }
    }

    /// The exact Smith masking function for this distribution, 1 / (1 + Λ(v)), with the same
    /// back-facing test as [`Self::smith_g1`]. Equal to it for GGX; for Beckmann it is the
    /// normalisation of the visible-normal distribution that the sampler draws from.
    pub fn smith_g1_exact(&self, v: Vec3, m: Vec3) -> f32 {
        match self.kind {
            MicrofacetKind::Ggx => self.smith_g1(v, m),
            MicrofacetKind::Beckmann => {
                if v.dot(m) * v.z <= 0.0 {
                    return 0.0;
                }
                let xy_alpha2 = self.projected_alpha2(v);
                if xy_alpha2 == 0.0 {
                    return 1.0;
                }
                // a = 1 / (α tan θ); Λ = (e^(−a²) / (a √π) − erfc(a)) / 2.
                let a = v.z.abs() / xy_alpha2.sqrt();
                let lambda = 0.5 * ((-a * a).exp() / (a * PI.sqrt()) - erfc(a));
                1.0 / (1.0 + lambda)
            }
        }
    }

    /// Smith's separable shadowing-masking G1(wo, m) · G1(wi, m), as Mitsuba uses.
    pub fn g(&self, wo: Vec3, wi: Vec3, m: Vec3) -> f32 {
        self.smith_g1(wo, m) * self.smith_g1(wi, m)
    }

    /// D_wo(m) with the exact G1: density per steradian of the normals visible from `wo`, the
    /// density of [`Self::sample_visible_normal`]. Zero unless `wo.z > 0`.
    pub fn visible_normal_pdf(&self, wo: Vec3, m: Vec3) -> f32 {
        if wo.z <= 0.0 {
            return 0.0;
        }
        self.visible_normal_pdf_given_d(wo, m, self.d(m))
    }

    /// [`Self::visible_normal_pdf`] for `wo.z > 0` when `d` is already known to be `D(m)`.
    pub(crate) fn visible_normal_pdf_given_d(&self, wo: Vec3, m: Vec3, d: f32) -> f32 {
        d * self.smith_g1_exact(wo, m) * wo.dot(m).abs() / wo.z
    }

    /// A microfacet normal visible from `wo` (`wo.z > 0`), distributed by D_wo, with its density
    /// per steradian. `None` when `wo` is not above the surface or the density vanishes.
    ///
    /// GGX uses Heitz's 2018 hemisphere construction (with the concentric disc map; the same
    /// distribution as Mitsuba's slope-space routine, a different map from `u`). Beckmann uses
    /// Mitsuba's routine: Jakob's numerically inverted slope CDF in the stretched frame.
    pub fn sample_visible_normal(&self, wo: Vec3, u: Vec2) -> Option<(Vec3, f32)> {
        if wo.z <= 0.0 {
            return None;
        }
        let m = match self.kind {
            MicrofacetKind::Ggx => self.sample_ggx_visible(wo, u),
            MicrofacetKind::Beckmann => self.sample_beckmann_visible(wo, u),
        }?;
        let pdf = self.visible_normal_pdf(wo, m);
        (pdf > 0.0 && pdf.is_finite()).then_some((m, pdf))
    }

    /// (α · v_xy)²: the squared length of `v`'s tangential part with each axis scaled by its
    /// roughness, which over v_z² is the squared tangent of θ the Smith terms need (the
    /// roughness in `v`'s azimuth, times its tangent).
    #[inline]
    fn projected_alpha2(&self, v: Vec3) -> f32 {
        let (x, y) = (self.alpha_u * v.x, self.alpha_v * v.y);
        x * x + y * y
    }

    /// Heitz 2018: sample the projected area of a hemisphere seen from the stretched direction.
    fn sample_ggx_visible(&self, wo: Vec3, u: Vec2) -> Option<Vec3> {
        let (au, av) = (self.alpha_u, self.alpha_v);
        let vh = Vec3::new(au * wo.x, av * wo.y, wo.z).normalize_or_zero();
        let len2 = vh.x * vh.x + vh.y * vh.y;
        let t1 = if len2 > 0.0 {
            Vec3::new(-vh.y, vh.x, 0.0) / len2.sqrt()
        } else {
            Vec3::X
        };
        let t2 = vh.cross(t1);
        let p = sample_concentric_disk(u);
        let s = 0.5 * (1.0 + vh.z);
        let p_y = (1.0 - s) * (1.0 - p.x * p.x).max(0.0).sqrt() + s * p.y;
        let n_z = (1.0 - p.x * p.x - p_y * p_y).max(0.0).sqrt();
        let nh = p.x * t1 + p_y * t2 + n_z * vh;
        let m = Vec3::new(au * nh.x, av * nh.y, nh.z.max(0.0)).normalize_or_zero();
        (m != Vec3::ZERO).then_some(m)
    }

    /// Mitsuba's Beckmann routine: stretch `wo`, sample unit-roughness slopes, rotate, unstretch.
    fn sample_beckmann_visible(&self, wo: Vec3, u: Vec2) -> Option<Vec3> {
        let (au, av) = (self.alpha_u, self.alpha_v);
        let wo_p = Vec3::new(au * wo.x, av * wo.y, wo.z).normalize_or_zero();
        let sin2 = wo_p.x * wo_p.x + wo_p.y * wo_p.y;
        let (sin_phi, cos_phi) = if sin2 <= 4.0 * f32::EPSILON {
            (0.0, 1.0)
        } else {
            let inv = 1.0 / sin2.sqrt();
            (
                (wo_p.y * inv).clamp(-1.0, 1.0),
                (wo_p.x * inv).clamp(-1.0, 1.0),
            )
        };
        let slope = beckmann_visible_slopes_unit(wo_p.z, u);
        let sx = (cos_phi * slope.x - sin_phi * slope.y) * au;
        let sy = (sin_phi * slope.x + cos_phi * slope.y) * av;
        let m = Vec3::new(-sx, -sy, 1.0).normalize_or_zero();
        m.is_finite().then_some(m).filter(|m| *m != Vec3::ZERO)
    }
}

impl Microfacet {
    /// The fraction of light arriving from `wo` (above the surface) that a rough dielectric
    /// interface of relative index `eta` with this distribution reflects (`reflect`) or
    /// refracts to the other side: the mean over the normals m visible from `wo` of F(wo·m)
    /// (or 1 − F) times the masking G1 of the direction leaving m. Integrated over the visible
    /// normal sampler's unit square by `n` × `n` Gauss–Legendre points, as Mitsuba's
    /// `eval_reflectance` and `eval_transmittance` are (its `roughplastic` tables come from them).
    pub fn interface_albedo(&self, wo: Vec3, eta: f32, reflect: bool, n: usize) -> f32 {
        let rule = crate::quadrature::gauss_legendre_unit(n);
        let mut sum = 0.0_f64;
        for &(x, wx) in &rule {
            for &(y, wy) in &rule {
                let Some((m, _)) = self.sample_visible_normal(wo, Vec2::new(x as f32, y as f32))
                else {
                    continue;
                };
                let fresnel = crate::fresnel::fresnel_dielectric(wo.dot(m), eta);
                let (wi, share) = if reflect {
                    (crate::fresnel::reflect_about(wo, m), fresnel.reflectance)
                } else {
                    let wi =
                        crate::fresnel::refract_about(wo, m, fresnel.cos_theta_t, fresnel.eta_ti);
                    (wi, 1.0 - fresnel.reflectance)
                };
                let right_side = if reflect { wi.z > 0.0 } else { wi.z < 0.0 };
                if right_side {
                    sum += wx * wy * f64::from(share * self.smith_g1(wi, m));
                }
            }
        }
        sum as f32
    }
}

/// Slopes of visible normals of the unit-roughness Beckmann surface seen at `cos_theta_i`
/// (Jakob 2014, "An Improved Visible Normal Sampling Routine for the Beckmann Distribution"):
/// the slope CDF is inverted in the erf domain by three Newton steps from an analytic guess.
fn beckmann_visible_slopes_unit(cos_theta_i: f32, u: Vec2) -> Vec2 {
    let inv_sqrt_pi = 0.5 * FRAC_2_SQRT_PI;
    let tan_theta_i = (1.0 - cos_theta_i * cos_theta_i).max(0.0).sqrt() / cos_theta_i;
    let cot_theta_i = 1.0 / tan_theta_i;
    let maxval = erf(cot_theta_i);
    let u = u.clamp(Vec2::splat(1e-6), Vec2::splat(1.0 - 1e-6));

    // Initial guess: the analytic solution at θi = π/2, the most nonlinear case.
    let mut x = maxval - (maxval + 1.0) * erf((-u.x.ln()).sqrt());
    // Scale the sample by the CDF's normalisation.
    let target =
        u.x * (1.0 + maxval + inv_sqrt_pi * tan_theta_i * (-cot_theta_i * cot_theta_i).exp());
    for _ in 0..3 {
        x = x.clamp(-ONE_MINUS_EPSILON, ONE_MINUS_EPSILON);
        let slope = erfinv(x);
        let value = 1.0 + x + inv_sqrt_pi * tan_theta_i * (-slope * slope).exp() - target;
        let derivative = 1.0 - slope * tan_theta_i;
        x -= value / derivative;
    }
    x = x.clamp(-ONE_MINUS_EPSILON, ONE_MINUS_EPSILON);
    let y = (2.0 * u.y - 1.0).clamp(-ONE_MINUS_EPSILON, ONE_MINUS_EPSILON);
    Vec2::new(erfinv(x), erfinv(y))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Midpoint rule over the upper hemisphere in (θ, φ), fine enough for alpha ≥ 0.05.
    fn integrate_hemisphere(f: impl Fn(Vec3) -> f32) -> f64 {
        let (n_theta, n_phi) = (2000, 64);
        let d_theta = std::f64::consts::FRAC_PI_2 / n_theta as f64;
        let d_phi = std::f64::consts::TAU / n_phi as f64;
        let mut sum = 0.0;
        for i in 0..n_theta {
            let theta = (i as f64 + 0.5) * d_theta;
            for j in 0..n_phi {
                let phi = (j as f64 + 0.5) * d_phi;
                let w = Vec3::new(
                    (theta.sin() * phi.cos()) as f32,
                    (theta.sin() * phi.sin()) as f32,
                    theta.cos() as f32,
                );
                sum += f64::from(f(w)) * theta.sin() * d_theta * d_phi;
            }
        }
        sum
    }

    fn distributions() -> Vec<Microfacet> {
        let mut all = Vec::new();
        for kind in [MicrofacetKind::Beckmann, MicrofacetKind::Ggx] {
            for alpha in [0.05, 0.3, 0.8] {
                all.push(Microfacet::new(kind, alpha).expect("finite alpha"));
            }
            for (alpha_u, alpha_v) in [(0.1, 0.4), (0.5, 0.2)] {
                all.push(Microfacet::anisotropic(kind, alpha_u, alpha_v).expect("finite alpha"));
            }
        }
        all
    }

    /// A direction at polar angle `theta` and an azimuth between the tangents, where an
    /// anisotropic lobe is neither of its two widths.
    fn oblique(theta: f32) -> Vec3 {
        let phi = 0.7_f32;
        Vec3::new(
            theta.sin() * phi.cos(),
            theta.sin() * phi.sin(),
            theta.cos(),
        )
    }

    #[test]
    fn projected_normal_density_integrates_to_one() {
        for distr in distributions() {
            let integral = integrate_hemisphere(|m| distr.d(m) * m.z);
            // GGX's long tail converges slowly for the widest lobe only at the horizon.
            assert!((integral - 1.0).abs() < 2e-3, "{distr:?}: {integral}");
        }
    }

    #[test]
    fn visible_normal_density_integrates_to_one() {
        for distr in distributions() {
            for theta_o in [0.0_f32, 0.8, 1.45] {
                let wo = oblique(theta_o);
                let integral = integrate_hemisphere(|m| distr.visible_normal_pdf(wo, m));
                assert!(
                    (integral - 1.0).abs() < 2e-3,
                    "{distr:?}, theta_o {theta_o}: {integral}"
                );
            }
        }
    }

    #[test]
    fn beckmann_g1_fit_is_close_to_exact_smith() {
        // Exact Beckmann Smith: G1 = 2 / (1 + erf(a) + e^(−a²) / (a √π)), a = 1 / (α tan θ).
        let distr = Microfacet::new(MicrofacetKind::Beckmann, 0.5).expect("finite alpha");
        for theta in [0.3_f32, 0.8, 1.2, 1.5] {
            let v = Vec3::new(theta.sin(), 0.0, theta.cos());
            let a = 1.0 / (0.5 * theta.tan());
            let exact = 2.0 / (1.0 + erf(a) + (-a * a).exp() / (a * PI.sqrt()));
            let fit = distr.smith_g1(v, Vec3::Z);
            assert!(
                (fit - exact).abs() / exact < 4e-3,
                "theta {theta}: {fit} vs {exact}"
            );
        }
    }

    #[test]
    fn g1_is_zero_for_backfacing_microfacets_and_one_at_normal_incidence() {
        for distr in distributions() {
            let m = Vec3::new(0.6, 0.0, 0.8);
            assert_eq!(
                distr.smith_g1(Vec3::new(-0.9, 0.0, 0.1).normalize(), m),
                0.0
            );
            assert_eq!(distr.smith_g1(Vec3::Z, m), 1.0);
        }
    }

    #[test]
    fn roughness_is_clamped_and_validated() {
        let tiny = Microfacet::new(MicrofacetKind::Ggx, 0.0).expect("finite alpha");
        assert_eq!(tiny.alpha(), Vec2::splat(Microfacet::MIN_ALPHA));
        let stretched = Microfacet::anisotropic(MicrofacetKind::Ggx, 0.0, 0.3).expect("finite");
        assert_eq!(stretched.alpha(), Vec2::new(Microfacet::MIN_ALPHA, 0.3));
        assert!(stretched.is_anisotropic() && !tiny.is_anisotropic());
        assert!(Microfacet::anisotropic(MicrofacetKind::Ggx, 0.2, f32::NAN).is_err());
        assert!(Microfacet::new(MicrofacetKind::Beckmann, f32::NAN).is_err());
        assert!(Microfacet::new(MicrofacetKind::Beckmann, f32::INFINITY).is_err());
    }

    #[test]
    fn sampled_normals_are_visible_and_unit() {
        let mut rng = sampling::Rng::new(7);
        for distr in distributions() {
            for theta_o in [0.0_f32, 0.8, 1.55] {
                let wo = oblique(theta_o);
                for _ in 0..1000 {
                    let u = Vec2::new(rng.next_f32(), rng.next_f32());
                    let (m, pdf) = distr
                        .sample_visible_normal(wo, u)
                        .unwrap_or_else(|| panic!("{distr:?} wo {wo} u {u}: no normal"));
                    assert!((m.length() - 1.0).abs() < 1e-5);
                    assert!(
                        m.z >= 0.0 && wo.dot(m) > 0.0,
                        "{distr:?} wo {wo} u {u}: m {m}"
                    );
                    assert!((pdf - distr.visible_normal_pdf(wo, m)).abs() <= 1e-6 * pdf);
                }
            }
        }
    }
}
