//! Mitsuba's `twosided`: one-sided reflecting BSDFs on both sides of a surface, the same one or
//! a different one per side.

use crate::bsdf::{Bsdf, BsdfSample, DeltaLobes, Model};
use crate::error::MaterialError;
use crate::flags::BsdfFlags;
use glam::{Vec2, Vec3};

/// A reflecting BSDF on each side of the surface. When `wo` is below the surface (its z has the
/// sign bit set, as Mitsuba's `mulsign`), the back BSDF is used with both directions mirrored to
/// the upper side (z ↦ −z), and a sampled direction is mirrored back; otherwise the front BSDF as
/// it is. With one BSDF for both sides the surface looks the same from either side.
#[derive(Clone, Debug, PartialEq)]
pub struct TwoSided {
    front: Box<Bsdf>,
    back: Box<Bsdf>,
    /// The union of both sides' flags: kept so that [`Bsdf::flags`], asked at every path vertex,
    /// is not recursive and can be inlined.
    flags: BsdfFlags,
}

impl TwoSided {
    /// `bsdf` on both sides; an error if it transmits (a dielectric), which Mitsuba also
    /// rejects.
    pub fn new(bsdf: Bsdf) -> Result<Self, MaterialError> {
        Self::with_sides(bsdf.clone(), bsdf)
    }

    /// `front` on the side of the normal, `back` on the other; an error if either transmits.
    pub fn with_sides(front: Bsdf, back: Bsdf) -> Result<Self, MaterialError> {
        if (front.flags() | back.flags()).contains(BsdfFlags::TRANSMISSION) {
            return Err(MaterialError::TransmissiveTwoSided);
        }
        Ok(Self {
            flags: front.flags() | back.flags(),
            front: Box::new(front),
            back: Box::new(back),
        })
    }

    /// Both sides with their diffuse albedo replaced by `reflectance`
    /// ([`Bsdf::with_diffuse_reflectance`]); `None` unless both have one.
    pub fn with_diffuse_reflectance(&self, reflectance: Vec3) -> Option<Self> {
        Some(Self {
            front: Box::new(self.front.with_diffuse_reflectance(reflectance)?),
            back: Box::new(self.back.with_diffuse_reflectance(reflectance)?),
            flags: self.flags,
        })
    }

    /// The BSDF on the side of the normal, which sees only `wo` with z ≥ 0.
    pub fn front(&self) -> &Bsdf {
        &self.front
    }

    /// The BSDF on the other side, seen through mirrored directions (z ≥ 0).
    pub fn back(&self) -> &Bsdf {
        &self.back
    }

    /// The BSDF that `wo` (local frame) sees, and whether directions must be mirrored for it.
    #[inline]
    pub fn facing(&self, wo: Vec3) -> (&Bsdf, bool) {
        if wo.z.is_sign_negative() {
            (&self.back, true)
        } else {
            (&self.front, false)
        }
    }

    /// The facing BSDF's `eval`, both directions mirrored for the back.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        let (bsdf, mirrored) = self.facing(wo);
        bsdf.eval(mirror_if(wo, mirrored), mirror_if(wi, mirrored))
    }

    /// The facing BSDF's `pdf_solid_angle`, both directions mirrored for the back.
    pub fn pdf_solid_angle(&self, wo: Vec3, wi: Vec3) -> f32 {
        let (bsdf, mirrored) = self.facing(wo);
        bsdf.pdf_solid_angle(mirror_if(wo, mirrored), mirror_if(wi, mirrored))
    }

    /// The facing BSDF's `eval_with_pdf`, both directions mirrored for the back.
    pub fn eval_with_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        let (bsdf, mirrored) = self.facing(wo);
        bsdf.eval_with_pdf(mirror_if(wo, mirrored), mirror_if(wi, mirrored))
    }

    /// The facing BSDF's `lobe_weight`, both directions mirrored for the back.
    pub fn lobe_weight(&self, wo: Vec3, wi: Vec3) -> Option<f32> {
        let (bsdf, mirrored) = self.facing(wo);
        bsdf.lobe_weight(mirror_if(wo, mirrored), mirror_if(wi, mirrored))
    }

    /// The facing BSDF's `sample` for the (mirrored) `wo`, the direction mirrored back to `wo`'s
    /// side.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u_dir: Vec2) -> Option<BsdfSample> {
        let (bsdf, mirrored) = self.facing(wo);
        let mut sample = bsdf.sample(mirror_if(wo, mirrored), u_lobe, u_dir)?;
        sample.wi = mirror_if(sample.wi, mirrored);
        Some(sample)
    }

    /// The facing BSDF's `sample_delta` for the (mirrored) `wo`, the direction mirrored back.
    pub fn sample_delta(&self, wo: Vec3, u_lobe: f32) -> Option<BsdfSample> {
        let (bsdf, mirrored) = self.facing(wo);
        let mut sample = bsdf.sample_delta(mirror_if(wo, mirrored), u_lobe)?;
        sample.wi = mirror_if(sample.wi, mirrored);
        Some(sample)
    }
}

/// `w` mirrored in the tangent plane when `mirrored`, else `w`.
fn mirror_if(w: Vec3, mirrored: bool) -> Vec3 {
    if mirrored {
        Vec3::new(w.x, w.y, -w.z)
    } else {
        w
    }
}

impl Model for TwoSided {
    #[inline]
    fn flags(&self) -> BsdfFlags {
        self.flags
    }

    #[inline]
    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        TwoSided::eval(self, wo, wi)
    }

    #[inline]
    fn pdf_solid_angle(&self, wo: Vec3, wi: Vec3) -> f32 {
        TwoSided::pdf_solid_angle(self, wo, wi)
    }

    #[inline]
    fn eval_with_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        TwoSided::eval_with_pdf(self, wo, wi)
    }

    #[inline]
    fn lobe_weight(&self, wo: Vec3, wi: Vec3) -> Option<f32> {
        TwoSided::lobe_weight(self, wo, wi)
    }

    #[inline]
    fn sample(&self, wo: Vec3, u_lobe: f32, u_dir: Vec2) -> Option<BsdfSample> {
        TwoSided::sample(self, wo, u_lobe, u_dir)
    }

    fn sample_delta(&self, wo: Vec3, u_lobe: f32) -> Option<BsdfSample> {
        TwoSided::sample_delta(self, wo, u_lobe)
    }

    fn delta_lobes(&self, wo: Vec3) -> DeltaLobes {
        let (bsdf, mirrored) = self.facing(wo);
        bsdf.delta_lobes(mirror_if(wo, mirrored)).map(|lobe| {
            lobe.map(|mut sample| {
                sample.wi = mirror_if(sample.wi, mirrored);
                sample
            })
        })
    }

    fn with_diffuse_reflectance(&self, reflectance: Vec3) -> Option<Bsdf> {
        TwoSided::with_diffuse_reflectance(self, reflectance).map(Bsdf::TwoSided)
    }

    fn albedo_hint(&self) -> Vec3 {
        0.5 * (self.front().albedo_hint() + self.back().albedo_hint())
    }
}
