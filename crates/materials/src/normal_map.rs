//! Mitsuba's `normalmap`: a nested BSDF whose shading normal an RGB texture gives.

use crate::bitmap::BitmapTexture;
use crate::bsdf::{Bsdf, BsdfSample, Model};
use crate::flags::BsdfFlags;
use crate::perturbed::{AdapterOptions, Perturbed, SurfacePoint};
use glam::{Vec2, Vec3};
use std::sync::Arc;

/// A nested BSDF seen through a shading frame whose normal a texture encodes: at surface
/// coordinates (u, v) the texture's linear RGB value c gives the normal 2c − 1 (normalised) in
/// Mitsuba's shading frame, whose first tangent s is ∂p/∂u made perpendicular to the shading
/// normal and whose second is n × s (not in Strata's own local frame, whose tangents are
/// arbitrary), so (0.5, 0.5, 1) changes nothing; s made perpendicular to the perturbed normal is
/// the perturbed frame's first tangent, as in Mitsuba 3.9. Mitsuba reads the texture as it is
/// stored (a PNG with `raw` set, so that no sRGB curve is undone). How directions pass through
/// the perturbed frame, and when they scatter nothing: see `Perturbed` (the flip, the side test,
/// the cosine and the shadowing term, as Mitsuba 3.9's adapter has them, switched by
/// [`AdapterOptions`]).
///
/// The BSDF as built has no perturbation; [`Bsdf::at_surface`] gives the one for a hit.
#[derive(Clone, Debug, PartialEq)]
pub struct NormalMap {
    perturbed: Perturbed,
    texture: Arc<BitmapTexture>,
}

impl NormalMap {
    /// `nested` under the normal map `texture` (linear RGB, each channel in [0, 1]), with
    /// Mitsuba's `options`.
    pub fn new(nested: Bsdf, texture: Arc<BitmapTexture>, options: AdapterOptions) -> Self {
        Self {
            perturbed: Perturbed::new(nested, options),
            texture,
        }
    }

    /// Mitsuba's switches: the flip of normals facing away from `wo` and the shadowing term.
    pub fn options(&self) -> AdapterOptions {
        self.perturbed.options()
    }

    /// The BSDF under the map.
    pub fn nested(&self) -> &Bsdf {
        &self.perturbed.nested
    }

    /// The perturbed shading normal at `point`, in the local shading frame (unit length unless
    /// the texture gives the zero vector, which perturbs nothing).
    pub fn normal(&self, point: &SurfacePoint) -> Vec3 {
        let c = self.texture.eval(point.uv) * 2.0 - 1.0;
        let s = tangent(point);
        let t = Vec3::new(-s.y, s.x, 0.0);
        (s * c.x + t * c.y + Vec3::new(0.0, 0.0, c.z))
            .try_normalize()
            .unwrap_or(Vec3::Z)
    }
}

/// The first tangent of Mitsuba's shading frame at `point` in the local one: ∂p/∂u made
/// perpendicular to the shading normal +z and normalised, or +x where ∂p/∂u has no tangential
/// part (Mitsuba then takes an arbitrary tangent too).
fn tangent(point: &SurfacePoint) -> Vec3 {
    point
        .dp_du
        .truncate()
        .try_normalize()
        .map_or(Vec3::X, |s| s.extend(0.0))
}

impl Model for NormalMap {
    #[inline]
    fn flags(&self) -> BsdfFlags {
        self.perturbed.flags() | BsdfFlags::AT_SURFACE
    }

    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        self.perturbed.eval(wo, wi)
    }

    fn pdf_solid_angle(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.perturbed.pdf_solid_angle(wo, wi)
    }

    fn eval_with_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        self.perturbed.eval_with_pdf(wo, wi)
    }

    fn lobe_weight(&self, wo: Vec3, wi: Vec3) -> Option<f32> {
        self.perturbed.lobe_weight(wo, wi)
    }

    fn sample(&self, wo: Vec3, u_lobe: f32, u_dir: Vec2) -> Option<BsdfSample> {
        self.perturbed.sample(wo, u_lobe, u_dir)
    }

    fn sample_delta(&self, wo: Vec3, u_lobe: f32) -> Option<BsdfSample> {
        self.perturbed.sample_delta(wo, u_lobe)
    }

    fn at_surface(&self, point: &SurfacePoint) -> Option<Bsdf> {
        Some(Bsdf::NormalMap(Self {
            perturbed: self
                .perturbed
                .with_normal(self.normal(point), tangent(point)),
            texture: Arc::clone(&self.texture),
        }))
    }

    fn albedo_hint(&self) -> Vec3 {
        self.perturbed.nested.albedo_hint()
    }
}
