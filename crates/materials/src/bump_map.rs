//! Mitsuba's `bumpmap`: a nested BSDF whose shading normal a height field's gradient turns.

use crate::bitmap::BitmapTexture;
use crate::bsdf::{Bsdf, Model};
use crate::perturbed::{AdapterOptions, Perturbed, SurfacePoint, forward_to_perturbed};
use glam::Vec3;
use std::sync::Arc;

/// A nested BSDF seen through a shading frame turned by a height field h(u, v) = `scale` × the
/// texture's luminance, as Mitsuba's `bumpmap`: with n the shading normal, the surface's
/// tangents become ∂p/∂u + (∂h/∂u − n · ∂p/∂u) n and ∂p/∂v + (∂h/∂v − n · ∂p/∂v) n (the
/// texture-space change of n itself neglected), their cross product is the new normal, turned
/// to the geometric normal's side, and ∂p/∂u made perpendicular to it the first tangent. Only
/// variations of the height matter, not its level; a texture read with `nearest` filtering has no
/// gradient (Mitsuba's) and perturbs nothing. How directions pass through the perturbed frame
/// (the flip, the side test, the cosine and the shadowing term, switched by
/// [`AdapterOptions`]): see `Perturbed`.
///
/// The BSDF as built has no perturbation; [`Bsdf::at_surface`] gives the one for a hit.
#[derive(Clone, Debug, PartialEq)]
pub struct BumpMap {
    perturbed: Perturbed,
    texture: Arc<BitmapTexture>,
    scale: f32,
}

impl BumpMap {
    /// `nested` under the height field `scale` × luminance of `texture` (Mitsuba's `scale`,
    /// default 1; a world-space height per unit of luminance), with Mitsuba's `options`.
    pub fn new(
        nested: Bsdf,
        texture: Arc<BitmapTexture>,
        scale: f32,
        options: AdapterOptions,
    ) -> Self {
        Self {
            perturbed: Perturbed::new(nested, options),
            texture,
            scale,
        }
    }

    /// Mitsuba's switches: the flip of normals facing away from `wo` and the shadowing term.
    pub fn options(&self) -> AdapterOptions {
        self.perturbed.options()
    }

    /// The BSDF under the bumps.
    pub fn nested(&self) -> &Bsdf {
        &self.perturbed.nested
    }

    /// The perturbed shading normal at `point`, in the local shading frame: unit length, or the
    /// unperturbed +z where the surface has no parameterisation (∂p/∂u or ∂p/∂v zero).
    pub fn normal(&self, point: &SurfacePoint) -> Vec3 {
        let gradient = self.scale * self.texture.luminance_gradient(point.uv);
        // In the shading frame n = +z, so replacing a tangent's normal part is setting its z.
        let dp_du = point.dp_du.truncate().extend(gradient.x);
        let dp_dv = point.dp_dv.truncate().extend(gradient.y);
        let Some(n) = dp_du.cross(dp_dv).try_normalize() else {
            return Vec3::Z;
        };
        if n.dot(point.ng) < 0.0 { -n } else { n }
    }
}

impl Model for BumpMap {
    forward_to_perturbed!();

    fn at_surface(&self, point: &SurfacePoint) -> Option<Bsdf> {
        Some(Bsdf::BumpMap(Self {
            perturbed: self.perturbed.with_normal(self.normal(point), point.dp_du),
            texture: Arc::clone(&self.texture),
            scale: self.scale,
        }))
    }
}
