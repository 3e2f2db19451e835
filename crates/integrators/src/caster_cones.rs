//! Light paths aimed at mirrors and glass: the light tracer's emitted direction drawn from a
//! mixture of the cosine distribution and cones towards the shapes that cast caustics.
//!
//! **What it is.** The light tracer contributes only paths whose first bounce is by a delta lobe
//! (`light_tracer`). From a light, the cosine-distributed direction of Lambertian emission meets a
//! small mirror or glass object rarely (a sphere of radius 0.23 three units away: at most one path
//! in 170), so most light paths end at their first hit, on a diffuse surface, having cost a ray.
//! Aiming a quarter of them at the *casters* — the shapes whose material has only delta lobes —
//! multiplies the paths that can make a caustic (Jensen's projection maps for photon mapping, with
//! a cone per bounding sphere instead of a map).
//!
//! **The formula.** From the emitted point y, each caster k outside whose bounding sphere
//! (centre c_k, radius r_k) y lies subtends a cone of half-angle θ_k, sin²θ_k = r_k² / |c_k − y|².
//! With the share s = [`COSINE_SHARE`] of directions cosine-distributed about the normal n and
//! the rest uniform within the cone of one of the K casters, chosen uniformly,
//!
//! ```text
//! p(ω) = s · max(0, n·ω) / π  +  (1 − s) / K · Σ_k [ω in cone k] / (2π (1 − cos θ_k))
//! ```
//!
//! per steradian. The cosine part keeps every direction possible, so every caustic the cosine
//! distribution could start (through plastic's coat as well) still can be; a cone chosen from a
//! point inside its sphere, or whose angle is too small for `f32`, draws nothing (a sample of
//! zero weight), and the density leaves it out alike, so the estimate stays unbiased. The path's
//! weight is Lambertian emission's over [`CasterCones::relative_density`], the ratio of p(ω)
//! to the cosine density, which the caustic weights against the path tracer take too
//! (`caustic_mis`).
//!
//! **When it is used.** With light tracing, in scenes with such shapes (static ones: moving
//! shapes are left to the cosine part).

use glam::{Vec2, Vec3};
use materials::BsdfFlags;
use sampling::Frame;
use sampling::warp::{sample_uniform_cone, uniform_cone_pdf};
use std::f32::consts::FRAC_1_PI;
use world::World;

/// Share of light paths whose direction is cosine-distributed, the rest aimed at casters. At
/// `auto`'s defaults (`--time 2`, 18 generated scenes with caustics and the glass box, two
/// seeds) 0.75 gave 0.96× the relMSE of cosine emission alone (standard error of the log 0.05)
/// and 0.5 gave 1.01×: aimed paths run on through the glass and cost more rays.
pub const COSINE_SHARE: f32 = 0.75;

/// The most casters light paths aim at (the largest by bounding radius); the rest are left to
/// the cosine part, which keeps the estimate unbiased.
const MAX_CASTERS: usize = 16;

/// Below this sin²θ a cone is too narrow to sample and test in `f32` and is left out.
const NARROWEST_CONE_SIN2: f32 = 1e-10;

/// The bounding spheres of the shapes that cast caustics (see the module documentation).
#[derive(Clone, Debug)]
pub(crate) struct CasterCones {
    /// Centre and radius (world units) of each caster's bounding sphere.
    spheres: Box<[(Vec3, f32)]>,
}

/// The cone from a point towards one caster's bounding sphere.
struct Cone {
    /// Unit axis, from the point to the sphere's centre.
    axis: Vec3,
    /// sin² of the half-angle.
    sin2_max: f32,
    /// 1 − cos of the half-angle, computed without cancellation.
    one_minus_cos_max: f32,
}

impl Cone {
    /// The cone from `y` towards the sphere (`centre`, `radius`); `None` from inside it or when
    /// it is too narrow.
    #[inline]
    fn towards(y: Vec3, (centre, radius): (Vec3, f32)) -> Option<Self> {
        let to_centre = centre - y;
        let d2 = to_centre.length_squared();
        let sin2_max = radius * radius / d2;
        if !(NARROWEST_CONE_SIN2..1.0).contains(&sin2_max) {
            return None;
        }
        Some(Self {
            axis: to_centre / d2.sqrt(),
            sin2_max,
            one_minus_cos_max: sin2_max / (1.0 + (1.0 - sin2_max).sqrt()),
        })
    }

    /// Whether the unit direction `w` lies in the cone (by its sine, exact for narrow cones).
    #[inline]
    fn contains(&self, w: Vec3) -> bool {
        w.dot(self.axis) > 0.0 && w.cross(self.axis).length_squared() <= self.sin2_max
    }

    /// Density per steradian of a direction uniform in the cone.
    #[inline]
    fn pdf(&self) -> f32 {
        uniform_cone_pdf(self.one_minus_cos_max)
    }

    /// A direction uniform in the cone from `u` ∈ [0, 1)².
    #[inline]
    fn sample(&self, u: Vec2) -> Vec3 {
        Frame::from_normal(self.axis)
            .to_world(sample_uniform_cone(u, self.one_minus_cos_max))
            .normalize()
    }
}

impl CasterCones {
    /// The casters of `world`: its static shapes whose material has delta lobes and no other
    /// (mirrors, glass), the largest [`MAX_CASTERS`] of them; `None` without any.
    pub(crate) fn new(world: &World) -> Option<Self> {
        let mut spheres: Vec<(Vec3, f32)> = world
            .static_shape_materials()
            .filter(|(_, bsdf)| {
                let flags = bsdf.flags();
                flags.contains(BsdfFlags::DELTA)
                    && !flags.intersects(BsdfFlags::DIFFUSE | BsdfFlags::GLOSSY)
            })
            .filter_map(|(bounds, _)| {
                let radius = 0.5 * bounds.diagonal().length();
                (radius.is_finite() && radius > 0.0).then(|| (bounds.center(), radius))
            })
            .collect();
        // The largest casters, at most MAX_CASTERS of them: each costs a cone test per light
        // path and per caustic the path tracer finds.
        spheres.sort_by(|a, b| b.1.total_cmp(&a.1));
        spheres.truncate(MAX_CASTERS);
        (!spheres.is_empty()).then_some(Self {
            spheres: spheres.into_boxed_slice(),
        })
    }

    /// Whether a light path draws its direction from the cosine part, for the direction's
    /// first number `u`, and `u` made uniform again in [0, 1) for that part.
    #[inline]
    pub(crate) fn cosine_part(u: f32) -> (bool, f32) {
        if u < COSINE_SHARE {
            (true, u / COSINE_SHARE)
        } else {
            (false, (u - COSINE_SHARE) / (1.0 - COSINE_SHARE))
        }
    }

    /// A direction from `y` aimed at a caster, from `u` ∈ [0, 1)² (its x already remapped by
    /// [`Self::cosine_part`]): the caster uniformly, then a direction uniform in its cone;
    /// `None` when the chosen cone is left out from `y` (see the module documentation).
    #[inline]
    pub(crate) fn sample(&self, y: Vec3, u: Vec2) -> Option<Vec3> {
        let count = self.spheres.len();
        let scaled = u.x * count as f32;
        let k = (scaled as usize).min(count - 1);
        let u_cone = Vec2::new(
            (scaled - k as f32).clamp(0.0, 1.0 - f32::EPSILON / 2.0),
            u.y,
        );
        Some(Cone::towards(y, self.spheres[k])?.sample(u_cone))
    }

    /// p(ω) over the cosine density, (n·ω / π), for the unit direction `w` from `y` on a
    /// surface with unit normal `n` (see the module documentation); 0 where n·ω ≤ 0, where
    /// nothing is emitted.
    #[inline]
    pub(crate) fn relative_density(&self, y: Vec3, n: Vec3, w: Vec3) -> f32 {
        let cosine = n.dot(w) * FRAC_1_PI;
        if cosine <= 0.0 {
            return 0.0;
        }
        self.density(y, n, w) / cosine
    }

    /// p(ω), per steradian, for the unit direction `w` from `y` on a surface with unit normal
    /// `n`: the cosine part (0 below the surface) and the cones that contain `w`.
    #[inline]
    fn density(&self, y: Vec3, n: Vec3, w: Vec3) -> f32 {
        let cosine = n.dot(w).max(0.0) * FRAC_1_PI;
        let cones: f32 = self
            .spheres
            .iter()
            .filter_map(|&sphere| Cone::towards(y, sphere))
            .filter(|cone| cone.contains(w))
            .map(|cone| cone.pdf())
            .sum();
        let aimed = (1.0 - COSINE_SHARE) / self.spheres.len() as f32 * cones;
        COSINE_SHARE * cosine + aimed
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use sampling::chi2::{Chi2Config, Chi2Domain, chi2_test, integrate_pdf};

    /// ∫ p(ω) dω over the sphere by the chi-square harness's cubature: a density must integrate
    /// to the probability of drawing a direction at all.
    #[test]
    fn the_mixture_integrates_to_what_it_draws() {
        let cones = CasterCones {
            spheres: Box::new([
                (Vec3::new(0.0, 3.0, 0.5), 0.4),
                (Vec3::new(2.0, 0.5, 0.0), 1.0),
            ]),
        };
        let (y, n) = (Vec3::ZERO, Vec3::Y);
        // Both cones are drawn from y, so all mass is drawn: ∫ p = 1.
        let integral = integrate_pdf(Chi2Domain::Sphere, |w| cones.density(y, n, w), 32);
        assert!((integral - 1.0).abs() < 0.01, "∫ p = {integral}");
    }

    /// A light path's directions as the light tracer draws them from `y` (normal `n`).
    fn draw(cones: &CasterCones, y: Vec3, n: Vec3, rng: &mut sampling::rng::Rng) -> Option<Vec3> {
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        let (cosine, u_x) = CasterCones::cosine_part(u.x);
        let u = Vec2::new(u_x, u.y);
        if cosine {
            Some(Frame::from_normal(n).to_world(sampling::warp::sample_cosine_hemisphere(u)))
        } else {
            cones.sample(y, u)
        }
    }

    /// Chi-square test (α = 0.01, two tests, Šidák-corrected) of the drawn directions against
    /// the density, from a point that sees one caster whole, one partly below its surface and
    /// one from inside (never drawn); and its power: the same draws against a density that
    /// gives the cones 60% of the paths instead of 50% must fail.
    #[test]
    fn drawn_directions_follow_the_mixture_density() {
        let cones = CasterCones {
            spheres: Box::new([
                (Vec3::new(0.5, 3.0, 0.2), 0.4),
                (Vec3::new(2.0, 0.4, -0.5), 1.0),
                (Vec3::new(0.1, 0.0, 0.0), 0.5),
            ]),
        };
        let (y, n) = (Vec3::ZERO, Vec3::Y);
        let config = Chi2Config {
            sample_count: 400_000,
            seed: 7,
            test_count: 2,
            ..Chi2Config::default()
        };
        let outcome = chi2_test(
            Chi2Domain::Sphere,
            |rng| draw(&cones, y, n, rng),
            |w| cones.density(y, n, w),
            &config,
        );
        println!("figure: aimed light paths: {}", outcome.summary());
        assert!(outcome.passed, "{outcome}");
        // Wrong shares: 40% cosine, 60% cones (both still integrate to what is drawn).
        let wrong = |w: Vec3| {
            let cosine = n.dot(w).max(0.0) * FRAC_1_PI;
            let aimed = cones.density(y, n, w) - COSINE_SHARE * cosine;
            0.4 * cosine + aimed * 0.6 / (1.0 - COSINE_SHARE)
        };
        let biased = chi2_test(
            Chi2Domain::Sphere,
            |rng| draw(&cones, y, n, rng),
            wrong,
            &config,
        );
        assert!(
            !biased.passed,
            "a 60/40 density passed: {}",
            biased.summary()
        );
    }

    #[test]
    fn sampled_directions_lie_in_their_cone_even_when_it_is_narrow() {
        let y = Vec3::new(0.1, 0.2, 0.3);
        for (centre, radius) in [
            (Vec3::new(0.0, 5.0, 0.0), 1.0),
            (Vec3::new(1e3, 2.0, 0.0), 1e-2),
        ] {
            let cone = Cone::towards(y, (centre, radius)).expect("outside the sphere");
            for i in 0..64 {
                let u = Vec2::new((i as f32 + 0.5) / 64.0, (i * 37 % 64) as f32 / 64.0);
                let w = cone.sample(u);
                assert!(cone.contains(w), "{w} outside the cone to {centre}");
            }
            // The edge of the cone, drawn at u.x → 1, stays inside within rounding.
            let edge = cone.sample(Vec2::new(1.0 - f32::EPSILON, 0.3));
            let sin2 = edge.cross(cone.axis).length_squared();
            assert!(
                sin2 <= cone.sin2_max * 1.001,
                "{sin2} against {}",
                cone.sin2_max
            );
        }
        assert!(
            Cone::towards(y, (y + Vec3::X * 0.5, 1.0)).is_none(),
            "from inside"
        );
    }
}
