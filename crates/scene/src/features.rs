//! What a scene contains, so that techniques it cannot use are left out.

use lights::Light;
use materials::{Bsdf, BsdfFlags};

/// The features of a scene that decide which variance-reduction techniques can pay off.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SceneFeatures {
    /// Number of lights (area, point and environment).
    pub light_count: usize,
    /// True when some material has a non-delta lobe (diffuse, rough conductor).
    pub has_non_delta_bsdfs: bool,
    /// Number of area lights (on meshes and spheres): lights with a place that rays can hit.
    pub area_light_count: usize,
    /// True when the scene has an environment emitter.
    pub has_environment: bool,
    /// Lights that light sampling leaves to BSDF samples under MIS
    /// ([`Light::left_to_bsdf_samples`]: a constant environment, or a map with nothing above
    /// its mean).
    pub lights_left_to_bsdf: usize,
    /// True when some material has a glossy lobe ([`BsdfFlags::GLOSSY`]: a rough conductor).
    pub has_glossy_bsdfs: bool,
    /// True when some material has a delta lobe (mirror, smooth dielectric, or a twosided
    /// with one on either side).
    pub has_delta_bsdfs: bool,
    /// True when some material chooses between a delta lobe and another lobe
    /// ([`BsdfFlags::chooses_delta_lobe`]: glass, smooth plastic), where delta splitting applies.
    pub has_delta_lobe_choice: bool,
    /// True when some material has a null lobe ([`BsdfFlags::NULL`]: `null`, a mask, a thin
    /// dielectric), which Mitsuba's volumetric path tracers do not count as a path vertex.
    pub has_null_lobes: bool,
    /// True when some material is Lambertian (`diffuse`, or a `twosided` with one on either
    /// side), which path reuse can connect.
    pub has_diffuse_bsdfs: bool,
    /// True when some shape moves while the shutter is open: each camera sample then draws a
    /// time, and path reuse (which joins paths of different pixels) does not apply.
    pub has_motion: bool,
}

impl SceneFeatures {
    /// True when some light can be hit by a ray (area lights, environment).
    pub fn has_hittable_lights(&self) -> bool {
        self.area_light_count > 0 || self.has_environment
    }

    /// Lights that next event estimation samples where BSDF samples continue the path and MIS
    /// weighs them (`auto`'s base): all but those [left to BSDF
    /// samples](Light::left_to_bsdf_samples).
    pub fn lights_sampled_under_mis(&self) -> usize {
        self.light_count - self.lights_left_to_bsdf
    }

    /// True when some light is a delta light (point lights), which no ray can hit.
    pub fn has_delta_lights(&self) -> bool {
        self.area_light_count + usize::from(self.has_environment) < self.light_count
    }

    /// The features of a scene with `materials` and `lights`, in which something moves while
    /// the shutter is open when `has_motion`.
    pub fn of(materials: &[Bsdf], lights: &[Light], has_motion: bool) -> Self {
        Self {
            light_count: lights.len(),
            has_non_delta_bsdfs: materials.iter().any(|m| !m.flags().is_delta()),
            has_delta_bsdfs: materials
                .iter()
                .any(|m| m.flags().contains(BsdfFlags::DELTA)),
            area_light_count: lights.iter().filter(|l| l.is_area()).count(),
            has_environment: lights.iter().any(Light::is_environment),
            lights_left_to_bsdf: lights.iter().filter(|l| l.left_to_bsdf_samples()).count(),
            has_glossy_bsdfs: materials
                .iter()
                .any(|m| m.flags().contains(BsdfFlags::GLOSSY)),
            has_delta_lobe_choice: materials.iter().any(|m| m.flags().chooses_delta_lobe()),
            has_null_lobes: materials
                .iter()
                .any(|m| m.flags().contains(BsdfFlags::NULL)),
            has_diffuse_bsdfs: materials.iter().any(|m| match m {
                Bsdf::Diffuse(_) => true,
                Bsdf::TwoSided(two_sided) => [two_sided.front(), two_sided.back()]
                    .iter()
                    .any(|side| matches!(side, Bsdf::Diffuse(_))),
                _ => false,
            }),
            has_motion,
        }
    }
}
