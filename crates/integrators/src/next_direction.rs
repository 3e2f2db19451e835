//! A sampled continuation of a path, whichever strategy sampled it.

use glam::Vec3;
use materials::BsdfSample;

/// The direction a walk continues in from a surface, with what its estimator needs.
#[derive(Clone, Copy, Debug)]
pub struct NextDirection {
    /// The direction, local shading frame, unit length.
    pub wi: Vec3,
    /// Throughput factor f·|cos θi| / pdf (RGB, dimensionless).
    pub weight: Vec3,
    /// Density per steradian of `wi` (for a delta lobe: the probability of choosing the lobe).
    pub pdf_solid_angle: f32,
    /// Whether `wi` came from a delta lobe.
    pub is_delta: bool,
    /// Whether `wi` passes straight on through a null lobe ([`materials::BsdfSample::is_null`]).
    pub is_null: bool,
    /// Relative index of refraction crossed (1 for reflection).
    pub eta: f32,
}

impl From<BsdfSample> for NextDirection {
    /// The continuation a BSDF's own sample gives, its weight f·|cos θi| / pdf.
    #[inline]
    fn from(s: BsdfSample) -> Self {
        Self {
            wi: s.wi,
            weight: s.f * s.wi.z.abs() / s.pdf_solid_angle,
            pdf_solid_angle: s.pdf_solid_angle,
            is_delta: s.is_delta,
            is_null: s.is_null,
            eta: s.eta,
        }
    }
}
