//! Mitsuba's `twosided`: makes a one-sided reflecting BSDF look the same from both sides.

use crate::bsdf::{Bsdf, BsdfSample};
use crate::error::MaterialError;
use glam::{Vec2, Vec3};

/// Wraps a reflecting BSDF; when `wo` is below the surface, both directions are mirrored to the
/// upper side (z ↦ −z), evaluated there, and the sampled direction is mirrored back.
#[derive(Clone, Debug, PartialEq)]
pub struct TwoSided {
    inner: Box<Bsdf>,
}

impl TwoSided {
    /// Two-sided version of `inner`; an error if `inner` transmits (a dielectric), which
    /// Mitsuba also rejects. Wrapping a `TwoSided` again changes nothing.
    pub fn new(inner: Bsdf) -> Result<Self, MaterialError> {
        if inner.has_transmission() {
            return Err(MaterialError::TransmissiveTwoSided);
        }
        Ok(Self {
            inner: Box::new(inner),
        })
    }

    /// The wrapped BSDF, which sees only `wo` with z ≥ 0.
    pub fn inner(&self) -> &Bsdf {
        &self.inner
    }

    /// `inner.eval` with both directions mirrored when `wo.z < 0`.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        let (wo, wi) = to_upper_side(wo, wi);
        self.inner.eval(wo, wi)
    }

    /// `inner.pdf_solid_angle` with both directions mirrored when `wo.z < 0`.
    pub fn pdf_solid_angle(&self, wo: Vec3, wi: Vec3) -> f32 {
        let (wo, wi) = to_upper_side(wo, wi);
        self.inner.pdf_solid_angle(wo, wi)
    }

    /// `inner.sample` for the mirrored `wo`, the sampled direction mirrored back to `wo`'s side.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u_dir: Vec2) -> Option<BsdfSample> {
        let below = wo.z.is_sign_negative();
        let wo_upper = if below { flip_z(wo) } else { wo };
        let mut sample = self.inner.sample(wo_upper, u_lobe, u_dir)?;
        if below {
            sample.wi = flip_z(sample.wi);
        }
        Some(sample)
    }
}

/// Mitsuba's flip: when `wo.z` is negative (sign bit set, as Mitsuba's `mulsign`), both
/// directions are mirrored so that `wo` is on the upper side.
fn to_upper_side(wo: Vec3, wi: Vec3) -> (Vec3, Vec3) {
    if wo.z.is_sign_negative() {
        (flip_z(wo), flip_z(wi))
    } else {
        (wo, wi)
    }
}

/// Mirror image of `w` in the tangent plane.
fn flip_z(w: Vec3) -> Vec3 {
    Vec3::new(w.x, w.y, -w.z)
}
