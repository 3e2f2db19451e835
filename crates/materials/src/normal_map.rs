//! Mitsuba's `normalmap`: a nested BSDF whose shading normal an RGB texture gives.

use crate::bitmap::BitmapTexture;
use crate::bsdf::{Bsdf, Model};
use crate::perturbed::{AdapterOptions, Perturbed, SurfacePoint, forward_to_perturbed};
use glam::Vec3;
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
    forward_to_perturbed!();

    fn at_surface(&self, point: &SurfacePoint) -> Option<Bsdf> {
        Some(Bsdf::NormalMap(Self {
            perturbed: self
                .perturbed
                .with_normal(self.normal(point), tangent(point)),
            texture: Arc::clone(&self.texture),
        }))
    }
}
