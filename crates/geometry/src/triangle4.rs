//! The watertight ray-triangle test of [`crate::triangle`] on four triangles at once.
//!
//! The four triangles sit in the four lanes of vectors, so every step of the single-triangle
//! test runs once for all of them, with the same operations in the same order: each lane's
//! result is bit for bit the single-triangle test's. The rare lanes that need more than single
//! precision (an edge function exactly zero, or a hit within the error bound of `t` from the
//! origin) are handed to the single-triangle test, which recomputes them in double precision.

use glam::{Vec3, Vec3A, Vec4};

use crate::triangle::{RayShear, TriangleCoords, TriangleHit, t_error_bound};

/// Up to four triangles, by vertex and coordinate: `vertices[i][c]` holds coordinate `c` of
/// vertex `i` of the triangles in its four lanes. Unused lanes hold NaN, which no ray hits.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Triangle4 {
    vertices: [[Vec4; 3]; 3],
}

impl Triangle4 {
    /// The packet of `triangles` (at most four) in lanes `0, 1, ...`.
    ///
    /// # Panics
    /// If there are more than four.
    pub fn new(triangles: impl IntoIterator<Item = TriangleCoords>) -> Self {
        let mut vertices = [[Vec4::NAN; 3]; 3];
        for (lane, tri) in triangles.into_iter().enumerate() {
            assert!(lane < 4, "more than four triangles in a packet");
            for (c, coords) in tri.coords.iter().enumerate() {
                for (i, vertex) in vertices.iter_mut().enumerate() {
                    vertex[c][lane] = coords[i];
                }
            }
        }
        Self { vertices }
    }

    /// The point with barycentric coordinates `b` (weights of `p0`, `p1`, `p2`) of the triangle in
    /// `lane`: the same sums as [`TriangleCoords::point`], computed for all lanes at once (which
    /// avoids gathering one lane's coordinates through memory).
    #[inline(always)]
    pub fn point(&self, lane: usize, b: Vec3) -> Vec3 {
        let [p0, p1, p2] = &self.vertices;
        let along = |c: usize| (p0[c] * b.x + p1[c] * b.y + p2[c] * b.z).to_array()[lane];
        Vec3::new(along(0), along(1), along(2))
    }

    /// The triangle in `lane` (NaN coordinates for an unused lane).
    pub fn triangle(&self, lane: usize) -> TriangleCoords {
        // Through arrays: indexing a vector by a variable lane compiles to a jump table.
        let [a, b, c] = self.vertices.map(|v| v.map(|c| c.to_array()[lane]));
        TriangleCoords {
            coords: [0, 1, 2].map(|k| Vec3A::new(a[k], b[k], c[k])),
        }
    }
}

/// [`RayShear::nearest4`] for the ray `origin + t dir` when some lane needs the single-triangle
/// test: a free function of values, so that the hot caller's ray data need not be kept in
/// memory for it.
#[cold]
fn nearest4_redone(
    origin: Vec3A,
    dir: Vec3A,
    tri: &Triangle4,
    t_max: f32,
) -> Option<(usize, TriangleHit)> {
    let mut nearest: Option<(usize, TriangleHit)> = None;
    let hits = RayShear::new(origin, dir).intersect4(tri, t_max);
    for (lane, hit) in hits.into_iter().enumerate() {
        if let Some(hit) = hit
            && nearest.is_none_or(|(_, n)| hit.t < n.t)
        {
            nearest = Some((lane, hit));
        }
    }
    nearest
}

/// The single-precision part of the test on four lanes.
struct Lanes {
    /// Distances (meaningful in `hit` lanes).
    t: Vec4,
    /// The edge functions.
    edges: [Vec4; 3],
    inv_det: Vec4,
    /// Lanes hit at `t` (bit `i` for lane `i`).
    hit: u32,
    /// Lanes the single-triangle test must decide.
    redo: u32,
}

impl RayShear {
    /// The hit of the ray with each triangle of `tri` (either side) with `0 < t < t_max`, by
    /// lane; bit for bit what [`RayShear::intersect`] gives for each of them.
    pub fn intersect4(&self, tri: &Triangle4, t_max: f32) -> [Option<TriangleHit>; 4] {
        let lanes = self.lanes(tri, 0b1111, t_max);
        std::array::from_fn(|lane| {
            if lanes.hit & (1 << lane) != 0 {
                Some(lanes.hit_in(lane))
            } else if lanes.redo & (1 << lane) != 0 {
                self.intersect(&tri.triangle(lane), t_max)
            } else {
                None
            }
        })
    }

    /// The nearest hit with a triangle of `tri` in the lanes `used` (a bitmask) with
    /// `0 < t < t_max` and its lane (the first lane of equally near ones).
    #[inline(always)]
    pub fn nearest4(&self, tri: &Triangle4, used: u32, t_max: f32) -> Option<(usize, TriangleHit)> {
        let lanes = self.lanes(tri, used, t_max);
        if lanes.redo != 0 {
            return nearest4_redone(self.origin_point(), self.dir(), tri, t_max);
        }
        if lanes.hit == 0 {
            return None;
        }
        let mut nearest = lanes.hit.trailing_zeros() as usize;
        let mut rest = lanes.hit & (lanes.hit - 1);
        let t = lanes.t.to_array();
        while rest != 0 {
            let lane = rest.trailing_zeros() as usize;
            if t[lane] < t[nearest] {
                nearest = lane;
            }
            rest &= rest - 1;
        }
        Some((nearest, lanes.hit_in(nearest)))
    }

    /// Whether the ray hits any triangle of `tri` in the lanes `used` (a bitmask) with
    /// `0 < t < t_max`.
    #[inline(always)]
    pub fn any4(&self, tri: &Triangle4, used: u32, t_max: f32) -> bool {
        let lanes = self.lanes(tri, used, t_max);
        lanes.hit != 0 || (lanes.redo != 0 && self.any_redone(tri, lanes.redo, t_max))
    }

    /// Whether the single-triangle test finds a hit in one of the lanes `redo` (a bitmask).
    #[cold]
    fn any_redone(&self, tri: &Triangle4, redo: u32, t_max: f32) -> bool {
        (0..4).any(|lane| {
            redo & (1 << lane) != 0 && self.intersect(&tri.triangle(lane), t_max).is_some()
        })
    }

    /// Every step of [`RayShear::intersect`] up to its double-precision cases, on the lanes
    /// `used` (a bitmask; the others count as misses).
    #[inline(always)]
    fn lanes(&self, tri: &Triangle4, used: u32, t_max: f32) -> Lanes {
        let [kx, ky, kz] = self.axes;
        let [sx, sy, sz] = self.shear;
        let o = &self.origin;
        let sheared = |p: &[Vec4; 3]| {
            let dz = p[kz] - o[kz];
            (p[kx] - o[kx] - sx * dz, p[ky] - o[ky] - sy * dz, sz * dz)
        };
        let (xa, ya, za) = sheared(&tri.vertices[0]);
        let (xb, yb, zb) = sheared(&tri.vertices[1]);
        let (xc, yc, zc) = sheared(&tri.vertices[2]);
        let u = xc * yb - yc * xb;
        let v = xa * yc - ya * xc;
        let w = xb * ya - yb * xa;
        let zero = Vec4::ZERO;
        // Lanes with an edge function exactly 0 go to the single-triangle test, which
        // recomputes it in double precision. In the others the edge functions have one sign
        // unless their sign bits differ.
        let any_zero = (u.cmpeq(zero) | v.cmpeq(zero) | w.cmpeq(zero)).bitmask() & used;
        let [su, sv, sw] = [u, v, w].map(Vec4::is_negative_bitmask);
        let same_side = used & !any_zero & !((su ^ sv) | (su ^ sw));
        // Most packets a ray reaches it misses: stop as soon as that is certain.
        if same_side | any_zero == 0 {
            return Lanes::NONE;
        }
        let det = u + v + w;
        let t_scaled = u * za + v * zb + w * zc;
        let t_max4 = Vec4::splat(t_max);
        let t_max_det = t_max4 * det;
        let front = det.cmpgt(zero);
        let inside = (front & t_scaled.cmpgt(zero) & t_scaled.cmplt(t_max_det))
            | (!front & t_scaled.cmplt(zero) & t_scaled.cmpgt(t_max_det));
        let inv_det = det.recip();
        let t = t_scaled * inv_det;
        let passed = same_side & (det.cmpne(zero) & inside & !t.cmpge(t_max4)).bitmask();
        if passed | any_zero == 0 {
            return Lanes::NONE;
        }
        let max = |a: Vec4, b: Vec4, c: Vec4| a.abs().max(b.abs()).max(c.abs());
        let bound = t_error_bound(
            [max(xa, xb, xc), max(ya, yb, yc), max(za, zb, zc)],
            max(u, v, w),
            inv_det.abs(),
        );
        let clear = t.cmpgt(bound).bitmask();
        Lanes {
            t,
            edges: [u, v, w],
            inv_det,
            hit: passed & clear,
            redo: any_zero | (passed & !clear),
        }
    }
}

impl Lanes {
    /// The hit in `lane`, one of the `hit` lanes.
    #[inline(always)]
    fn hit_in(&self, lane: usize) -> TriangleHit {
        // Through arrays: indexing a vector by a variable lane compiles to a jump table.
        let [u, v, w] = self.edges.map(|e| e.to_array()[lane]);
        TriangleHit {
            t: self.t.to_array()[lane],
            bary: Vec3::new(u, v, w) * self.inv_det.to_array()[lane],
        }
    }

    /// No lane hit, none to redo.
    const NONE: Lanes = Lanes {
        t: Vec4::ZERO,
        edges: [Vec4::ZERO; 3],
        inv_det: Vec4::ZERO,
        hit: 0,
        redo: 0,
    };
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::TestRng;

    fn same(a: Option<TriangleHit>, b: Option<TriangleHit>) -> bool {
        let bits = |h: Option<TriangleHit>| {
            h.map(|h| (h.t.to_bits(), h.bary.to_array().map(f32::to_bits)))
        };
        bits(a) == bits(b)
    }

    /// Triangles sharing edges and vertices (edge functions exactly zero for rays through them),
    /// some degenerate, some huge next to the ray origin (double-precision hits), all compared
    /// lane by lane with the single-triangle test, bit for bit.
    #[test]
    fn every_lane_matches_the_single_triangle_test() {
        let seed = 0x5eed_0020;
        let mut rng = TestRng(seed);
        let mut hits = 0;
        let mut redone = 0;
        for case in 0..100_000 {
            let corners = [rng.vec_a(), rng.vec_a(), rng.vec_a(), rng.vec_a()];
            let count = 1 + case % 4;
            let tris: Vec<TriangleCoords> = (0..count)
                .map(|i| {
                    let tri = match (case / 4 + i) % 5 {
                        // A fan around corner 0: shared edges and a shared vertex.
                        0 => [corners[0], corners[1 + i % 3], corners[1 + (i + 1) % 3]],
                        // Degenerate: a repeated vertex.
                        1 => [corners[0], corners[1], corners[1]],
                        // Huge, through the origin region.
                        2 => [corners[0] * 1e4, corners[1] * 1e4, corners[2] * 1e4],
                        _ => [rng.vec_a(), rng.vec_a(), rng.vec_a()],
                    };
                    TriangleCoords::new(tri)
                })
                .collect();
            let packet = Triangle4::new(tris.iter().copied());
            // Rays from random points, or from a point of a triangle (hits at t near 0), aimed
            // at corners (through shared vertices and edges) or anywhere.
            let origin = if case % 3 == 0 {
                let tri = &tris[0];
                let (u, v) = (rng.f32() * 0.5, rng.f32() * 0.5);
                Vec3A::from(tri.point(Vec3::new(1.0 - u - v, u, v))) + 1e-6 * rng.vec_a()
            } else {
                2.0 * rng.vec_a()
            };
            let target = match case % 4 {
                0 => corners[case % 3],
                1 => (corners[0] + corners[1]) * 0.5,
                _ => rng.vec_a(),
            };
            let dir = target - origin;
            if dir.length_squared() == 0.0 {
                continue;
            }
            let dir = dir.normalize();
            let t_max = if case % 5 == 0 {
                rng.f32()
            } else {
                f32::INFINITY
            };
            let shear = RayShear::new(origin, dir);
            let got = shear.intersect4(&packet, t_max);
            for lane in 0..4 {
                let expected = if lane < count {
                    shear.intersect(&tris[lane], t_max)
                } else {
                    None
                };
                assert!(
                    same(got[lane], expected),
                    "seed {seed:#x}, case {case}, lane {lane}: {:?} vs {expected:?}",
                    got[lane]
                );
                hits += usize::from(expected.is_some());
            }
            assert_eq!(
                shear.any4(&packet, (1 << count) - 1, t_max),
                got.iter().any(Option::is_some),
                "seed {seed:#x}, case {case}"
            );
            let lanes = shear.lanes(&packet, (1 << count) - 1, t_max);
            redone += lanes.redo.count_ones() as usize;
            assert_eq!(
                lanes.redo & !((1 << count) - 1),
                0,
                "unused lanes are never redone"
            );
        }
        assert!(hits > 20_000, "only {hits} hits");
        assert!(redone > 1_000, "only {redone} lanes redone");
    }

    #[test]
    fn points_match_the_single_triangle_points() {
        let mut rng = TestRng(0x5eed_0021);
        for _ in 0..1000 {
            let tris: Vec<TriangleCoords> = (0..4)
                .map(|_| {
                    TriangleCoords::new([rng.vec_a(), rng.vec_a(), rng.vec_a()].map(|v| v * 100.0))
                })
                .collect();
            let packet = Triangle4::new(tris.iter().copied());
            let b = Vec3::new(rng.f32(), rng.f32(), rng.f32());
            for (lane, tri) in tris.iter().enumerate() {
                let bits = |p: Vec3| p.to_array().map(f32::to_bits);
                assert_eq!(bits(packet.point(lane, b)), bits(tri.point(b)));
            }
        }
    }

    #[test]
    fn nearest_takes_the_first_of_equal_hits() {
        let tri = TriangleCoords::new([
            Vec3A::new(-1.0, -1.0, -2.0),
            Vec3A::new(1.0, -1.0, -2.0),
            Vec3A::new(0.0, 1.0, -2.0),
        ]);
        // The same plane one unit nearer (z holds the three vertices' z coordinates).
        let mut closer = tri;
        closer.coords[2] = Vec3A::splat(-1.0);
        let packet = Triangle4::new([tri, closer, closer]);
        let shear = RayShear::new(Vec3A::ZERO, Vec3A::NEG_Z);
        let (lane, hit) = shear
            .nearest4(&packet, 0b111, f32::INFINITY)
            .expect("a hit");
        assert_eq!((lane, hit.t), (1, 1.0));
        let packet = Triangle4::new([tri, tri]);
        assert_eq!(
            shear
                .nearest4(&packet, 0b11, f32::INFINITY)
                .map(|(l, h)| (l, h.t)),
            Some((0, 2.0))
        );
        assert_eq!(shear.nearest4(&packet, 0b11, 2.0).map(|(l, _)| l), None);
    }
}
