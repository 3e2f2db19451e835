//! Watertight ray-triangle intersection (Woop, Benthin and Wald, "Watertight Ray/Triangle
//! Intersection", JCGT 2013).
//!
//! The ray is made the +z axis of a sheared frame; each vertex is transformed once, and the
//! three edge functions are 2D cross products of transformed vertices. A shared edge is evaluated
//! from the same transformed vertices by both of its triangles, with opposite signs, so a ray can
//! never pass between them; exact zeros are re-evaluated in double precision.
//!
//! A hit must also lie conservatively in front of the origin: its `t` has to exceed a bound on
//! the rounding error of `t` (the bound of pbrt-v4, section 6.8.4), which grows with the distance
//! of the vertices from the origin. Without it, a ray leaving a large triangle whose own hit point
//! has small coordinates (a 1000-unit floor through the origin) can re-hit it at a `t` that is
//! pure rounding noise. A hit whose `t` is positive but inside that bound is recomputed in double
//! precision, where the bound is 2^29 times smaller: a ray that really meets a huge triangle
//! close to its origin (a camera a centimetre above a 10 km ground plane) still hits it.

use std::ops::{Add, Mul};

use glam::{DVec3, Vec3, Vec3A, Vec3Swizzles, Vec4};

/// Per-ray data of the watertight test: the ray origin, the dominant axis `kz` of the direction
/// and the other two `kx`, `ky`, and the shear that maps the direction to `+z`, each number
/// splatted so that one vector operation handles the same coordinate of several vertices.
///
/// A vertex `p` is sheared to `(d[kx] - sx d[kz], d[ky] - sy d[kz], sz d[kz])` with
/// `d = p - origin`, `sz = 1 / dir[kz]`, `sx = dir[kx] sz`, `sy = dir[ky] sz`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RayShear {
    /// Origin coordinates x, y, z.
    pub(crate) origin: [Vec4; 3],
    /// `[kx, ky, kz]`.
    pub(crate) axes: [usize; 3],
    /// `[sx, sy, sz]`.
    pub(crate) shear: [Vec4; 3],
    /// The ray direction, for the double-precision recomputation.
    dir: Vec3A,
}

/// A triangle's vertices stored by coordinate: `coords[0]` holds the x coordinates of `p0`, `p1`,
/// `p2` (in its lanes 0, 1, 2), and likewise y and z.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TriangleCoords {
    pub coords: [Vec3A; 3],
}

impl TriangleCoords {
    /// The triangle with vertices `p0`, `p1`, `p2`.
    pub fn new([p0, p1, p2]: [Vec3A; 3]) -> Self {
        Self {
            coords: [
                Vec3A::new(p0.x, p1.x, p2.x),
                Vec3A::new(p0.y, p1.y, p2.y),
                Vec3A::new(p0.z, p1.z, p2.z),
            ],
        }
    }

    /// The point with barycentric coordinates `b` (weights of `p0`, `p1`, `p2`), summed in
    /// vertex order (what [`crate::triangle4::Triangle4::point`] must match).
    #[cfg(test)]
    pub fn point(&self, b: Vec3) -> Vec3 {
        let along = |c: Vec3A| c.x * b.x + c.y * b.y + c.z * b.z;
        Vec3::from(self.coords.map(along))
    }
}

/// Barycentric coordinates `(b0, b1, b2)` of `p0`, `p1`, `p2` and the distance of a hit.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TriangleHit {
    pub t: f32,
    pub bary: Vec3,
}

impl RayShear {
    /// Prepares the shear for the ray `origin + t * dir` (`dir` non-zero).
    #[inline(always)]
    pub fn new(origin: Vec3A, dir: Vec3A) -> Self {
        // kz is the dominant axis; (kx, ky) follow it cyclically, swapped when the ray looks
        // down -kz so that the projected triangle keeps its winding.
        let a = dir.abs();
        let kz = if a.x >= a.y && a.x >= a.z {
            0
        } else if a.y >= a.z {
            1
        } else {
            2
        };
        let (next, after) = ((kz + 1) % 3, (kz + 2) % 3);
        // Through an array: indexing a vector by a variable compiles to a jump table.
        let d = dir.to_array();
        let (kx, ky) = if d[kz] < 0.0 {
            (after, next)
        } else {
            (next, after)
        };
        let sz = 1.0 / d[kz];
        Self {
            origin: [origin.x, origin.y, origin.z].map(Vec4::splat),
            axes: [kx, ky, kz],
            shear: [d[kx] * sz, d[ky] * sz, sz].map(Vec4::splat),
            dir,
        }
    }

    /// The hit of the ray with triangle `tri` (either side) with `0 < t < t_max`, if any.
    #[inline(always)]
    pub fn intersect(&self, tri: &TriangleCoords, t_max: f32) -> Option<TriangleHit> {
        // Sheared coordinates of the three vertices a, b, c, by coordinate: xs = (a.x, b.x, c.x).
        let [kx, ky, kz] = self.axes;
        let d = |k: usize| tri.coords[k] - Vec3A::from_vec4(self.origin[k]);
        let [sx, sy, sz] = self.shear.map(Vec3A::from_vec4);
        let dz = d(kz);
        let xs = d(kx) - sx * dz;
        let ys = d(ky) - sy * dz;
        let zs = sz * dz;
        // Edge functions (u, v, w) = (c.x b.y - c.y b.x, a.x c.y - a.y c.x, b.x a.y - b.y a.x).
        let mut edges = xs.zxy() * ys.yzx() - ys.zxy() * xs.yzx();
        if edges.cmpeq(Vec3A::ZERO).any() {
            let cross = |i: usize, j: usize| {
                (f64::from(xs[i]) * f64::from(ys[j]) - f64::from(ys[i]) * f64::from(xs[j])) as f32
            };
            edges = Vec3A::new(cross(2, 1), cross(0, 2), cross(1, 0));
        }
        if edges.cmplt(Vec3A::ZERO).any() && edges.cmpgt(Vec3A::ZERO).any() {
            return None;
        }
        let det = edges.x + edges.y + edges.z;
        if det == 0.0 {
            return None;
        }
        let weighted = edges * zs;
        let t_scaled = weighted.x + weighted.y + weighted.z;
        // 0 < t_scaled / det < t_max without dividing.
        let inside = if det > 0.0 {
            t_scaled > 0.0 && t_scaled < t_max * det
        } else {
            t_scaled < 0.0 && t_scaled > t_max * det
        };
        if !inside {
            return None;
        }
        let inv_det = 1.0 / det;
        let t = t_scaled * inv_det;
        let max = [xs, ys, zs].map(|v| v.abs().max_element());
        if t >= t_max {
            return None;
        }
        let bound = t_error_bound(max, edges.abs().max_element(), inv_det.abs());
        if t > bound {
            return Some(TriangleHit {
                t,
                bary: Vec3::from(edges * inv_det),
            });
        }
        intersect_f64(self.origin_point(), self.dir, tri, t_max)
    }

    /// The ray origin (the first lane of the splatted coordinates).
    #[inline(always)]
    pub(crate) fn origin_point(&self) -> Vec3A {
        Vec3A::new(self.origin[0].x, self.origin[1].x, self.origin[2].x)
    }

    /// The ray direction.
    #[inline(always)]
    pub(crate) fn dir(&self) -> Vec3A {
        self.dir
    }
}

/// The same test in double precision, for hits too close to the origin for the single
/// precision error bound to place them in front of it.
///
/// A free function of values (not of the `RayShear`), so that the hot caller's ray data need
/// not be kept in memory for it.
#[cold]
fn intersect_f64(
    origin: Vec3A,
    dir: Vec3A,
    tri: &TriangleCoords,
    t_max: f32,
) -> Option<TriangleHit> {
    let dir = dir.as_dvec3();
    let kz = dir.abs().max_position();
    let (kx, ky) = if dir[kz] < 0.0 {
        ((kz + 2) % 3, (kz + 1) % 3)
    } else {
        ((kz + 1) % 3, (kz + 2) % 3)
    };
    let (sx, sy, sz) = (dir[kx] / dir[kz], dir[ky] / dir[kz], 1.0 / dir[kz]);
    let origin = origin.as_dvec3();
    let sheared = |i: usize| {
        let p = DVec3::from(tri.coords.map(|c| f64::from(c[i]))) - origin;
        DVec3::new(p[kx] - sx * p[kz], p[ky] - sy * p[kz], sz * p[kz])
    };
    let (a, b, c) = (sheared(0), sheared(1), sheared(2));
    let edges = DVec3::new(
        c.x * b.y - c.y * b.x,
        a.x * c.y - a.y * c.x,
        b.x * a.y - b.y * a.x,
    );
    if edges.min_element() < 0.0 && edges.max_element() > 0.0 {
        return None;
    }
    let det = edges.element_sum();
    if det == 0.0 {
        return None;
    }
    let t = (edges.x * a.z + edges.y * b.z + edges.z * c.z) / det;
    let max = a.abs().max(b.abs()).max(c.abs());
    let gamma = |n: f64| n * f64::EPSILON * 0.5 / (1.0 - n * f64::EPSILON * 0.5);
    let delta_z = gamma(3.0) * max.z;
    let delta_x = gamma(5.0) * (max.x + max.z);
    let delta_y = gamma(5.0) * (max.y + max.z);
    let delta_e = 2.0 * (gamma(2.0) * max.x * max.y + delta_y * max.x + delta_x * max.y);
    let max_e = edges.abs().max_element();
    let bound = 3.0 * (gamma(3.0) * max_e * max.z + delta_e * max.z + delta_z * max_e) / det.abs();
    (t > bound && t < f64::from(t_max) && t as f32 > 0.0).then(|| TriangleHit {
        t: t as f32,
        bary: (edges / det).as_vec3(),
    })
}

/// `n u / (1 - n u)` with `u = 2^-24`: the relative error bound of `n` rounded `f32` operations
/// (pbrt's `gamma`).
pub const fn gamma(n: f32) -> f32 {
    let u = f32::EPSILON * 0.5;
    n * u / (1.0 - n * u)
}

/// Numbers the error bound can be computed on: one `f32`, or four lanes of them.
pub(crate) trait Number: Copy + Add<Output = Self> + Mul<Output = Self> {
    fn splat(x: f32) -> Self;
}

impl Number for f32 {
    #[inline(always)]
    fn splat(x: f32) -> Self {
        x
    }
}

impl Number for Vec4 {
    #[inline(always)]
    fn splat(x: f32) -> Self {
        Vec4::splat(x)
    }
}

/// Bound on the absolute rounding error of `t` computed from the largest magnitude `max` of each
/// sheared coordinate over the three vertices, the largest magnitude `max_e` of the edge
/// functions and `|1 / det|`. Written once for one triangle and for four, so that both compute it
/// with the same operations in the same order.
#[inline(always)]
pub(crate) fn t_error_bound<T: Number>(max: [T; 3], max_e: T, inv_det_abs: T) -> T {
    let [x, y, z] = max;
    let g = |n: f32| T::splat(gamma(n));
    let delta_z = g(3.0) * z;
    let delta_x = g(5.0) * (x + z);
    let delta_y = g(5.0) * (y + z);
    let delta_e = T::splat(2.0) * (g(2.0) * x * y + delta_y * x + delta_x * y);
    T::splat(3.0) * (g(3.0) * max_e * z + delta_e * z + delta_z * max_e) * inv_det_abs
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri() -> TriangleCoords {
        TriangleCoords::new([
            Vec3A::new(0.0, 0.0, -2.0),
            Vec3A::new(1.0, 0.0, -2.0),
            Vec3A::new(0.0, 1.0, -2.0),
        ])
    }

    #[test]
    fn hit_distance_and_barycentrics() {
        let shear = RayShear::new(Vec3A::new(0.25, 0.5, 0.0), Vec3A::NEG_Z);
        let hit = shear.intersect(&tri(), f32::INFINITY).expect("inside");
        assert_eq!(hit.t, 2.0);
        assert!(hit.bary.abs_diff_eq(Vec3::new(0.25, 0.25, 0.5), 1e-6));
        // Both sides hit, since nothing is culled.
        let back = RayShear::new(Vec3A::new(0.25, 0.5, -4.0), Vec3A::Z);
        assert_eq!(
            back.intersect(&tri(), f32::INFINITY).map(|h| h.t),
            Some(2.0)
        );
    }

    #[test]
    fn misses_outside_behind_and_beyond_t_max() {
        let outside = RayShear::new(Vec3A::new(0.75, 0.5, 0.0), Vec3A::NEG_Z);
        assert!(outside.intersect(&tri(), f32::INFINITY).is_none());
        let behind = RayShear::new(Vec3A::new(0.25, 0.25, 0.0), Vec3A::Z);
        assert!(behind.intersect(&tri(), f32::INFINITY).is_none());
        let short = RayShear::new(Vec3A::new(0.25, 0.25, 0.0), Vec3A::NEG_Z);
        assert!(short.intersect(&tri(), 2.0).is_none());
    }

    #[test]
    fn rounding_noise_behind_the_origin_is_not_a_hit() {
        // A ray leaving a 2000-unit floor upwards, from 2^-16 above it at a point with small
        // coordinates: t comes out at about +6e-5 though the floor lies behind the origin.
        let floor = TriangleCoords::new([
            Vec3A::new(-1000.0, -1000.0, 0.0),
            Vec3A::new(1000.0, 1000.0, 0.0),
            Vec3A::new(-1000.0, 1000.0, 0.0),
        ]);
        let origin = Vec3A::new(-381.40607, 200.33887, 1.0 / 65536.0);
        let dir = Vec3A::new(0.734063, -0.3494725, 0.58225465);
        assert!(
            RayShear::new(origin, dir)
                .intersect(&floor, f32::INFINITY)
                .is_none()
        );
        // Turned downwards it hits at every height, though below about 3e-2 its single
        // precision t is within the error bound and is recomputed in double precision.
        let down = dir * Vec3A::new(1.0, 1.0, -1.0);
        for height in [1e-1, 3e-2, 1e-3, 1e-6] {
            let from = Vec3A::new(origin.x, origin.y, height);
            let hit = RayShear::new(from, down).intersect(&floor, f32::INFINITY);
            let hit = hit.unwrap_or_else(|| panic!("height {height}: no hit"));
            // Single precision is good to about 1e-4 here, double to about 1e-7 of t.
            let expected = height / 0.58225465;
            let tolerance = if height < 1e-2 { 1e-3 * expected } else { 1e-3 };
            assert!(
                (hit.t - expected).abs() < tolerance,
                "height {height}: t = {}",
                hit.t
            );
        }
    }

    #[test]
    fn degenerate_triangle_never_hits() {
        let line = TriangleCoords::new([Vec3A::ZERO, Vec3A::X, Vec3A::new(2.0, 0.0, 0.0)]);
        let point = TriangleCoords::new([Vec3A::ONE; 3]);
        for dir in [
            Vec3A::NEG_Z,
            Vec3A::new(1.0, 0.0, -1.0).normalize(),
            Vec3A::Y,
        ] {
            let shear = RayShear::new(Vec3A::new(0.5, 0.0, 1.0), dir);
            assert!(shear.intersect(&line, f32::INFINITY).is_none());
            assert!(shear.intersect(&point, f32::INFINITY).is_none());
        }
    }
}
