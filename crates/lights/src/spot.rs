//! Spot lights (Mitsuba's `spot` emitter): a point light whose intensity falls off away from its
//! axis and is zero beyond a cutoff angle.

use crate::PointLight;
use crate::light::{Emitter, Kind};
use crate::sample::{LightSample, mean_rgb};
use glam::{Mat3, Vec2, Vec3};
use std::f32::consts::PI;

/// A point emitting `intensity` (W/sr, RGB) along its axis, with Mitsuba's falloff: full intensity
/// within `beam_width` of the axis, then falling linearly in angle to zero at `cutoff_angle`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpotLight {
    /// The light on the axis: position and intensity.
    point: PointLight,
    /// Maps world directions into the light's frame, whose +z is the axis (the inverse of the
    /// linear part of Mitsuba's `to_world`).
    world_to_local: Mat3,
    cutoff_radians: f32,
    cos_cutoff: f32,
    cos_beam: f32,
    /// 1 / (cutoff − beam width), radians⁻¹ (infinite when the two are equal).
    inv_transition: f32,
    /// ∫ falloff dω over the sphere, sr.
    falloff_solid_angle: f32,
}

impl SpotLight {
    /// A spot at `position` whose frame is `to_world` (its +z the axis; any invertible linear
    /// map, directions are normalised after it as Mitsuba's are), with `intensity` W/sr on the
    /// axis, `cutoff_degrees` in (0, 180] and `beam_width_degrees` ≥ 0 (a beam at least as wide as
    /// the cutoff gives full intensity up to the cutoff). `None` when `to_world` is not invertible
    /// or an angle is out of range.
    pub fn new(
        position: Vec3,
        to_world: Mat3,
        intensity: Vec3,
        cutoff_degrees: f32,
        beam_width_degrees: f32,
    ) -> Option<Self> {
        let determinant = to_world.determinant();
        let angles_valid = cutoff_degrees > 0.0
            && cutoff_degrees <= 180.0
            && beam_width_degrees >= 0.0
            && beam_width_degrees.is_finite();
        if !(determinant.is_finite() && determinant != 0.0 && angles_valid) {
            return None;
        }
        let cutoff = cutoff_degrees.to_radians();
        let beam = beam_width_degrees.to_radians().min(cutoff);
        Some(Self {
            point: PointLight {
                position,
                intensity,
            },
            world_to_local: to_world.inverse(),
            cutoff_radians: cutoff,
            cos_cutoff: cutoff.cos(),
            cos_beam: beam.cos(),
            inv_transition: 1.0 / (cutoff - beam),
            falloff_solid_angle: falloff_solid_angle(cutoff, beam),
        })
    }

    /// World-space position of the light.
    pub fn position(&self) -> Vec3 {
        self.point.position
    }

    /// The falloff in [0, 1] towards the world direction `d` (any length) leaving the light: 1
    /// within the beam, (cutoff − θ) / (cutoff − beam width) in the transition, 0 from the cutoff
    /// on, where θ is the angle between `d` mapped into the light's frame and its axis.
    #[inline]
    pub fn falloff(&self, d: Vec3) -> f32 {
        let cos_theta = (self.world_to_local * d).normalize_or_zero().z;
        if cos_theta <= self.cos_cutoff {
            0.0
        } else if cos_theta >= self.cos_beam {
            1.0
        } else {
            (self.cutoff_radians - cos_theta.min(1.0).acos()) * self.inv_transition
        }
    }

    /// The only direction towards the light, with `intensity · falloff / distance²`; `None` at
    /// the light itself and where the falloff is zero.
    #[inline]
    pub fn sample_li(&self, p: Vec3) -> Option<LightSample> {
        let sample = self.point.sample_li(p)?;
        let falloff = self.falloff(-sample.wi);
        (falloff > 0.0).then(|| LightSample {
            radiance: sample.radiance * falloff,
            ..sample
        })
    }

    /// Irradiance (W m⁻², mean over channels) the light delivers at `p` on a surface facing it:
    /// intensity · falloff / distance².
    pub fn irradiance_facing(&self, p: Vec3) -> f32 {
        let from_light = p - self.point.position;
        let distance_squared = from_light.length_squared();
        if distance_squared <= 0.0 || distance_squared.is_nan() {
            return 0.0;
        }
        mean_rgb(self.point.intensity) * self.falloff(from_light) / distance_squared
    }

    /// Total emitted power (W, mean over channels): the axis intensity times ∫ falloff dω
    /// (exact for a rigid `to_world`).
    pub fn power(&self) -> f32 {
        mean_rgb(self.point.intensity) * self.falloff_solid_angle
    }
}

/// ∫ falloff dω, sr, for the cone of half-angle `cutoff` with full intensity up to `beam` ≤
/// `cutoff` (radians): 2π [(1 − cos β) + ((c − β) cos β + sin β − sin c) / (c − β)], the second
/// term being 2π ∫ (c − θ)/(c − β) sin θ dθ over [β, c].
fn falloff_solid_angle(cutoff: f32, beam: f32) -> f32 {
    let full = 1.0 - beam.cos();
    let width = cutoff - beam;
    let ramp = if width > 0.0 {
        (width * beam.cos() + beam.sin() - cutoff.sin()) / width
    } else {
        0.0
    };
    2.0 * PI * (full + ramp)
}

impl Emitter for SpotLight {
    const KIND: Kind = Kind::Delta;

    #[inline]
    fn sample_li(&self, p: Vec3, _u: Vec2, _time: f32) -> Option<LightSample> {
        SpotLight::sample_li(self, p)
    }

    fn bounding_sphere(&self) -> Option<(Vec3, f32)> {
        Some((self.position(), 0.0))
    }

    /// The irradiance itself, falloff and |cos θ| at `p` included.
    fn irradiance_estimate(&self, p: Vec3, n: Vec3) -> f32 {
        let cos = (self.position() - p).normalize_or_zero().dot(n).abs();
        self.irradiance_facing(p) * cos
    }

    fn power(&self) -> f32 {
        SpotLight::power(self)
    }
}
