//! What Mitsuba's BSDF adapters `normalmap` and `bumpmap` share: a nested BSDF seen through a
//! shading frame turned at each hit, and the surface geometry that frame is computed from.

use crate::bsdf::{Bsdf, BsdfSample};
use crate::flags::BsdfFlags;
use glam::{Vec2, Vec3};
use sampling::Frame;
use std::sync::Arc;

/// The geometry of a surface point that a BSDF depending on it needs ([`Bsdf::at_surface`]),
/// every vector in the local shading frame of the hit (+z the shading normal, before a
/// twosided's mirroring).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// Surface coordinates (u, v), dimensionless, as textures are looked up by them.
    pub uv: Vec2,
    /// ∂p/∂u: world units per unit of u (zero where the parameterisation has none).
    pub dp_du: Vec3,
    /// ∂p/∂v: world units per unit of v (zero where the parameterisation has none).
    pub dp_dv: Vec3,
    /// The unit geometric normal.
    pub ng: Vec3,
}

/// A nested BSDF seen through `frame`, an orthonormal frame given in the local shading frame
/// (its `n` the perturbed normal), as Mitsuba's adapters see theirs:
///
/// - directions are moved into `frame` before the nested BSDF sees them;
/// - a direction `wi` on one side of the shading normal and on the other of the perturbed one
///   scatters nothing (Mitsuba: `cos_theta(wo) * cos_theta(perturbed_wo) > 0`, where its `wo` is
///   `wi` here); `wo` is left for the nested BSDF to judge in the perturbed frame;
/// - the cosine that weights the nested BSDF is the perturbed one (Mitsuba's BSDFs include it),
///   so f = f_nested(wo', wi') · |cos θ'i| / |cos θi|, which gives the estimator the nested
///   BSDF's weight f_nested · |cos θ'i| / pdf. The density is the nested one (a rotation keeps
///   solid angles).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Perturbed {
    /// The BSDF seen through the frame, shared by the copies made at each hit.
    pub nested: Arc<Bsdf>,
    /// The perturbed frame in local shading coordinates; the identity until a hit sets it.
    pub frame: Frame,
}

/// The frame that perturbs nothing: local coordinates stay as they are.
pub(crate) const IDENTITY: Frame = Frame {
    s: Vec3::X,
    t: Vec3::Y,
    n: Vec3::Z,
};

impl Perturbed {
    /// `nested` seen through the identity frame.
    pub fn new(nested: Bsdf) -> Self {
        Self {
            nested: Arc::new(nested),
            frame: IDENTITY,
        }
    }

    /// The same nested BSDF seen through the frame around the local unit normal `n` whose first
    /// tangent is `dp_du` made perpendicular to it (Mitsuba's Gram–Schmidt step), or the
    /// identity when `n` is not a finite direction in the upper hemisphere's closure.
    pub fn with_normal(&self, n: Vec3, dp_du: Vec3) -> Self {
        let frame = if n.is_finite() && n.length_squared() > 0.0 {
            let n = n.normalize();
            let tangent = if dp_du.length_squared() > 0.0 {
                dp_du
            } else {
                Vec3::X
            };
            Frame::from_normal_and_tangent(n, tangent)
        } else {
            IDENTITY
        };
        Self {
            nested: Arc::clone(&self.nested),
            frame,
        }
    }

    /// The nested BSDF's flags.
    #[inline]
    pub fn flags(&self) -> BsdfFlags {
        self.nested.flags()
    }

    /// `wo` and `wi` in the perturbed frame, `None` when `wi` changes sides.
    #[inline]
    fn directions(&self, wo: Vec3, wi: Vec3) -> Option<(Vec3, Vec3)> {
        let wi_p = self.frame.to_local(wi);
        (wi.z * wi_p.z > 0.0).then(|| (self.frame.to_local(wo), wi_p))
    }

    /// f(wo, wi) per steradian without the cosine (see the type's documentation).
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        self.eval_with_pdf(wo, wi).0
    }

    /// Density per steradian of [`Self::sample`]'s directions.
    pub fn pdf_solid_angle(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.directions(wo, wi)
            .map_or(0.0, |(wo_p, wi_p)| self.nested.pdf_solid_angle(wo_p, wi_p))
    }

    /// [`Self::eval`] and [`Self::pdf_solid_angle`] at once.
    pub fn eval_with_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        let Some((wo_p, wi_p)) = self.directions(wo, wi) else {
            return (Vec3::ZERO, 0.0);
        };
        let (f, pdf) = self.nested.eval_with_pdf(wo_p, wi_p);
        (f * (wi_p.z.abs() / wi.z.abs()), pdf)
    }

    /// The nested BSDF's lobe weight for the perturbed directions (an estimate of f · |cos θ|,
    /// which the perturbation does not change).
    pub fn lobe_weight(&self, wo: Vec3, wi: Vec3) -> Option<f32> {
        self.nested
            .lobe_weight(self.frame.to_local(wo), self.frame.to_local(wi))
    }

    /// A nested sample moved back to the shading frame, `None` when it changes sides.
    fn unperturbed(&self, sample: BsdfSample) -> Option<BsdfSample> {
        let wi = self.frame.to_world(sample.wi);
        (wi.z * sample.wi.z > 0.0).then(|| BsdfSample {
            f: sample.f * (sample.wi.z.abs() / wi.z.abs()),
            wi,
            ..sample
        })
    }

    /// Samples the nested BSDF in the perturbed frame.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u_dir: Vec2) -> Option<BsdfSample> {
        let sample = self.nested.sample(self.frame.to_local(wo), u_lobe, u_dir)?;
        self.unperturbed(sample)
    }

    /// Samples the nested BSDF's delta lobes in the perturbed frame.
    pub fn sample_delta(&self, wo: Vec3, u_lobe: f32) -> Option<BsdfSample> {
        let sample = self.nested.sample_delta(self.frame.to_local(wo), u_lobe)?;
        self.unperturbed(sample)
    }
}
