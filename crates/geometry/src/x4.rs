//! Ray spawning four lanes at a time: 3-vectors coordinate by coordinate (structure of arrays),
//! surface points with their offset ray origins, and the shadow rays between such points, each
//! lane bit for bit what [`SpawnPoint`] and [`crate::Ray::between`] give for it.

use glam::{BVec4A, Mat4, Vec3, Vec3A, Vec4};

use crate::SpawnPoint;

/// Four 3-vectors, coordinate by coordinate (structure of arrays).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vec3x4 {
    /// The four x coordinates.
    pub x: Vec4,
    /// The four y coordinates.
    pub y: Vec4,
    /// The four z coordinates.
    pub z: Vec4,
}

impl Vec3x4 {
    /// `v` in all four lanes.
    #[inline]
    pub fn splat(v: Vec3) -> Self {
        Self {
            x: Vec4::splat(v.x),
            y: Vec4::splat(v.y),
            z: Vec4::splat(v.z),
        }
    }

    /// Sets the vector in `lane` (0–3) to `v`.
    #[inline]
    pub fn set_lane(&mut self, lane: usize, v: Vec3) {
        (self.x[lane], self.y[lane], self.z[lane]) = (v.x, v.y, v.z);
    }

    /// Dot products, summed x, y, z in that order (as [`Vec3::dot`] sums them).
    #[inline]
    pub fn dot(&self, other: &Self) -> Vec4 {
        self.x * other.x + self.y * other.y + self.z * other.z
    }

    /// Differences, lane by lane.
    #[inline]
    pub fn minus(&self, other: &Self) -> Self {
        Self {
            x: self.x - other.x,
            y: self.y - other.y,
            z: self.z - other.z,
        }
    }

    /// Each lane's vector divided by that lane of `by`.
    #[inline]
    pub fn divided_by(&self, by: Vec4) -> Self {
        Self {
            x: self.x / by,
            y: self.y / by,
            z: self.z / by,
        }
    }

    /// `if_true`'s vectors where `mask` is set, `if_false`'s elsewhere.
    #[inline]
    pub fn select(mask: BVec4A, if_true: &Self, if_false: &Self) -> Self {
        Self {
            x: Vec4::select(mask, if_true.x, if_false.x),
            y: Vec4::select(mask, if_true.y, if_false.y),
            z: Vec4::select(mask, if_true.z, if_false.z),
        }
    }
}

/// Four [`SpawnPoint`]s, lane by lane.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SpawnPointx4 {
    /// Positions on the surfaces (world units).
    pub p: Vec3x4,
    /// Unit geometric normals.
    pub ng: Vec3x4,
    /// The positions moved to the side of `ng` (world units).
    pub front: Vec3x4,
    /// The positions moved to the other side (world units).
    pub back: Vec3x4,
}

impl SpawnPointx4 {
    /// `point` in all four lanes.
    #[inline]
    pub fn splat(point: &SpawnPoint) -> Self {
        Self {
            p: Vec3x4::splat(point.p),
            ng: Vec3x4::splat(point.ng),
            front: Vec3x4::splat(point.front),
            back: Vec3x4::splat(point.back),
        }
    }

    /// Sets `lane` (0–3) to `point`.
    #[inline]
    pub fn set_lane(&mut self, lane: usize, point: &SpawnPoint) {
        self.p.set_lane(lane, point.p);
        self.ng.set_lane(lane, point.ng);
        self.front.set_lane(lane, point.front);
        self.back.set_lane(lane, point.back);
    }

    /// [`SpawnPoint::origin_towards`] lane by lane, given each lane's `ng · dir`.
    #[inline]
    pub fn origins_towards(&self, ng_dot_dir: Vec4) -> Vec3x4 {
        Vec3x4::select(ng_dot_dir.cmplt(Vec4::ZERO), &self.back, &self.front)
    }
}

/// Four rays, lane by lane.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rayx4 {
    /// Start points (world units).
    pub origin: Vec3x4,
    /// Unit directions.
    pub dir: Vec3x4,
}

impl Rayx4 {
    /// [`crate::Ray::between`] lane by lane: the shadow rays from `origin` to `end` and their
    /// `t_max` (short of `end` by [`crate::SHADOW_EPSILON`] of the distance), where `to_target` is each lane's direction between the unmoved points; direction
    /// `fallback` and `t_max = 0` where the moved points coincide or pass each other.
    #[inline]
    pub fn between(
        origin: &Vec3x4,
        end: &Vec3x4,
        to_target: &Vec3x4,
        fallback: &Vec3x4,
    ) -> (Self, Vec4) {
        let d = end.minus(origin);
        let distance = d.dot(&d).sqrt();
        // `distance < ∞` also leaves out NaN, as `is_finite` does.
        let forward = distance.cmpgt(Vec4::ZERO)
            & distance.cmplt(Vec4::INFINITY)
            & d.dot(to_target).cmpgt(Vec4::ZERO);
        (
            Self {
                origin: *origin,
                dir: Vec3x4::select(forward, &d.divided_by(distance), fallback),
            },
            Vec4::select(
                forward,
                distance * (1.0 - crate::SHADOW_EPSILON),
                Vec4::ZERO,
            ),
        )
    }

    /// All four rays, lane by lane, as [`crate::Accel::occluded_wide`] takes them: origin and
    /// unit direction as 16-byte vectors, and that lane of `t_max` (world units). Two 4 × 4
    /// transposes, instead of gathering each lane's coordinates one by one.
    #[inline]
    pub fn lanes(&self, t_max: Vec4) -> [(Vec3A, Vec3A, f32); 4] {
        let origins = Mat4::from_cols(self.origin.x, self.origin.y, self.origin.z, t_max);
        let dirs = Mat4::from_cols(self.dir.x, self.dir.y, self.dir.z, Vec4::ZERO);
        let (origins, dirs) = (origins.transpose(), dirs.transpose());
        std::array::from_fn(|lane| {
            let origin = origins.col(lane);
            (
                Vec3A::from_vec4(origin),
                Vec3A::from_vec4(dirs.col(lane)),
                origin.w,
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::TestRng;

    /// A surface point at `p` with unit normal `n` and an error bound of a few ulps of `p`,
    /// and that bound.
    fn point(p: Vec3, n: Vec3) -> (SpawnPoint, Vec3) {
        let e = crate::gamma(7.0) * p.abs();
        (SpawnPoint::new(p, n, e), e)
    }

    /// Pairs of surface points (with their error bounds): random ones near and far from the
    /// origin, coincident ones, ones a few ulps apart (whose offset points pass each other), and
    /// tangent ones.
    #[allow(clippy::type_complexity)]
    fn pairs() -> Vec<((SpawnPoint, Vec3), (SpawnPoint, Vec3))> {
        let mut rng = TestRng(11);
        let mut pairs = Vec::new();
        for scale in [1e-3, 0.02, 1.0, 40.0, 3e4] {
            for _ in 0..100 {
                let (p, q) = (scale * rng.vec(), scale * rng.vec());
                let (n, m) = (rng.vec().normalize(), rng.vec().normalize());
                pairs.push((point(p, n), point(q, m)));
                pairs.push((point(p, n), point(p, -n)));
                let next = Vec3::new(f32::from_bits(p.x.to_bits() + 3), p.y, p.z);
                pairs.push((point(p, n), point(next, m)));
            }
        }
        let (p, n) = (Vec3::new(2.0, 1.0, -3.0), Vec3::Z);
        pairs.push((point(p, n), point(p + Vec3::X, n)));
        pairs
    }

    #[test]
    fn each_lane_is_the_scalar_shadow_ray() {
        let pairs = pairs();
        let mut degenerate = 0;
        for group in pairs.chunks(4) {
            let (mut from, mut to) = (SpawnPointx4::default(), SpawnPointx4::default());
            let mut to_target = Vec3x4::default();
            for (lane, ((a, _), (b, _))) in group.iter().enumerate() {
                from.set_lane(lane, a);
                to.set_lane(lane, b);
                to_target.set_lane(lane, b.p - a.p);
            }
            let origin = from.origins_towards(from.ng.dot(&to_target));
            let end = to.origins_towards(-to.ng.dot(&to_target));
            let (rays, t_max) = Rayx4::between(&origin, &end, &to_target, &from.ng);
            let lanes = rays.lanes(t_max);
            for (lane, ((a, _), (b, b_error))) in group.iter().enumerate() {
                let (expected, expected_t_max) = a.spawn_to(b.p, b.ng, *b_error);
                let what = format!("lane {lane}: {a:?} to {b:?}");
                assert_eq!(t_max.to_array()[lane], expected_t_max, "{what}");
                let (wide_origin, wide_dir, wide_t_max) = lanes[lane];
                assert_eq!(Vec3::from(wide_origin), expected.origin, "wide {what}");
                assert_eq!(Vec3::from(wide_dir), expected.dir, "wide {what}");
                assert_eq!(
                    wide_t_max.to_bits(),
                    expected_t_max.to_bits(),
                    "wide {what}"
                );
                degenerate += usize::from(expected_t_max == 0.0);
            }
        }
        assert!(
            degenerate > 0,
            "no pair whose offset points coincide or pass"
        );
    }
}
