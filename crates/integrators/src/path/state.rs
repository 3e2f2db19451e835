//! What the path walk carries from vertex to vertex ([`PathState`]), and how a bounce and path
//! reuse's split change it.

use super::mis::PreviousVertex;
use crate::next_direction::NextDirection;
use glam::Vec3;

/// What the walk carries from vertex to vertex.
#[derive(Clone, Copy, Debug)]
pub(super) struct PathState {
    /// The estimate so far (W m⁻² sr⁻¹, RGB).
    pub radiance: Vec3,
    /// Product of f · |cos θ| / pdf over the bounces so far (RGB; from the second vertex on
    /// with path reuse's split).
    pub throughput: Vec3,
    /// Path reuse's throughput to the second vertex, once the walk has split there, else 1:
    /// roulette weighs the whole path's throughput.
    pub prefix: Vec3,
    /// Product of η² over the refractions so far: refraction scales radiance by 1/η², which
    /// roulette must not mistake for absorption (pbrt-v4's `etaScale`, Mitsuba's `eta`).
    pub eta_scale: f32,
    /// The vertex the ray leaves, for the MIS weight of emission it finds.
    pub previous: PreviousVertex,
    /// Whether every bounce so far was by a delta lobe: what the path finds next, neither light
    /// sampling nor the light tracer can reach.
    pub seen_through_delta: bool,
    /// Whether the first vertex was left by a non-delta lobe.
    pub first_vertex_non_delta: bool,
    /// Whether the path's first vertex was left by a non-delta lobe and its last by a delta
    /// one: emission it meets next is the light tracer's with `light_tracing` on, or, when
    /// every bounce after the first was by a delta lobe (`through_deltas`), shared with it by
    /// `caustic_mis`'s weights.
    pub caustic_chain: bool,
    /// Whether every bounce after the first was by a delta lobe.
    pub through_deltas: bool,
    /// The path tracer's side of `caustic_mis`'s density ratio: at the first vertex the
    /// camera's importance times |cos θ| towards the camera, from the first bounce on times
    /// that bounce's pdf / |cos θ| (0 where light tracing does not share caustics).
    pub camera_side: f32,
    /// The direction (local frame) of the delta lobe the bounce at the current vertex chose,
    /// `None` before it or after a non-delta one: what [delta splitting](super::delta_splitting)
    /// does not trace again.
    pub chosen_delta: Option<Vec3>,
    /// The share of the emission met at the next vertex that the walk counts: the chosen delta
    /// lobe's probability where delta splitting counted the others' emission, else 1.
    pub emission_scale: f32,
    /// The number of the vertex the ray is about to find: one more per bounce, not per pass
    /// through a null lobe with `skip_null_vertices`.
    pub depth: u32,
}

impl PathState {
    /// A path leaving the camera at `origin`.
    #[inline(always)]
    pub fn at_camera(origin: Vec3) -> Self {
        Self {
            radiance: Vec3::ZERO,
            throughput: Vec3::ONE,
            prefix: Vec3::ONE,
            eta_scale: 1.0,
            previous: PreviousVertex {
                p: origin,
                pdf_dir: 0.0,
                delta: true,
            },
            seen_through_delta: true,
            first_vertex_non_delta: false,
            caustic_chain: false,
            through_deltas: true,
            camera_side: 0.0,
            chosen_delta: None,
            emission_scale: 1.0,
            depth: 1,
        }
    }

    /// The path continues from the vertex at `p` in the direction `next`.
    #[inline(always)]
    pub fn bounce(&mut self, next: &NextDirection, p: Vec3) {
        self.throughput *= next.weight;
        self.eta_scale *= next.eta * next.eta;
        self.seen_through_delta &= next.is_delta;
        self.chosen_delta = next.is_delta.then_some(next.wi);
        self.emission_scale = 1.0;
        if self.depth == 1 {
            self.first_vertex_non_delta = !next.is_delta;
            self.camera_side *= next.pdf_solid_angle / next.wi.z.abs();
        } else {
            self.caustic_chain = self.first_vertex_non_delta && next.is_delta;
            self.through_deltas &= next.is_delta;
        }
        self.previous = PreviousVertex {
            p,
            pdf_dir: next.pdf_solid_angle,
            delta: next.is_delta,
        };
    }

    /// Path reuse's split at the second vertex: the estimate so far is kept apart (by
    /// [`crate::path_reuse::WalkSplit`]), and the estimate and throughput start afresh from
    /// here, the throughput so far kept as `prefix`.
    #[inline(always)]
    pub fn restart_at_second_vertex(&mut self) {
        self.radiance = Vec3::ZERO;
        self.prefix = self.throughput;
        self.throughput = Vec3::ONE;
    }
}
