//! The connections of a path reuse block computed four paths at a time: its first vertices laid
//! out lane by lane (structure of arrays), and their densities and shadow rays towards one second
//! vertex, as [`super::combine`] needs them.

use super::{MAX_BLOCK_PATHS, ReusablePath, SecondVertex};
use geometry::Ray;
use glam::{BVec4A, Vec3, Vec4};
use std::f32::consts::FRAC_1_PI;

/// Four 3-vectors, coordinate by coordinate (structure of arrays).
#[derive(Clone, Copy, Debug, Default)]
struct Vec3x4 {
    x: Vec4,
    y: Vec4,
    z: Vec4,
}

impl Vec3x4 {
    /// `v` in all four lanes.
    #[inline]
    fn splat(v: Vec3) -> Self {
        Self {
            x: Vec4::splat(v.x),
            y: Vec4::splat(v.y),
            z: Vec4::splat(v.z),
        }
    }

    /// Vector `lane`.
    #[inline]
    fn lane(&self, lane: usize) -> Vec3 {
        // Through arrays: indexing a vector by a variable lane compiles to a jump table.
        Vec3::new(
            self.x.to_array()[lane],
            self.y.to_array()[lane],
            self.z.to_array()[lane],
        )
    }

    /// Sets vector `lane` to `v`.
    #[inline]
    fn set_lane(&mut self, lane: usize, v: Vec3) {
        (self.x[lane], self.y[lane], self.z[lane]) = (v.x, v.y, v.z);
    }

    /// Dot products, summed x, y, z in that order (as [`Vec3::dot`] sums them).
    #[inline]
    fn dot(&self, other: &Self) -> Vec4 {
        self.x * other.x + self.y * other.y + self.z * other.z
    }

    /// Differences, lane by lane.
    #[inline]
    fn minus(&self, other: &Self) -> Self {
        Self {
            x: self.x - other.x,
            y: self.y - other.y,
            z: self.z - other.z,
        }
    }

    /// Each lane's vector divided by that lane of `by`.
    #[inline]
    fn divided_by(&self, by: Vec4) -> Self {
        Self {
            x: self.x / by,
            y: self.y / by,
            z: self.z / by,
        }
    }

    /// `if_true`'s vectors where `mask` is set, `if_false`'s elsewhere.
    #[inline]
    fn select(mask: BVec4A, if_true: &Self, if_false: &Self) -> Self {
        Self {
            x: Vec4::select(mask, if_true.x, if_false.x),
            y: Vec4::select(mask, if_true.y, if_false.y),
            z: Vec4::select(mask, if_true.z, if_false.z),
        }
    }
}

/// Groups of four lanes in a block of [`MAX_BLOCK_PATHS`] paths.
const GROUPS: usize = MAX_BLOCK_PATHS / 4;

/// The first vertices of a block laid out lane by lane (structure of arrays), so that the
/// connections from all of them towards one second vertex are computed four at a time. A lane
/// without a first vertex, or whose first vertex faces away from the camera, has `inv_pi` zero,
/// hence density zero everywhere.
pub(super) struct FirstVertexLanes {
    /// Positions (world units).
    p: [Vec3x4; GROUPS],
    /// Unit shading normals (the BSDF's +z).
    n: [Vec3x4; GROUPS],
    /// Unit geometric normals.
    ng: [Vec3x4; GROUPS],
    /// The positions moved off their surfaces to the side of `ng` and to the other
    /// ([`geometry::SpawnPoint`]).
    front: [Vec3x4; GROUPS],
    back: [Vec3x4; GROUPS],
    /// 1/π where the lane's cosine-sampling density counts, else 0 (sr⁻¹).
    inv_pi: [Vec4; GROUPS],
    /// The RGB albedos (zero in lanes without a first vertex).
    pub(super) albedo: [Vec3; MAX_BLOCK_PATHS],
}

/// The connections of four of a block's first vertices to one second vertex y, lane by lane.
#[derive(Clone, Copy, Debug, Default)]
struct ConnectionLanes {
    /// The density per unit area with which each lane's cosine sampling reaches y if nothing is
    /// in between; zero where the lane does not count (see [`FirstVertexLanes::towards`]).
    pdf_area: Vec4,
    /// The lanes whose density is not zero, as a bit mask.
    counted: u32,
    /// The shadow ray from each lane's first vertex to y, as [`Ray::between`] makes it from the
    /// two ends moved off their surfaces: origin, unit direction and `t_max`.
    origin: Vec3x4,
    dir: Vec3x4,
    t_max: Vec4,
}

/// The connections of all of a block's first vertices to one second vertex y.
pub(super) struct Connections([ConnectionLanes; GROUPS]);

impl Connections {
    /// The lanes whose density is not zero, as a bit mask.
    #[inline]
    pub(super) fn counted(&self) -> u32 {
        let mut mask = 0;
        for (group, lanes) in self.0.iter().enumerate() {
            mask |= lanes.counted << (4 * group);
        }
        mask
    }

    /// The density per unit area of `lane` (see [`ConnectionLanes::pdf_area`]).
    #[inline]
    pub(super) fn pdf_area(&self, lane: usize) -> f32 {
        self.0[lane / 4].pdf_area.to_array()[lane % 4]
    }

    /// The shadow ray of `lane` and its `t_max`.
    #[inline]
    pub(super) fn ray(&self, lane: usize) -> (Ray, f32) {
        let lanes = &self.0[lane / 4];
        let ray = Ray {
            origin: lanes.origin.lane(lane % 4),
            dir: lanes.dir.lane(lane % 4),
        };
        (ray, lanes.t_max.to_array()[lane % 4])
    }

    /// Counts `lane` out: its first vertex does not see y.
    #[inline]
    pub(super) fn occlude(&mut self, lane: usize) {
        let pdf_area = &mut self.0[lane / 4].pdf_area;
        let mut lanes = pdf_area.to_array();
        lanes[lane % 4] = 0.0;
        *pdf_area = Vec4::from_array(lanes);
    }

    /// The sum of the densities, lane by lane in order.
    #[inline]
    pub(super) fn total_pdf_area(&self) -> f32 {
        let mut total = 0.0;
        for lanes in &self.0 {
            for pdf in lanes.pdf_area.to_array() {
                total += pdf;
            }
        }
        total
    }
}

impl FirstVertexLanes {
    /// The first vertices of `paths` (at most [`MAX_BLOCK_PATHS`]), path k in lane k.
    #[inline]
    pub(super) fn of(paths: &[ReusablePath]) -> Self {
        let mut lanes = Self {
            p: [Vec3x4::default(); GROUPS],
            n: [Vec3x4::default(); GROUPS],
            ng: [Vec3x4::default(); GROUPS],
            front: [Vec3x4::default(); GROUPS],
            back: [Vec3x4::default(); GROUPS],
            inv_pi: [Vec4::ZERO; GROUPS],
            albedo: [Vec3::ZERO; MAX_BLOCK_PATHS],
        };
        for (k, first) in paths.iter().enumerate() {
            let Some(x) = &first.first else {
                continue;
            };
            let (group, lane) = (k / 4, k % 4);
            lanes.p[group].set_lane(lane, x.point.p);
            lanes.n[group].set_lane(lane, x.frame.n);
            lanes.ng[group].set_lane(lane, x.point.ng);
            lanes.front[group].set_lane(lane, x.point.front);
            lanes.back[group].set_lane(lane, x.point.back);
            // The diffuse lobe reflects nothing towards a camera behind it.
            lanes.inv_pi[group][lane] = if x.wo.z > 0.0 { FRAC_1_PI } else { 0.0 };
            lanes.albedo[k] = x.diffuse.reflectance();
        }
        lanes
    }

    /// For every lane, the density per unit area with which its cosine sampling reaches `y` if
    /// nothing is in between, where its first vertex lies on the sides of `y` given by `side`
    /// ([`SecondVertex::side_of`]), zero elsewhere and where the density is not positive and
    /// finite; and the shadow ray to `y`.
    #[inline]
    pub(super) fn towards(&self, y: &SecondVertex, side: (bool, bool)) -> Connections {
        // Seen from y the first vertex lies along −d: on the front of a normal n where n·d < 0.
        let (front_ng, front_ns) = (BVec4A::splat(side.0), BVec4A::splat(side.1));
        let (y_p, y_ng, y_ns) = (
            Vec3x4::splat(y.point.p),
            Vec3x4::splat(y.point.ng),
            Vec3x4::splat(y.ns),
        );
        let (y_front, y_back) = (Vec3x4::splat(y.point.front), Vec3x4::splat(y.point.back));
        let mut connections = Connections([ConnectionLanes::default(); GROUPS]);
        for (group, out) in connections.0.iter_mut().enumerate() {
            let d = y_p.minus(&self.p[group]);
            let distance_squared = d.dot(&d);
            let distance = distance_squared.sqrt();
            let cos_x = d.dot(&self.n[group]) / distance;
            let (ng_dot, ns_dot) = (d.dot(&y_ng), d.dot(&y_ns));
            let cos_y = ng_dot.abs() / distance;
            let pdf = cos_x * self.inv_pi[group] * cos_y / distance_squared;
            let same_side =
                !(ng_dot.cmplt(Vec4::ZERO) ^ front_ng) & !(ns_dot.cmplt(Vec4::ZERO) ^ front_ns);
            let counts = same_side & pdf.cmpgt(Vec4::ZERO) & pdf.cmplt(Vec4::INFINITY);

            // The ends moved off their surfaces as `offset_ray_origin` moves them, and the ray
            // between them as `Ray::between` makes it.
            let ng = &self.ng[group];
            let leaves_back = d.dot(ng).cmplt(Vec4::ZERO);
            let origin = Vec3x4::select(leaves_back, &self.back[group], &self.front[group]);
            let end = Vec3x4::select(ng_dot.cmpgt(Vec4::ZERO), &y_back, &y_front);
            let segment = end.minus(&origin);
            let length = segment.dot(&segment).sqrt();
            let forward = length.cmpgt(Vec4::ZERO)
                & length.cmplt(Vec4::INFINITY)
                & segment.dot(&d).cmpgt(Vec4::ZERO);
            *out = ConnectionLanes {
                pdf_area: Vec4::select(counts, pdf, Vec4::ZERO),
                counted: counts.bitmask(),
                origin,
                dir: Vec3x4::select(forward, &segment.divided_by(length), ng),
                t_max: Vec4::select(forward, length, Vec4::ZERO),
            };
        }
        connections
    }
}

/// The lanes set in `mask`, lowest first.
pub(super) fn lanes_of(mut mask: u32) -> impl Iterator<Item = usize> {
    std::iter::from_fn(move || {
        (mask != 0).then(|| {
            let lane = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            lane
        })
    })
}
