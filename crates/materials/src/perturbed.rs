//! What Mitsuba's BSDF adapters `normalmap` and `bumpmap` share: a nested BSDF seen through a
//! shading frame turned at each hit, and the surface geometry that frame is computed from.

use crate::bsdf::{Bsdf, BsdfSample};
use crate::flags::BsdfFlags;
use glam::{Vec2, Vec3};
use sampling::Frame;
use std::sync::Arc;

/// The [`crate::bsdf::Model`] methods of an adapter whose `perturbed: Perturbed` field does the
/// work (`normalmap`, `bumpmap`): each forwards to it, and the flags add
/// [`BsdfFlags::AT_SURFACE`]. The adapter writes only `at_surface`, which turns the frame.
macro_rules! forward_to_perturbed {
    () => {
        #[inline]
        fn flags(&self) -> $crate::flags::BsdfFlags {
            self.perturbed.flags() | $crate::flags::BsdfFlags::AT_SURFACE
        }

        fn eval(&self, wo: glam::Vec3, wi: glam::Vec3) -> glam::Vec3 {
            self.perturbed.eval(wo, wi)
        }

        fn pdf_solid_angle(&self, wo: glam::Vec3, wi: glam::Vec3) -> f32 {
            self.perturbed.pdf_solid_angle(wo, wi)
        }

        fn eval_with_pdf(&self, wo: glam::Vec3, wi: glam::Vec3) -> (glam::Vec3, f32) {
            self.perturbed.eval_with_pdf(wo, wi)
        }

        fn lobe_weight(&self, wo: glam::Vec3, wi: glam::Vec3) -> Option<f32> {
            self.perturbed.lobe_weight(wo, wi)
        }

        fn sample(
            &self,
            wo: glam::Vec3,
            u_lobe: f32,
            u_dir: glam::Vec2,
        ) -> Option<$crate::bsdf::BsdfSample> {
            self.perturbed.sample(wo, u_lobe, u_dir)
        }

        fn sample_delta(&self, wo: glam::Vec3, u_lobe: f32) -> Option<$crate::bsdf::BsdfSample> {
            self.perturbed.sample_delta(wo, u_lobe)
        }

        fn albedo_hint(&self) -> glam::Vec3 {
            self.perturbed.nested.albedo_hint()
        }
    };
}
pub(crate) use forward_to_perturbed;

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

/// Mitsuba 3.9's two switches of its `normalmap` and `bumpmap` adapters, both on by default
/// ([`Default`]), as its XML booleans `flip_invalid_normals` and `use_shadowing_function`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AdapterOptions {
    /// Where `wo` is below the perturbed normal n, use n mirrored about the shading normal,
    /// (−nx, −ny, nz), instead (Schüssler et al. 2017's flip, as Mitsuba has it): the viewer
    /// always sees the front of the perturbed surface rather than black.
    pub flip_invalid_normals: bool,
    /// Weight the BSDF by the microfacet shadowing term of Estevez et al. 2019 (Mitsuba's
    /// `eval_shadow_terminator`), G(wi) = 2 / (1 + √(1 + α² tan²θi)) with
    /// α² = min(tan²θn / 8, 1), θ from the shading normal: a softer terminator on the light's side.
    pub shadowing_function: bool,
}

impl Default for AdapterOptions {
    /// Mitsuba's defaults: both on.
    fn default() -> Self {
        Self {
            flip_invalid_normals: true,
            shadowing_function: true,
        }
    }
}

/// A nested BSDF seen through a perturbed frame, an orthonormal frame given in the local shading
/// frame (its `n` the perturbed normal), as Mitsuba 3.9's adapters see theirs (Mitsuba's `wo` is
/// `wi` here and its `si.wi` is `wo`):
///
/// - with [`AdapterOptions::flip_invalid_normals`], a `wo` on the other side of the perturbed
///   normal than of the shading normal uses the flipped frame (normal (−nx, −ny, nz));
/// - directions are moved into the chosen frame before the nested BSDF sees them;
/// - a direction `wi` on one side of the shading normal and on the other of the perturbed one
///   scatters nothing (Mitsuba: `cos_theta(wo) * cos_theta(perturbed_wo) > 0`); `wo` is left for
///   the nested BSDF to judge in the perturbed frame;
/// - the cosine that weights the nested BSDF is the perturbed one (Mitsuba's BSDFs include it),
///   and the shadowing term G(wi) multiplies it when enabled, so
///   f = f_nested(wo', wi') · |cos θ'i| / |cos θi| · G(wi), which gives the estimator the nested
///   BSDF's weight f_nested · |cos θ'i| / pdf times G(wi), Mitsuba's sample weight. The density
///   is the nested one (a rotation keeps solid angles).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Perturbed {
    /// The BSDF seen through the frame, shared by the copies made at each hit.
    pub nested: Arc<Bsdf>,
    /// The perturbed frame in local shading coordinates; the identity until a hit sets it.
    pub frame: Frame,
    /// `frame` with its normal mirrored about the shading normal, for a `wo` below `frame.n`.
    flipped: Frame,
    /// Mitsuba's switches.
    options: AdapterOptions,
    /// α² of the shadowing term: min(tan²θn / 8, 1) of the perturbed normal, 0 (G = 1) when the
    /// term is off or nothing is perturbed.
    alpha2: f32,
}

/// The frame that perturbs nothing: local coordinates stay as they are.
pub(crate) const IDENTITY: Frame = Frame {
    s: Vec3::X,
    t: Vec3::Y,
    n: Vec3::Z,
};

/// tan²θ of a unit vector `w` from +z, as Mitsuba's `Frame::tan_theta_2`: (1 − z²) / z².
#[inline]
fn tan_theta_2(w: Vec3) -> f32 {
    (1.0 - w.z * w.z).max(0.0) / (w.z * w.z)
}

impl Perturbed {
    /// `nested` seen through the identity frame.
    pub fn new(nested: Bsdf, options: AdapterOptions) -> Self {
        Self {
            nested: Arc::new(nested),
            frame: IDENTITY,
            flipped: IDENTITY,
            options,
            alpha2: 0.0,
        }
    }

    /// The same nested BSDF seen through the frame around the local unit normal `n` whose first
    /// tangent is `dp_du` made perpendicular to it (Mitsuba's Gram–Schmidt step), or the
    /// identity when `n` is not a finite nonzero direction.
    pub fn with_normal(&self, n: Vec3, dp_du: Vec3) -> Self {
        let (frame, flipped, alpha2) = if n.is_finite() && n.length_squared() > 0.0 {
            let n = n.normalize();
            let tangent = if dp_du.length_squared() > 0.0 {
                dp_du
            } else {
                Vec3::X
            };
            let flipped = Vec3::new(-n.x, -n.y, n.z);
            let alpha2 = if self.options.shadowing_function {
                (0.125 * tan_theta_2(n)).min(1.0)
            } else {
                0.0
            };
            (
                Frame::from_normal_and_tangent(n, tangent),
                Frame::from_normal_and_tangent(flipped, tangent),
                alpha2,
            )
        } else {
            (IDENTITY, IDENTITY, 0.0)
        };
        Self {
            nested: Arc::clone(&self.nested),
            frame,
            flipped,
            options: self.options,
            alpha2,
        }
    }

    /// Mitsuba's switches this adapter was built with.
    pub fn options(&self) -> AdapterOptions {
        self.options
    }

    /// The nested BSDF's flags.
    #[inline]
    pub fn flags(&self) -> BsdfFlags {
        self.nested.flags()
    }

    /// The frame `wo` sees: the flipped one when flipping is on and `wo` is on the other side of
    /// the perturbed normal than of the shading normal (Mitsuba's test, `<= 0`).
    #[inline]
    fn frame_for(&self, wo: Vec3) -> &Frame {
        if self.options.flip_invalid_normals && wo.z * wo.dot(self.frame.n) <= 0.0 {
            &self.flipped
        } else {
            &self.frame
        }
    }

    /// The shadowing term G(wi) (1 when off or unperturbed).
    #[inline]
    fn shadowing(&self, wi: Vec3) -> f32 {
        if self.alpha2 == 0.0 {
            1.0
        } else {
            2.0 / (1.0 + (1.0 + self.alpha2 * tan_theta_2(wi)).sqrt())
        }
    }

    /// `wo` and `wi` in the frame `wo` sees, `None` when `wi` changes sides.
    #[inline]
    fn directions(&self, wo: Vec3, wi: Vec3) -> Option<(Vec3, Vec3)> {
        let frame = self.frame_for(wo);
        let wi_p = frame.to_local(wi);
        (wi.z * wi_p.z > 0.0).then(|| (frame.to_local(wo), wi_p))
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
        (f * (wi_p.z.abs() / wi.z.abs() * self.shadowing(wi)), pdf)
    }

    /// The nested BSDF's lobe weight for the perturbed directions (an estimate of f · |cos θ|,
    /// which the perturbation changes only by the shadowing term, at most 1, left out here).
    pub fn lobe_weight(&self, wo: Vec3, wi: Vec3) -> Option<f32> {
        let frame = self.frame_for(wo);
        self.nested
            .lobe_weight(frame.to_local(wo), frame.to_local(wi))
    }

    /// A nested sample drawn in `frame` moved back to the shading frame, `None` when it changes
    /// sides.
    fn unperturbed(&self, frame: &Frame, sample: BsdfSample) -> Option<BsdfSample> {
        let wi = frame.to_world(sample.wi);
        (wi.z * sample.wi.z > 0.0).then(|| BsdfSample {
            f: sample.f * (sample.wi.z.abs() / wi.z.abs() * self.shadowing(wi)),
            wi,
            ..sample
        })
    }

    /// Samples the nested BSDF in the perturbed frame.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u_dir: Vec2) -> Option<BsdfSample> {
        let frame = self.frame_for(wo);
        let sample = self.nested.sample(frame.to_local(wo), u_lobe, u_dir)?;
        self.unperturbed(frame, sample)
    }

    /// Samples the nested BSDF's delta lobes in the perturbed frame.
    pub fn sample_delta(&self, wo: Vec3, u_lobe: f32) -> Option<BsdfSample> {
        let frame = self.frame_for(wo);
        let sample = self.nested.sample_delta(frame.to_local(wo), u_lobe)?;
        self.unperturbed(frame, sample)
    }
}
