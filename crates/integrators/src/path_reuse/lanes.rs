//! The connections of a path reuse block computed four paths at a time: its first vertices laid
//! out lane by lane (structure of arrays), their densities and shadow rays towards one second
//! vertex, and the block's estimates that the shares of each second vertex are added to, as
//! [`super::combine`] needs them.

use super::{MAX_BLOCK_PATHS, ReusablePath, SecondVertex};
use geometry::{Rayx4, SpawnPointx4, Vec3x4};
use glam::{BVec4A, Vec3, Vec4};
use std::f32::consts::FRAC_1_PI;

/// Groups of four lanes in a block of [`MAX_BLOCK_PATHS`] paths.
pub(super) const GROUPS: usize = MAX_BLOCK_PATHS / 4;

/// The first vertices of a block laid out lane by lane (structure of arrays), so that the
/// connections from all of them towards one second vertex are computed four at a time. A lane
/// without a first vertex, or whose first vertex faces away from the camera, has `inv_pi` zero,
/// hence density zero everywhere.
pub(super) struct FirstVertexLanes {
    /// Positions, geometric normals, and the positions moved off their surfaces to either side.
    points: [SpawnPointx4; GROUPS],
    /// Unit shading normals (the BSDF's +z).
    n: [Vec3x4; GROUPS],
    /// 1/π where the lane's cosine-sampling density counts, else 0 (sr⁻¹).
    inv_pi: [Vec4; GROUPS],
    /// The RGB albedos (zero in lanes without a first vertex).
    albedo: [Vec3x4; GROUPS],
    /// How many groups of four lanes hold paths.
    groups: usize,
}

/// The connections of one group of four of a block's first vertices to one second vertex y,
/// lane by lane.
pub(super) struct ConnectionLanes {
    /// The density per unit area with which each lane's cosine sampling reaches y if nothing is
    /// in between; zero where the lane does not count (see [`FirstVertexLanes::towards`]).
    pub(super) pdf_area: Vec4,
    /// The lanes whose density is not zero, as a bit mask.
    pub(super) counted: u32,
    /// The shadow ray from each lane's first vertex to y, as [`geometry::Ray::between`] makes
    /// it from the two ends moved off their surfaces, and its `t_max`.
    pub(super) rays: Rayx4,
    pub(super) t_max: Vec4,
}

impl FirstVertexLanes {
    /// The first vertices of `paths` (at most [`MAX_BLOCK_PATHS`]), path k in lane k.
    #[inline]
    pub(super) fn of(paths: &[ReusablePath]) -> Self {
        let mut lanes = Self {
            points: [SpawnPointx4::default(); GROUPS],
            n: [Vec3x4::default(); GROUPS],
            inv_pi: [Vec4::ZERO; GROUPS],
            albedo: [Vec3x4::default(); GROUPS],
            groups: paths.len().div_ceil(4),
        };
        for (k, first) in paths.iter().enumerate() {
            let Some(x) = &first.first else {
                continue;
            };
            let (group, lane) = (k / 4, k % 4);
            lanes.points[group].set_lane(lane, &x.point);
            lanes.n[group].set_lane(lane, x.n);
            // The diffuse lobe reflects nothing towards a camera behind it.
            lanes.inv_pi[group][lane] = if x.faces_camera { FRAC_1_PI } else { 0.0 };
            lanes.albedo[group].set_lane(lane, x.albedo);
        }
        lanes
    }

    /// How many groups of four lanes hold paths (the lanes of path k are in group k / 4).
    #[inline]
    pub(super) fn groups(&self) -> usize {
        self.groups
    }

    /// For every lane of `group`, the density per unit area with which its cosine sampling
    /// reaches `y` if nothing is in between, where its first vertex lies on the sides of `y`
    /// given by `side` ([`SecondVertex::side_of`]), zero elsewhere and where the density is not
    /// positive and finite; and the shadow ray to `y`.
    #[inline]
    pub(super) fn towards(
        &self,
        group: usize,
        y: &SecondVertex,
        side: (bool, bool),
    ) -> ConnectionLanes {
        // Seen from y the first vertex lies along −d: on the front of a normal n where n·d < 0.
        let (front_ng, front_ns) = (BVec4A::splat(side.0), BVec4A::splat(side.1));
        let (y_point, y_ns) = (SpawnPointx4::splat(&y.point), Vec3x4::splat(y.ns));
        let x_point = &self.points[group];
        let d = y_point.p.minus(&x_point.p);
        let distance_squared = d.dot(&d);
        let distance = distance_squared.sqrt();
        let cos_x = d.dot(&self.n[group]) / distance;
        let (ng_dot, ns_dot) = (d.dot(&y_point.ng), d.dot(&y_ns));
        let cos_y = ng_dot.abs() / distance;
        let pdf = cos_x * self.inv_pi[group] * cos_y / distance_squared;
        let same_side =
            !(ng_dot.cmplt(Vec4::ZERO) ^ front_ng) & !(ns_dot.cmplt(Vec4::ZERO) ^ front_ns);
        let counts = same_side & pdf.cmpgt(Vec4::ZERO) & pdf.cmplt(Vec4::INFINITY);

        // The shadow ray as `SpawnPoint::spawn_to` makes it: from x's origin towards y to y's
        // origin towards x (y's `ng · -d` is `-ng_dot`, exactly).
        let origin = x_point.origins_towards(d.dot(&x_point.ng));
        let end = y_point.origins_towards(-ng_dot);
        let (rays, t_max) = Rayx4::between(&origin, &end, &d, &x_point.ng);
        ConnectionLanes {
            pdf_area: Vec4::select(counts, pdf, Vec4::ZERO),
            counted: counts.bitmask(),
            rays,
            t_max,
        }
    }
}

/// A block's radiance estimates (W m⁻² sr⁻¹, RGB) lane by lane, path k in lane k, while
/// [`super::combine`] adds the shared second vertices to them.
pub(super) struct RadianceLanes([Vec3x4; GROUPS]);

impl RadianceLanes {
    /// The estimates `own`, path k in lane k.
    #[inline]
    pub(super) fn of(own: impl Iterator<Item = Vec3>) -> Self {
        let mut lanes = [Vec3x4::default(); GROUPS];
        for (k, radiance) in own.enumerate() {
            lanes[k / 4].set_lane(k % 4, radiance);
        }
        Self(lanes)
    }

    /// Adds to each lane of `group` whose `pdf_area` is positive (a first vertex that sees the
    /// second vertex) its share of the radiance `share` (the second vertex's reflected radiance
    /// over the sum of the densities): albedo · pdf_area · share, f G / Σ p_k · L for a
    /// Lambertian first vertex, in each lane as `albedo * pdf_area * share` computes it.
    #[inline]
    pub(super) fn add_shares(
        &mut self,
        firsts: &FirstVertexLanes,
        group: usize,
        pdf_area: Vec4,
        share: Vec3,
    ) {
        let seen = pdf_area.cmpgt(Vec4::ZERO);
        let (sums, albedo) = (&mut self.0[group], &firsts.albedo[group]);
        sums.x = Vec4::select(seen, sums.x + albedo.x * pdf_area * share.x, sums.x);
        sums.y = Vec4::select(seen, sums.y + albedo.y * pdf_area * share.y, sums.y);
        sums.z = Vec4::select(seen, sums.z + albedo.z * pdf_area * share.z, sums.z);
    }

    /// Writes the estimates to `radiance`, path k's to `radiance[k]`.
    #[inline]
    pub(super) fn write_to(&self, radiance: &mut [Vec3]) {
        for (group, out) in self.0.iter().zip(radiance.chunks_mut(4)) {
            let (x, y, z) = (group.x.to_array(), group.y.to_array(), group.z.to_array());
            for (lane, value) in out.iter_mut().enumerate() {
                *value = Vec3::new(x[lane], y[lane], z[lane]);
            }
        }
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
