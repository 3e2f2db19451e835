//! Connecting a shading point to every delta light: the only unbiased way to see point, spot and
//! directional lights without light selection, since no sampled direction can hit them.

use geometry::SpawnPoint;
use glam::{Vec2, Vec3};
use world::{RayTally, SurfaceHit, World};

/// Light from every delta light at `surface` (whose point is `point`), each by its one shadow
/// ray. Without light sampling this is the only way to see a point light: no sampled direction
/// can hit it.
pub(crate) fn delta_lights(
    world: &World,
    surface: &SurfaceHit<'_>,
    point: &SpawnPoint,
    wo: Vec3,
    counters: &mut impl RayTally,
) -> Vec3 {
    let mut sum = Vec3::ZERO;
    for &index in world.delta_lights() {
        let Some(s) =
            world.lights()[index as usize].sample_li(surface.hit.p, Vec2::ZERO, surface.hit.time)
        else {
            continue;
        };
        let wi = surface.frame.to_local(s.wi);
        let f = surface.bsdf.eval(wo, wi);
        if f != Vec3::ZERO && world.light_unoccluded(point, &s, counters) {
            sum += f * wi.z.abs() * s.radiance / s.pdf_solid_angle;
        }
    }
    sum
}
