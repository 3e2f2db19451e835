//! Caustics by light tracing: paths traced from the area lights, first through a mirror or glass,
//! and connected to the camera (through a point of its aperture, for a thin lens) from every
//! non-delta surface they reach.
//!
//! **What it is.** A path tracer finds light that reaches a diffuse surface through a specular chain (light →
//! glass → floor → camera) only when a BSDF-sampled direction happens to run through the chain
//! into a light, which for a small light is rare and bright: such caustics, and the light they
//! throw on to other surfaces, dominate the noise of scenes with glass. Traced from the light,
//! the same paths are found by following the emitted light and joining each non-delta vertex to
//! the camera with one shadow ray (pbrt-v4's `LightPathIntegrator`, restricted to these paths).
//! With [`crate::PathSettings::light_tracing`] on, the two share these paths (a first vertex
//! after the camera left by a non-delta lobe, emission met by a delta bounce, k ≥ 3 vertices),
//! which this tracer contributes (its light leaves the light's first hit by a delta lobe and
//! reaches the camera from a non-delta vertex): one bounce from the camera (camera → x₁ → delta
//! chain → light) each path is weighted between the two by MIS (`caustic_mis`), so that a
//! glossy x₁ stays mostly the path tracer's; longer paths are split, not weighted: the path
//! tracer drops them. Either way the sum is unbiased.
//!
//! **The formula** (the technique goes beyond the lecture). A light path carries
//! β = Le · |cos θ_light| / (P(light) · p_A · p_ω) · Π f · |cos θ| / pdf over its bounces; a
//! non-delta vertex x adds, to the pixel its film position falls in,
//!
//! ```text
//! β · f(x → camera) · |cos θ_x| · W_e · |cos θ_camera| / r² · V(x, camera)
//! ```
//!
//! **When `auto` uses it.** In its base wherever it applies (a delta BSDF, an area light,
//! `max_depth` ≥ 3, a camera that light paths can reach, emitters not hidden); switching it off
//! is one of `auto`'s trials, kept only when the pilot measures it more efficient.
//!
//! One camera sample in [`crate::LightTracing::samples_per_path`] also traces a light path
//! ([`LightTracer::path_of_sample`]): with `L` paths for an `N`-pixel image, a pixel's value
//! gains `N / L` times the sum of the paths' contributions to it (see `render::film`), and the
//! caustics both strategies find are weighted for that rate (`caustic_mis`).
//!
//! Sampler dimensions, in order, only those the scene needs (as the path tracer's): time (1D,
//! when something moves: the whole light path, and its connections to the camera, see the
//! scene at that time), light choice (1D, with more than one area light), point on the light (2D), emitted direction (2D), then per
//! vertex the aperture point of the camera connection (2D, from the second vertex on, with a
//! thin-lens camera), the BSDF lobe (1D, when some material chooses a lobe) and direction (2D),
//! and roulette (1D, with roulette from its start depth on).

use crate::caster_cones::CasterCones;
use crate::caustic_mis::{LightPathStarts, camera_side, density_ratio};
use crate::optional_draw::next_1d_if;
use crate::{PathSettings, RussianRoulette};
use geometry::Ray;
use glam::{UVec2, Vec2, Vec3};
use materials::BsdfFlags;
use sampling::Sampler;
use world::{BsdfSlot, CameraConnection, CameraTraits, RayTally, SurfaceHit, World};

/// One contribution of a light path to the camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraSplat {
    /// Where the path reaches the film, pixels.
    pub film: Vec2,
    /// The contribution, MIS-weighted, in units of one pixel sample's radiance
    /// (W m⁻² sr⁻¹, RGB).
    pub value: Vec3,
    /// The contribution before its MIS weight (same units).
    pub unweighted: Vec3,
    /// For a caustic one bounce from the camera, which the path tracer samples too, the ratio
    /// r of the light tracer's density of the path to the path tracer's (`caustic_mis`): the
    /// path tracer's own sample of the path is worth `unweighted · r`. Zero for other
    /// connections.
    pub path_tracer_ratio: f32,
}

/// Traces light paths for caustics (see the module documentation).
#[derive(Clone, Debug)]
pub struct LightTracer {
    /// The choice of the area light each path starts on.
    starts: LightPathStarts,
    /// Longest path, in vertices after the camera (Mitsuba's `max_depth`).
    max_depth: u32,
    /// Roulette on the light paths' bounces, as the path tracer's.
    russian_roulette: Option<RussianRoulette>,
    /// Whether caustics one bounce from the camera are weighted against the path tracer's
    /// BSDF samples (`caustic_mis`): with BSDF sampling on.
    weighs_caustics: bool,
    /// Whether some material draws a number to choose its lobe.
    draws_lobe_choice: bool,
    /// Whether the camera has an aperture, so each camera connection draws a point on it.
    draws_lens: bool,
    /// Whether something moves, so each light path draws a time.
    draws_time: bool,
    /// Camera samples per light path ([`crate::LightTracing::samples_per_path`]).
    samples_per_path: u32,
}

impl LightTracer {
    /// The tracer for `world` with the path tracer's `settings` (depth, roulette, BSDF
    /// sampling), for a camera with an aperture or a pinhole, moving or not (`camera`); `None`
    /// when the world has no area light with power, or when `settings` hide emitters: the
    /// camera then sees through area emitters, which its connections from light paths do not
    /// (the path tracer keeps those paths). Also `None` when `settings` skip null vertices in a
    /// world with null lobes (the tracer counts every pass through one as a vertex), and when
    /// `settings` have light tracing off.
    pub fn new(world: &World, settings: &PathSettings, camera: CameraTraits) -> Option<Self> {
        if settings.hide_emitters || (settings.skip_null_vertices && world.has_null_lobes()) {
            return None;
        }
        Some(Self {
            starts: LightPathStarts::new(world, settings.light_tracing?.paths_per_sample())?,
            max_depth: settings
                .max_depth
                .unwrap_or(crate::reference::UNBOUNDED_DEPTH_CAP),
            russian_roulette: settings.russian_roulette,
            weighs_caustics: settings.sample_bsdf,
            draws_lobe_choice: world.has_lobe_choice(),
            draws_lens: camera.has_lens,
            draws_time: world.has_motion() || camera.moves,
            samples_per_path: settings.light_tracing?.samples_per_path.max(1),
        })
    }

    /// Whether the camera sample `sample_index` of `pixel` also traces a light path, and if so
    /// that path's index among the pixel's light paths (0, 1, 2, …: the sample index its
    /// sampler starts with). One sample in [`crate::LightTracing::samples_per_path`] does: those
    /// whose index has the pixel's phase, (x + 2y) mod that count, so that at any sample index
    /// the pixels that trace one are spread over the image (one in every 2 × 2 block at 4).
    #[inline]
    pub fn path_of_sample(&self, pixel: UVec2, sample_index: u32) -> Option<u32> {
        let period = self.samples_per_path;
        let phase = pixel.x.wrapping_add(pixel.y.wrapping_mul(2)) % period;
        (sample_index % period == phase).then_some(sample_index / period)
    }

    /// Traces one light path with `sampler` (already started on its pixel sample) and hands each
    /// contribution to the camera to `splat`.
    pub fn trace(
        &self,
        world: &World,
        sampler: &mut impl Sampler,
        connect: &impl Fn(Vec3, Vec2, f32) -> Option<CameraConnection>,
        tally: &mut impl RayTally,
        splat: &mut impl FnMut(CameraSplat),
    ) {
        let time = if self.draws_time {
            sampler.next_1d()
        } else {
            0.0
        };
        let u_choice = next_1d_if(sampler, self.starts.chooses());
        let u_point = sampler.next_2d();
        let u_dir = sampler.next_2d();
        let (chosen, pmf) = self.starts.sample(u_choice);
        let light = &world.lights()[chosen as usize];
        // The direction: cosine-distributed, or with casters, aimed at one part of the time.
        let (cosine, u_x) = match self.starts.casters() {
            Some(_) => CasterCones::cosine_part(u_dir.x),
            None => (true, u_dir.x),
        };
        let u_dir = Vec2::new(u_x, u_dir.y);
        let Some(mut emitted) = light.sample_emission(u_point, u_dir, time) else {
            return;
        };
        if let (false, Some(casters)) = (cosine, self.starts.casters()) {
            let Some(dir) = casters.sample(emitted.p, u_dir) else {
                return;
            };
            emitted.dir = dir;
        }
        // Lambertian emission's weight is for the cosine distribution; `aim` is the drawn
        // direction's density over it (0 behind the emitter).
        let aim = self.starts.aim(emitted.p, emitted.n, emitted.dir);
        if aim <= 0.0 {
            return;
        }
        // The light the path carries is `emitted_weight * throughput`.
        let emitted_weight = emitted.weight / (pmf * aim);
        let mut throughput = Vec3::ONE;
        // While every bounce so far was by a delta lobe, a connection makes a caustic path one
        // bounce from the camera, weighted against the path tracer's (`caustic_mis`) with the
        // light side of the densities' ratio.
        let light_side = self.weighs_caustics.then(|| {
            self.starts
                .density_aimed(world, chosen, emitted.n, time, aim)
        });
        let mut through_deltas = true;
        let mut ray = Ray::spawn(emitted.p, emitted.n, emitted.p_error, emitted.dir).at_time(time);
        // The vertex about to be found, counted from the light (1 = the first hit). A connection
        // at vertex j makes a path of j + 1 vertices after the camera (j of them, and the light).
        let mut vertex = 1;
        let mut slot = BsdfSlot::default();
        while vertex < self.max_depth {
            let Some(surface) = world.intersect(&ray, tally, &mut slot) else {
                return;
            };
            let towards_light = -ray.dir;
            let wo = surface.frame.to_local(towards_light);
            let u_lens = if vertex > 1 && self.draws_lens {
                sampler.next_2d()
            } else {
                Vec2::ZERO
            };
            if vertex > 1
                && !surface.bsdf.flags().is_delta()
                && let Some(camera) = connect(surface.hit.p, u_lens, time)
            {
                let weight = emitted_weight * throughput;
                let light_side = light_side.filter(|_| through_deltas);
                connect_to_camera(
                    world,
                    &self.starts,
                    &surface,
                    towards_light,
                    camera,
                    light_side,
                    tally,
                    weight,
                    splat,
                );
            }
            if vertex + 1 >= self.max_depth {
                return;
            }
            // Light that leaves the first vertex by a non-delta lobe is the path tracer's, so a
            // surface without delta (or null) lobes ends the path here, before drawing a bounce.
            if vertex == 1
                && !surface
                    .bsdf
                    .flags()
                    .intersects(BsdfFlags::DELTA | BsdfFlags::NULL)
            {
                return;
            }
            let u_lobe = next_1d_if(sampler, self.draws_lobe_choice);
            let u_bounce = sampler.next_2d();
            let Some(bounce) = surface.bsdf.sample(wo, u_lobe, u_bounce) else {
                return;
            };
            // Likewise a non-delta bounce from a surface with both kinds of lobe.
            if vertex == 1 && !bounce.is_delta {
                return;
            }
            let outgoing = surface.frame.to_world(bounce.wi);
            // The sample's weight is for radiance, which refraction scales by 1/η²; the light
            // carried by a path from the light is not (pbrt's importance transport), and shading
            // normals differ from geometric ones in the two directions (Veach's correction).
            let ng = surface.hit.ng;
            let adjoint = (bounce.eta * bounce.eta)
                * shading_normal_correction(wo.z, bounce.wi.z, ng, towards_light, outgoing);
            let factor = bounce.f * (bounce.wi.z.abs() / bounce.pdf_solid_angle * adjoint);
            throughput *= factor;
            through_deltas &= bounce.is_delta;
            if let Some(roulette) = self.russian_roulette
                && vertex >= roulette.start_depth
            {
                let u_survive = sampler.next_1d();
                let survival = throughput.max_element().clamp(0.0, 1.0);
                if u_survive >= survival {
                    return;
                }
                throughput /= survival;
            }
            let weight = emitted_weight * throughput;
            if weight == Vec3::ZERO || !weight.is_finite() {
                return;
            }
            vertex += 1;
            ray = Ray::spawn(surface.hit.p, ng, surface.hit.p_error, outgoing).at_time(time);
        }
    }
}

/// Joins the non-delta vertex `surface`, reached by light arriving from `towards_light`, to the
/// camera and splats the path's contribution (`weight` before this vertex) if nothing blocks it.
/// With `light_side`, the path is a caustic one bounce from the camera that the path tracer
/// samples too, and the contribution takes the light tracer's weight against it
/// (`caustic_mis`, at the light paths per camera sample of `starts`).
#[allow(clippy::too_many_arguments)]
fn connect_to_camera(
    world: &World,
    starts: &LightPathStarts,
    surface: &SurfaceHit<'_>,
    towards_light: Vec3,
    camera: CameraConnection,
    light_side: Option<f32>,
    tally: &mut impl RayTally,
    weight: Vec3,
    splat: &mut impl FnMut(CameraSplat),
) {
    let wo = surface.frame.to_local(towards_light);
    let to_camera = (camera.target - surface.hit.p).normalize_or_zero();
    let wc = surface.frame.to_local(to_camera);
    // Radiance leaves towards the camera; light arrives from the light's side. The path tracer
    // would have sampled the light's side from the camera's.
    let (f, pdf_bsdf) = match light_side {
        Some(_) => surface.bsdf.eval_with_pdf(wc, wo),
        None => (surface.bsdf.eval(wc, wo), 0.0),
    };
    let ng = surface.hit.ng;
    let cos_light_geometric = ng.dot(towards_light).abs();
    let cos_camera = ng.dot(to_camera).abs();
    // The light tracer's MIS weight, and the ratio r of its density to the path tracer's.
    let (mis, ratio) = light_side.map_or((1.0, 0.0), |light_side| {
        let camera_side = camera_side(camera.importance, cos_camera, pdf_bsdf, wo.z.abs());
        (
            starts.light_tracer_weight(light_side, camera_side),
            density_ratio(light_side, camera_side),
        )
    });
    if f == Vec3::ZERO
        || mis == 0.0
        || cos_light_geometric <= 0.0
        || !world.unoccluded(&surface.hit, camera.target, tally)
    {
        return;
    }
    // The path tracer's measurement uses the shading normal's cosine towards the light and the
    // geometric one towards the camera (its ray's hit).
    let cosines = wo.z.abs() * cos_camera / cos_light_geometric;
    let unweighted = weight * f * (cosines * camera.importance);
    splat(CameraSplat {
        film: camera.film,
        value: unweighted * mis,
        unweighted,
        path_tracer_ratio: ratio,
    });
}

/// |n_s · wo| |n_g · wi| / (|n_g · wo| |n_s · wi|) for light arriving from `wo` and leaving along
/// `wi` (world directions; `cos_wo_shading`, `cos_wi_shading` their shading-frame cosines): the
/// factor by which a BSDF sample's radiance weight differs from its weight for light carried
/// from the light (Veach 1997, §5.3); 1 where the shading normal is the geometric one.
fn shading_normal_correction(
    cos_wo_shading: f32,
    cos_wi_shading: f32,
    ng: Vec3,
    wo: Vec3,
    wi: Vec3,
) -> f32 {
    let denominator = ng.dot(wo).abs() * cos_wi_shading.abs();
    if denominator > 0.0 {
        cos_wo_shading.abs() * ng.dot(wi).abs() / denominator
    } else {
        0.0
    }
}
