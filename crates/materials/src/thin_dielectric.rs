//! Mitsuba's `thindielectric`: a thin pane of glass seen as one surface, which reflects like a
//! smooth dielectric with all its internal reflections summed and lets the rest through without
//! bending it.

use crate::bsdf::{BsdfSample, Model};
use crate::error::{MaterialError, relative_ior};
use crate::flags::BsdfFlags;
use crate::fresnel::{fresnel_dielectric, reflect};
use glam::{Vec2, Vec3};

/// A thin slab of a dielectric with relative index η = int_ior / ext_ior (a window pane, a soap
/// film), the same from both sides.
///
/// Light meets two parallel interfaces and bounces between them; summing the series
/// R + T²R + T²R³ + … with T = 1 − R gives the slab's reflectance R' = 2R / (1 + R), where R is
/// the single interface's Fresnel reflectance at the incident angle, and the rest, 1 − R',
/// leaves the far side in the incident direction (the two refractions cancel; absorption
/// inside is not modelled). Both lobes are deltas.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThinDielectric {
    eta: f32,
    specular_reflectance: Vec3,
    specular_transmittance: Vec3,
}

impl ThinDielectric {
    /// A thin slab with interior index `int_ior` and exterior index `ext_ior` (both finite and
    /// positive, else an error; equal indices make it fully transparent), with RGB multipliers on
    /// the reflected and transmitted light (Mitsuba's `specular_reflectance` and
    /// `specular_transmittance`, default 1).
    pub fn new(
        int_ior: f32,
        ext_ior: f32,
        specular_reflectance: Vec3,
        specular_transmittance: Vec3,
    ) -> Result<Self, MaterialError> {
        Ok(Self {
            eta: relative_ior(int_ior, ext_ior)?,
            specular_reflectance,
            specular_transmittance,
        })
    }

    /// The slab's reflectance R' = 2R / (1 + R) for light arriving at `cos_theta` (either sign),
    /// with R the Fresnel reflectance of one of its interfaces.
    pub fn reflectance(&self, cos_theta: f32) -> f32 {
        let r = fresnel_dielectric(cos_theta.abs(), self.eta).reflectance;
        2.0 * r / (1.0 + r)
    }

    /// Reflectance and transmittance multipliers at normal incidence, RGB:
    /// R'₀ · `specular_reflectance` + (1 − R'₀) · `specular_transmittance`.
    pub fn normal_albedo(&self) -> Vec3 {
        let r = self.reflectance(1.0);
        r * self.specular_reflectance + (1.0 - r) * self.specular_transmittance
    }

    /// Chooses reflection with probability R' (when `u_lobe < R'`) and transmission straight
    /// through otherwise, for `wo` on either side. `None` for `wo` in the tangent plane.
    ///
    /// `pdf_solid_angle` is the lobe's probability and `f` is chosen so that the weight
    /// `f · |cos θi| / pdf` is Mitsuba's: `specular_reflectance` for reflection and
    /// `specular_transmittance` for transmission (no radiance scale: the ray leaves into the
    /// medium it came from). The ray crosses no index (`eta` 1 either way).
    pub fn sample(&self, wo: Vec3, u_lobe: f32) -> Option<BsdfSample> {
        let r = self.reflectance(wo.z);
        let is_null = u_lobe >= r;
        let (wi, pdf, weight) = if is_null {
            (-wo, 1.0 - r, self.specular_transmittance)
        } else {
            (reflect(wo), r, self.specular_reflectance)
        };
        let cos_i = wi.z.abs();
        (pdf > 0.0 && cos_i > 0.0).then(|| BsdfSample {
            f: weight * (pdf / cos_i),
            wi,
            pdf_solid_angle: pdf,
            is_delta: true,
            eta: 1.0,
            is_null,
        })
    }
}

impl Model for ThinDielectric {
    #[inline]
    fn flags(&self) -> BsdfFlags {
        BsdfFlags::DELTA | BsdfFlags::NULL | BsdfFlags::TRANSMISSION | BsdfFlags::LOBE_CHOICE
    }

    #[inline]
    fn sample(&self, wo: Vec3, u_lobe: f32, _u_dir: Vec2) -> Option<BsdfSample> {
        ThinDielectric::sample(self, wo, u_lobe)
    }

    fn sample_delta(&self, wo: Vec3, u_lobe: f32) -> Option<BsdfSample> {
        ThinDielectric::sample(self, wo, u_lobe)
    }

    fn albedo_hint(&self) -> Vec3 {
        self.normal_albedo()
    }
}
