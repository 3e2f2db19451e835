//! Path reuse (Bekaert, Sbert and Halton, "Accelerating Path Tracing by Re-Using Paths", EGWR
//! 2002): the camera paths of a small block of pixels share their second vertices.
//!
//! A pixel's indirect light through its first vertex x is ∫ f(x → y) G(x, y) L_r(y → x) dA(y)
//! over the surfaces y that x sees, where L_r is the radiance y reflects (its emission is left
//! to x's own path, with its usual MIS weight). Each path j of the block sampled one such y_j
//! from its own first vertex x_j with density p_j(y) = pdf_bsdf(x_j → y) · cos θ_y / d² ·
//! V(x_j, y) per unit area, and estimated L_r(y_j) by the rest of its walk. Where y_j is
//! diffuse, the radiance it reflects is the same in every direction of its side, so that
//! estimate serves every first vertex on the same side of y_j. Every path i of the block then
//! counts every shared y_j with the balance heuristic over the block's first vertices,
//!
//! ```text
//! Σ_j  f(x_i → y_j) G(x_i, y_j) V(x_i, y_j) L_r(y_j)  /  Σ_k p_k(y_j),
//! ```
//!
//! the sums over the paths whose first vertex is diffuse and on the same side of y_j as x_j
//! (by its geometric and by its shading normal). The weights p_k / Σ p_k sum to one over the
//! strategies that can produce y wherever path i's own can, so each pixel's estimate stays
//! unbiased; where y_j is not diffuse, or was not reached, path j's estimate stays its own. A
//! block of n paths traces up to n(n − 1) more shadow rays (x_k to y_j, k ≠ j, one ray serving
//! both the weight and the contribution) and gives each pixel n estimates of its indirect
//! light. With the balance heuristic a connection never weighs more than its path's own BSDF
//! sample would (f G / Σ p_k ≤ f G / p_i = f cos / pdf, the albedo for cosine sampling), so
//! short connections into corners make no fireflies. The pixels' errors are correlated within a
//! block (each pixel's own error is what shrinks), which shows as blocky noise at low sample
//! counts.
//!
//! **When `auto` uses it.** 4 × 4 blocks are one of `auto`'s trials wherever a diffuse material
//! is, kept when the pilot measures them more efficient (the Cornell box); path reuse and light
//! tracing exclude each other.

use geometry::SpawnPoint;
use glam::{Vec3, Vec4};
use materials::Bsdf;
use world::{RayTally, SurfaceHit, World};

mod lanes;

use lanes::{FirstVertexLanes, GROUPS, RadianceLanes, lanes_of};

/// The most paths [`combine`] takes at once.
pub const MAX_BLOCK_PATHS: usize = 16;

/// A path's first vertex, kept where it is diffuse, to be connected to the block's second
/// vertices.
#[derive(Clone, Copy, Debug)]
pub struct FirstVertex {
    /// Position, geometric normal, and where its shadow rays start (moved off the surface to
    /// either side once per vertex rather than once per connection).
    point: SpawnPoint,
    /// Unit normal of the shading frame its BSDF sees (the diffuse lobe's +z).
    n: Vec3,
    /// Whether the camera is above the lobe (`wo.z > 0`): else it reflects nothing that way.
    faces_camera: bool,
    /// Its reflectance (RGB, not zero).
    albedo: Vec3,
}

impl FirstVertex {
    /// The first vertex at `surface` (whose point is `point`), seen from `wo` (local frame), if
    /// its BSDF is diffuse and reflects something: a black one never continues its path, so it
    /// samples no second vertex.
    pub(crate) fn at(surface: &SurfaceHit<'_>, point: &SpawnPoint, wo: Vec3) -> Option<Self> {
        match surface.bsdf {
            Bsdf::Diffuse(diffuse) if diffuse.reflectance() != Vec3::ZERO => Some(Self {
                point: *point,
                n: surface.frame.n,
                faces_camera: wo.z > 0.0,
                albedo: diffuse.reflectance(),
            }),
            _ => None,
        }
    }
}

/// A path's second vertex, kept where it is diffuse, with the radiance it reflects towards the
/// path's first vertex (W m⁻² sr⁻¹, RGB; its own emission not included).
#[derive(Clone, Copy, Debug)]
pub struct SecondVertex {
    /// Position, geometric normal, and where shadow rays to it end.
    point: SpawnPoint,
    /// Unit shading normal.
    ns: Vec3,
    /// The estimate of the radiance reflected towards the path's first vertex.
    pub(crate) reflected: Vec3,
}

impl SecondVertex {
    /// The second vertex at `surface` (whose point is `point`) if its BSDF is diffuse (the
    /// radiance it reflects is then the same towards every point on one side of it);
    /// `reflected` is filled in later.
    pub(crate) fn at(surface: &SurfaceHit<'_>, point: &SpawnPoint) -> Option<Self> {
        matches!(surface.bsdf, Bsdf::Diffuse(_)).then_some(Self {
            point: *point,
            ns: surface.hit.ns,
            reflected: Vec3::ZERO,
        })
    }

    /// On which side of this vertex `x` lies, by its geometric and by its shading normal: the
    /// radiance it reflects towards points with the same sides is the same (a two-sided
    /// material's side and a diffuse lobe's hemisphere follow the shading normal, ray offsets
    /// the geometric one).
    fn side_of(&self, x: Vec3) -> (bool, bool) {
        let to_x = x - self.point.p;
        (self.point.ng.dot(to_x) > 0.0, self.ns.dot(to_x) > 0.0)
    }
}

/// One camera path's estimate, split for path reuse by
/// [`crate::PathIntegrator::radiance_reusable`].
#[derive(Clone, Copy, Debug, Default)]
pub struct ReusablePath {
    /// The estimate (W m⁻² sr⁻¹, RGB) without what the second vertex reflects towards the
    /// first; the whole estimate when `second` is `None`.
    pub own: Vec3,
    /// The first vertex, where it is diffuse.
    pub first: Option<FirstVertex>,
    /// The second vertex, where both it and the first are diffuse.
    pub second: Option<SecondVertex>,
}

/// What path reuse keeps of one walk of [`crate::PathIntegrator::radiance_reusable`]: the first
/// vertex where it is diffuse, the second once it is found diffuse, and then the estimate up to
/// the second vertex, while the walk goes on estimating what the second reflects.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct WalkSplit {
    /// The first vertex, where it is diffuse.
    first: Option<FirstVertex>,
    /// The second vertex, where both it and the first are diffuse.
    second: Option<SecondVertex>,
    /// The estimate up to the second vertex (W m⁻² sr⁻¹, RGB), once it is found.
    own: Vec3,
}

impl WalkSplit {
    /// Keeps the walk's vertex number `depth` at `surface` (whose point is `point`, seen from
    /// `wo`, local frame) where it is one path reuse connects, with the walk's estimate so far,
    /// `radiance`. True when the vertex is the second: the walk then estimates afresh, from it,
    /// the radiance it reflects.
    #[inline(always)]
    pub(crate) fn keep(
        &mut self,
        depth: u32,
        surface: &SurfaceHit<'_>,
        point: &SpawnPoint,
        wo: Vec3,
        radiance: Vec3,
    ) -> bool {
        if depth == 1 {
            self.first = FirstVertex::at(surface, point, wo);
        } else if depth == 2
            && self.first.is_some()
            && let Some(found) = SecondVertex::at(surface, point)
        {
            self.second = Some(found);
            self.own = radiance;
            return true;
        }
        false
    }

    /// The path's estimate with the walk's final `radiance` (the whole estimate, or with a
    /// second vertex what it reflects).
    #[inline(always)]
    pub(crate) fn finish(self, radiance: Vec3) -> ReusablePath {
        match self.second {
            Some(mut second) => {
                second.reflected = radiance;
                ReusablePath {
                    own: self.own,
                    first: self.first,
                    second: Some(second),
                }
            }
            None => ReusablePath {
                own: radiance,
                first: self.first,
                second: None,
            },
        }
    }
}

/// The estimates of `paths` (one camera sample each, of nearby pixels) with their second
/// vertices shared as the module documentation says, written to `radiance` (same length; W
/// m⁻² sr⁻¹, RGB). Traces a shadow ray from each first vertex to each other path's second
/// vertex on its side. Alone, a path gets its unsplit estimate back (up to rounding).
///
/// # Panics
/// If `radiance` is shorter than `paths` or `paths` has more than [`MAX_BLOCK_PATHS`] entries.
pub fn combine(
    world: &World,
    paths: &[ReusablePath],
    tally: &mut impl RayTally,
    radiance: &mut [Vec3],
) {
    assert!(paths.len() <= MAX_BLOCK_PATHS, "too many paths to combine");
    let mut sums = RadianceLanes::of(paths.iter().map(|path| path.own));
    let firsts = FirstVertexLanes::of(paths);
    for (j, path) in paths.iter().enumerate() {
        let (Some(x_j), Some(y)) = (&path.first, &path.second) else {
            continue;
        };
        let side = y.side_of(x_j.point.p);
        // The densities of the first vertices that see y, group by group (zero elsewhere).
        let mut pdf_area = [Vec4::ZERO; GROUPS];
        for (group, seen_pdf) in pdf_area.iter_mut().enumerate().take(firsts.groups()) {
            let connections = firsts.towards(group, y, side);
            if connections.counted == 0 {
                continue;
            }
            let rays = connections.rays.lanes(connections.t_max);
            let mut pdf = connections.pdf_area.to_array();
            for lane in lanes_of(connections.counted) {
                let (origin, dir, t_max) = rays[lane];
                // Path j's own second vertex is what its ray found, visible; the others are
                // seen where their shadow ray is not blocked.
                if 4 * group + lane != j && !world.connection_unoccluded(origin, dir, t_max, tally)
                {
                    pdf[lane] = 0.0;
                }
            }
            *seen_pdf = Vec4::from_array(pdf);
        }
        let total_pdf_area = pdf_area
            .iter()
            .flat_map(|group| group.to_array())
            .fold(0.0, |total, pdf| total + pdf);
        if total_pdf_area > 0.0 {
            let share = y.reflected / total_pdf_area;
            for (group, &pdf) in pdf_area.iter().enumerate().take(firsts.groups()) {
                sums.add_shares(&firsts, group, pdf, share);
            }
        }
    }
    sums.write_to(&mut radiance[..paths.len()]);
}

#[cfg(test)]
mod tests {
    use super::*;
    use geometry::{Accel, Ray, Shape, Sphere};
    use glam::Mat3;
    use materials::Diffuse;
    use std::f32::consts::FRAC_1_PI;
    use world::RayCounters;

    const ALBEDO: Vec3 = Vec3::new(0.8, 0.5, 0.2);
    const REFLECTED: Vec3 = Vec3::new(2.0, 3.0, 4.0);

    /// A world of `spheres` (diffuse, no lights) for the connections' shadow rays.
    fn world(spheres: &[(Vec3, f32)]) -> World {
        let shapes = spheres
            .iter()
            .map(|&(center, radius)| {
                Shape::Sphere(Sphere {
                    center,
                    radius,
                    flip_normals: false,
                    to_local: Mat3::IDENTITY,
                })
            })
            .collect::<Vec<_>>();
        let count = shapes.len();
        World::new(
            Accel::new(shapes),
            vec![Bsdf::Diffuse(Diffuse::new(Vec3::splat(0.5)))],
            vec![0; count],
            vec![None; count],
            Vec::new(),
            Vec::new(),
        )
        .expect("valid world")
    }

    /// A path whose first vertex is at `x` on the floor (normal +z) seen from straight above,
    /// and whose second vertex, if any, is at `y` with normal `n`.
    fn path(own: f32, x: Vec3, second: Option<(Vec3, Vec3)>) -> ReusablePath {
        path_from(own, (x, Vec3::Z), second)
    }

    /// The error bound test points are given: a few units in the last place of `p`'s
    /// coordinates, as a hit's.
    fn error(p: Vec3) -> Vec3 {
        geometry::gamma(7.0) * p.abs()
    }

    /// [`path`] with the first vertex's normal given too (seen along it).
    fn path_from(own: f32, x: (Vec3, Vec3), second: Option<(Vec3, Vec3)>) -> ReusablePath {
        ReusablePath {
            own: Vec3::splat(own),
            first: Some(FirstVertex {
                point: SpawnPoint::new(x.0, x.1, error(x.0)),
                n: x.1,
                faces_camera: true,
                albedo: ALBEDO,
            }),
            second: second.map(|(p, n)| SecondVertex {
                point: SpawnPoint::new(p, n, error(p)),
                ns: n,
                reflected: REFLECTED,
            }),
        }
    }

    /// f · cos θx · cos θy / d² and the area density, from first vertex `x` (normal +z) to `y`
    /// (normal `n`), written out independently of [`FirstVertexLanes::towards`].
    fn by_hand(x: Vec3, y: Vec3, n: Vec3) -> (Vec3, f32) {
        let d = y - x;
        let (cos_x, cos_y) = (d.z / d.length(), n.dot(-d).abs() / d.length());
        let g = cos_x * cos_y / d.length_squared();
        (
            ALBEDO * FRAC_1_PI * g,
            cos_x * FRAC_1_PI * cos_y / d.length_squared(),
        )
    }

    fn combined(world: &World, paths: &[ReusablePath]) -> (Vec<Vec3>, RayCounters) {
        let mut radiance = vec![Vec3::ZERO; paths.len()];
        let mut tally = RayCounters::default();
        combine(world, paths, &mut tally, &mut radiance);
        (radiance, tally)
    }

    fn assert_close(actual: Vec3, expected: Vec3, what: &str) {
        assert!(
            (actual - expected).abs().max_element() <= 1e-5 * expected.abs().max_element(),
            "{what}: {actual} against {expected}"
        );
    }

    #[test]
    fn a_path_alone_gets_its_own_estimate_back() {
        // Cosine sampling's weight f cos / pdf is the albedo, so the path's own second vertex
        // adds albedo × reflected, as the unsplit walk would.
        let (y, n) = (Vec3::new(0.3, -0.2, 1.5), Vec3::NEG_Z);
        let (radiance, tally) = combined(&world(&[]), &[path(1.0, Vec3::ZERO, Some((y, n)))]);
        assert_close(radiance[0], Vec3::ONE + ALBEDO * REFLECTED, "alone");
        assert_eq!(
            tally.shadow_rays, 0,
            "its own second vertex needs no shadow ray"
        );
    }

    #[test]
    fn shared_second_vertices_are_weighted_by_the_balance_heuristic() {
        let (x0, x1) = (Vec3::ZERO, Vec3::new(0.5, 0.0, 0.0));
        let (y0, y1) = (Vec3::new(0.2, 0.1, 1.0), Vec3::new(-0.4, 0.3, 2.0));
        let n = Vec3::NEG_Z;
        let paths = [path(0.0, x0, Some((y0, n))), path(0.0, x1, Some((y1, n)))];
        let (radiance, tally) = combined(&world(&[]), &paths);
        for (i, x) in [x0, x1].into_iter().enumerate() {
            let expected: Vec3 = [y0, y1]
                .into_iter()
                .map(|y| {
                    let (f_g, _) = by_hand(x, y, n);
                    let total = by_hand(x0, y, n).1 + by_hand(x1, y, n).1;
                    f_g * REFLECTED / total
                })
                .sum();
            assert_close(radiance[i], expected, &format!("path {i}"));
        }
        assert_eq!(tally.shadow_rays, 2, "one shadow ray per shared connection");
        assert_eq!(tally.connection_rays, 2, "counted as connections");
    }

    #[test]
    fn occluded_and_other_side_first_vertices_neither_share_nor_weigh() {
        // Path 1's first vertex is hidden from path 0's second vertex by a sphere, and path 2's
        // faces it from behind its plane (a ceiling above a card lit from below): path 0 keeps
        // its own estimate whole, and paths 1 and 2 get nothing from it.
        let (x0, y0, n) = (Vec3::ZERO, Vec3::new(0.0, 0.0, 1.0), Vec3::NEG_Z);
        let x1 = Vec3::new(2.0, 0.0, 0.0);
        let x2 = (Vec3::new(0.3, 0.0, 1.5), Vec3::NEG_Z);
        let blocker = (Vec3::new(1.0, 0.0, 0.5), 0.2);
        let paths = [
            path(0.0, x0, Some((y0, n))),
            path(0.0, x1, None),
            path_from(0.0, x2, None),
        ];
        let (radiance, tally) = combined(&world(&[blocker]), &paths);
        assert_close(radiance[0], ALBEDO * REFLECTED, "the path that found it");
        assert_eq!(radiance[1], Vec3::ZERO, "occluded");
        assert_eq!(radiance[2], Vec3::ZERO, "other side");
        assert_eq!(tally.shadow_rays, 1, "no shadow ray to the other side");
    }

    #[test]
    fn connection_rays_are_the_shadow_rays_of_world_unoccluded() {
        // Every first vertex of a block against second vertices on both sides of each, far from
        // and near the origin (where the offsets switch from ulps to a fixed distance), bit for
        // bit against `Ray::spawn_to`, which `World::unoccluded` traces.
        let firsts = [
            (Vec3::new(0.3, -2.0, 5.0), Vec3::Z),
            (Vec3::new(1e4, 0.01, -3e3), Vec3::new(0.0, 0.6, -0.8)),
            (Vec3::ZERO, Vec3::new(-0.48, 0.6, 0.64)),
            (Vec3::new(0.02, -0.01, 0.5), Vec3::NEG_X),
            (Vec3::new(-7.0, 3.0, 0.0), Vec3::new(0.6, 0.0, 0.8)),
        ];
        let seconds = [
            (Vec3::new(0.3, -2.0, 6.0), Vec3::NEG_Z),
            (Vec3::new(1e4, 2.0, -3e3), Vec3::Y),
            (Vec3::new(0.01, 0.0, 0.0), Vec3::new(0.0, 0.8, 0.6)),
            (Vec3::new(-7.0, 3.0, 1e-3), Vec3::new(0.6, 0.0, 0.8)),
            // In the tangent plane of the first: n · d is exactly zero there.
            (Vec3::new(1.3, -2.0, 5.0), Vec3::X),
        ];
        let paths = firsts.map(|x| path_from(0.0, x, None));
        let lanes = FirstVertexLanes::of(&paths);
        let mut rays = 0;
        for (q, n) in seconds.into_iter().flat_map(|(q, n)| [(q, n), (q, -n)]) {
            let y = SecondVertex {
                point: SpawnPoint::new(q, n, error(q)),
                ns: n,
                reflected: REFLECTED,
            };
            let side = y.side_of(firsts[0].0);
            let groups = (0..lanes.groups())
                .map(|group| {
                    let connections = lanes.towards(group, &y, side);
                    connections.rays.lanes(connections.t_max)
                })
                .collect::<Vec<_>>();
            for (k, &(p, ng)) in firsts.iter().enumerate() {
                let (origin, dir, t_max) = groups[k / 4][k % 4];
                let (expected, expected_t_max) = Ray::spawn_to(p, ng, error(p), q, n, error(q));
                let what = format!("from {p} (normal {ng}) to {q} (normal {n})");
                assert_eq!(Vec3::from(origin), expected.origin, "origin {what}");
                assert_eq!(Vec3::from(dir), expected.dir, "direction {what}");
                assert_eq!(t_max, expected_t_max, "t_max {what}");
                rays += usize::from(t_max > 0.0);
            }
        }
        assert!(rays > 40, "only {rays} of 50 connections have a segment");
    }
}
