//! A transform that moves over time, given by keyframes: the object-to-world matrix of a moving
//! shape or camera during the shutter interval (motion blur).
//!
//! Each keyframe matrix `M` is decomposed into translation, rotation and scale, `M = T · R · S`
//! (pbrt's `AnimatedTransform`): `T` is the last column, and the upper 3 × 3 block is split by
//! its polar decomposition into a rotation `R` and a symmetric stretch `S`. Between two
//! keyframes the translation and the stretch interpolate linearly and the rotation by
//! quaternion slerp along the shorter arc, so a rigid motion stays rigid at every time; before
//! the first keyframe and after the last the transform holds. A rotation of half a turn or more
//! between two keyframes takes the other way round: spin by several keyframes (a full turn by
//! at least three segments).
//!
//! Times are in the scene's units (those of the sensor's `shutter_open` and `shutter_close`),
//! lengths in the scene's.

use glam::{DMat3, DMat4, DQuat, DVec3};

use crate::Aabb;

/// The polar decomposition stops when no entry of `R` moves by more than this.
const POLAR_TOLERANCE: f64 = 1e-13;

/// The most iterations of the polar decomposition (it converges quadratically: a matrix of
/// condition number 1e6 needs about 30).
const POLAR_ITERATIONS: usize = 100;

/// A keyframe matrix [`AnimatedTransform::new`] cannot use.
#[derive(Clone, Debug, PartialEq)]
pub enum AnimationError {
    /// Fewer than two keyframes.
    TooFewKeyframes,
    /// Keyframe `index`'s time is not after the one before it, or not finite.
    TimesNotIncreasing {
        /// The keyframe (from 0) whose time is out of order.
        index: usize,
    },
    /// Keyframe `index`'s matrix is projective, singular or not finite, so it is not a
    /// translation, rotation and scale.
    NotDecomposable {
        /// The keyframe (from 0).
        index: usize,
        /// Why.
        reason: &'static str,
    },
}

impl std::fmt::Display for AnimationError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::TooFewKeyframes => write!(f, "an animation needs at least two keyframes"),
            Self::TimesNotIncreasing { index } => write!(
                f,
                "keyframe {} must come strictly after the one before it (times strictly increasing)",
                index + 1
            ),
            Self::NotDecomposable { index, reason } => write!(
                f,
                "keyframe {}'s matrix cannot be decomposed into translation, rotation and scale: {reason}",
                index + 1
            ),
        }
    }
}

impl std::error::Error for AnimationError {}

/// One keyframe, decomposed.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Keyframe {
    time: f64,
    translation: DVec3,
    rotation: DQuat,
    /// The symmetric stretch `S` (a reflection is kept here as a negative scale).
    stretch: DMat3,
}

/// A transform interpolated between keyframes (see the module documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct AnimatedTransform {
    keyframes: Vec<Keyframe>,
}

impl AnimatedTransform {
    /// The transform through `keyframes` (time, matrix), at least two, times strictly increasing.
    ///
    /// # Errors
    /// Too few keyframes, times out of order, or a matrix that is projective, singular or not
    /// finite.
    pub fn new(keyframes: &[(f64, DMat4)]) -> Result<Self, AnimationError> {
        if keyframes.len() < 2 {
            return Err(AnimationError::TooFewKeyframes);
        }
        let mut decomposed: Vec<Keyframe> = Vec::with_capacity(keyframes.len());
        for (index, &(time, matrix)) in keyframes.iter().enumerate() {
            let in_order = time.is_finite() && decomposed.last().is_none_or(|k| time > k.time);
            if !in_order {
                return Err(AnimationError::TimesNotIncreasing { index });
            }
            let (translation, mut rotation, stretch) = decompose(&matrix)
                .map_err(|reason| AnimationError::NotDecomposable { index, reason })?;
            // Slerp along the shorter arc from the keyframe before.
            if let Some(previous) = decomposed.last()
                && previous.rotation.dot(rotation) < 0.0
            {
                rotation = -rotation;
            }
            decomposed.push(Keyframe {
                time,
                translation,
                rotation,
                stretch,
            });
        }
        Ok(Self {
            keyframes: decomposed,
        })
    }

    /// The first and last keyframes' times.
    pub fn time_range(&self) -> (f64, f64) {
        (
            self.keyframes[0].time,
            self.keyframes[self.keyframes.len() - 1].time,
        )
    }

    /// The same motion followed by a translation by `offset` (world units).
    pub fn translated(&self, offset: DVec3) -> Self {
        let mut moved = self.clone();
        for keyframe in &mut moved.keyframes {
            keyframe.translation += offset;
        }
        moved
    }

    /// The keyframes' times and matrices (as decomposed and recomposed).
    pub fn keyframes(&self) -> impl Iterator<Item = (f64, DMat4)> + '_ {
        self.keyframes.iter().map(|k| (k.time, k.matrix()))
    }

    /// Whether some keyframe mirrors space (a negative determinant).
    pub fn mirrors(&self) -> bool {
        self.keyframes
            .iter()
            .any(|keyframe| keyframe.stretch.determinant() < 0.0)
    }

    /// The object-to-world matrix at `time` (held outside the keyframes).
    pub fn at(&self, time: f64) -> DMat4 {
        let frames = &self.keyframes;
        let last = frames.len() - 1;
        if time.is_nan() || time <= frames[0].time {
            return frames[0].matrix();
        }
        if time >= frames[last].time {
            return frames[last].matrix();
        }
        // The segment [k, k + 1] holding `time`.
        let k = frames.partition_point(|f| f.time <= time) - 1;
        let (a, b) = (&frames[k], &frames[k + 1]);
        let s = (time - a.time) / (b.time - a.time);
        Keyframe {
            time,
            translation: a.translation.lerp(b.translation, s),
            rotation: a.rotation.slerp(b.rotation, s),
            stretch: a.stretch * (1.0 - s) + b.stretch * s,
        }
        .matrix()
    }

    /// A box holding `bounds` (object space) transformed at every time: exact for segments
    /// whose rotation does not change (the transformed points then move affinely in time, so
    /// the box of the two ends holds the sweep), and for rotating segments the box of the
    /// translations grown by the largest distance an object point can have from its own
    /// translation, `|S| · max |x|` with `|S|` the larger Frobenius norm of the two stretches
    /// (a bound on the spectral norm along the whole segment, the norm being convex).
    pub fn motion_bounds(&self, bounds: &Aabb) -> Aabb {
        let (lo, hi) = (bounds.min.as_dvec3(), bounds.max.as_dvec3());
        let corners = (0..8).map(|i| {
            DVec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            )
        });
        let radius = corners.clone().map(DVec3::length).fold(0.0, f64::max);
        let box_at = |m: DMat4| {
            corners
                .clone()
                .map(|c| m.transform_point3(c))
                .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(a, b), p| {
                    (a.min(p), b.max(p))
                })
        };
        let (mut min, mut max) = box_at(self.keyframes[0].matrix());
        for pair in self.keyframes.windows(2) {
            let (a, b) = (&pair[0], &pair[1]);
            if a.rotation.abs_diff_eq(b.rotation, 1e-15) {
                let (b_min, b_max) = box_at(b.matrix());
                (min, max) = (min.min(b_min), max.max(b_max));
            } else {
                let reach = radius * frobenius(&a.stretch).max(frobenius(&b.stretch));
                let low = a.translation.min(b.translation) - DVec3::splat(reach);
                let high = a.translation.max(b.translation) + DVec3::splat(reach);
                (min, max) = (min.min(low), max.max(high));
            }
        }
        // Rounding to f32 outwards keeps the box conservative.
        Aabb {
            min: min.as_vec3().map(f32::next_down),
            max: max.as_vec3().map(f32::next_up),
        }
    }
}

impl Keyframe {
    fn matrix(&self) -> DMat4 {
        let linear = DMat3::from_quat(self.rotation) * self.stretch;
        DMat4::from_cols(
            linear.x_axis.extend(0.0),
            linear.y_axis.extend(0.0),
            linear.z_axis.extend(0.0),
            self.translation.extend(1.0),
        )
    }
}

/// `M = T · R · S`: the translation, the rotation (a unit quaternion) and the symmetric
/// stretch, by the polar decomposition of the upper 3 × 3 block (Higham's iteration
/// `R ← (R + R⁻ᵀ) / 2`). An improper rotation (a reflection) is returned as the rotation of
/// `−R` with the stretch `−S`.
fn decompose(m: &DMat4) -> Result<(DVec3, DQuat, DMat3), &'static str> {
    if !m.is_finite() {
        return Err("it is not finite");
    }
    let bottom = m.row(3);
    if bottom.x != 0.0 || bottom.y != 0.0 || bottom.z != 0.0 || bottom.w != 1.0 {
        return Err("its last row is not (0, 0, 0, 1) (a projective matrix)");
    }
    let linear = DMat3::from_mat4(*m);
    let scale = frobenius(&linear);
    if linear.determinant().abs() <= 1e-12 * scale * scale * scale {
        return Err("it is singular (it flattens space)");
    }
    let mut rotation = linear;
    let mut converged = false;
    for _ in 0..POLAR_ITERATIONS {
        let next = (rotation + rotation.inverse().transpose()) * 0.5;
        let change = (next - rotation)
            .to_cols_array()
            .iter()
            .fold(0.0, |a: f64, d| a.max(d.abs()));
        rotation = next;
        if change <= POLAR_TOLERANCE {
            converged = true;
            break;
        }
    }
    if !converged {
        return Err("its polar decomposition does not converge");
    }
    let mut stretch = rotation.transpose() * linear;
    if rotation.determinant() < 0.0 {
        rotation = -rotation;
        stretch = -stretch;
    }
    Ok((
        m.w_axis.truncate(),
        DQuat::from_mat3(&rotation).normalize(),
        stretch,
    ))
}

/// The Frobenius norm of `m`, at least its largest singular value.
fn frobenius(m: &DMat3) -> f64 {
    m.to_cols_array().iter().map(|v| v * v).sum::<f64>().sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn rotation_y(degrees: f64) -> DMat4 {
        DMat4::from_rotation_y(degrees.to_radians())
    }

    #[test]
    fn keyframes_are_reproduced_and_held_outside() {
        let m0 = DMat4::from_translation(DVec3::new(1.0, 2.0, 3.0))
            * rotation_y(20.0)
            * DMat4::from_scale(DVec3::new(2.0, 0.5, 1.0));
        let m1 = DMat4::from_translation(DVec3::new(-4.0, 0.0, 1.0))
            * DMat4::from_axis_angle(DVec3::new(1.0, 1.0, 0.0).normalize(), 1.0)
            * DMat4::from_scale(DVec3::new(-1.0, 3.0, 2.0));
        let animation = AnimatedTransform::new(&[(0.0, m0), (2.0, m1)]).unwrap();
        for (time, expected) in [(-1.0, m0), (0.0, m0), (2.0, m1), (5.0, m1)] {
            assert!(
                animation.at(time).abs_diff_eq(expected, 1e-12),
                "at {time}: {} against {expected}",
                animation.at(time)
            );
        }
    }

    #[test]
    fn rotation_is_slerped_and_translation_and_scale_lerped() {
        let m0 = DMat4::from_translation(DVec3::X) * DMat4::from_scale(DVec3::splat(1.0));
        let m1 = DMat4::from_translation(DVec3::new(3.0, 0.0, 0.0))
            * rotation_y(90.0)
            * DMat4::from_scale(DVec3::splat(3.0));
        let animation = AnimatedTransform::new(&[(0.0, m0), (1.0, m1)]).unwrap();
        let expected = DMat4::from_translation(DVec3::new(2.0, 0.0, 0.0))
            * rotation_y(45.0)
            * DMat4::from_scale(DVec3::splat(2.0));
        assert!(animation.at(0.5).abs_diff_eq(expected, 1e-12));
    }

    #[test]
    fn a_full_turn_in_three_segments_passes_half_a_turn_half_way() {
        let frames: Vec<(f64, DMat4)> = (0..4)
            .map(|i| (f64::from(i) / 3.0, rotation_y(120.0 * f64::from(i))))
            .collect();
        let animation = AnimatedTransform::new(&frames).unwrap();
        assert!(animation.at(0.5).abs_diff_eq(rotation_y(180.0), 1e-12));
        // The shorter arc is taken between keyframes whose quaternions have opposite signs.
        assert!(
            animation
                .at(5.0 / 6.0)
                .abs_diff_eq(rotation_y(300.0), 1e-12)
        );
    }

    #[test]
    fn bad_keyframes_are_refused() {
        let id = DMat4::IDENTITY;
        assert_eq!(
            AnimatedTransform::new(&[(0.0, id)]),
            Err(AnimationError::TooFewKeyframes)
        );
        assert_eq!(
            AnimatedTransform::new(&[(0.0, id), (0.0, id)]),
            Err(AnimationError::TimesNotIncreasing { index: 1 })
        );
        assert_eq!(
            AnimatedTransform::new(&[(1.0, id), (0.5, id)]),
            Err(AnimationError::TimesNotIncreasing { index: 1 })
        );
        let flat = DMat4::from_scale(DVec3::new(1.0, 0.0, 1.0));
        assert!(matches!(
            AnimatedTransform::new(&[(0.0, id), (1.0, flat)]),
            Err(AnimationError::NotDecomposable { index: 1, .. })
        ));
        let mut projective = id;
        projective.x_axis.w = 0.5;
        assert!(matches!(
            AnimatedTransform::new(&[(0.0, projective), (1.0, id)]),
            Err(AnimationError::NotDecomposable { index: 0, .. })
        ));
    }

    #[test]
    fn motion_bounds_hold_the_sweep() {
        let unit = Aabb {
            min: Vec3::splat(-1.0),
            max: Vec3::splat(1.0),
        };
        let offset = DMat4::from_translation(DVec3::new(5.0, 0.0, 0.0));
        let cases = [
            // A full turn about an axis away from the object, and a shear with a reflection.
            (0..4)
                .map(|i| (f64::from(i), rotation_y(120.0 * f64::from(i)) * offset))
                .collect::<Vec<_>>(),
            vec![
                (0.0, DMat4::from_scale(DVec3::new(-1.0, 2.0, 1.0))),
                (
                    1.0,
                    DMat4::from_translation(DVec3::splat(1e4)) * rotation_y(170.0),
                ),
            ],
            vec![
                (0.0, DMat4::IDENTITY),
                (1e-9, DMat4::from_translation(DVec3::new(0.0, 1e4, 0.0))),
            ],
        ];
        for frames in cases {
            let animation = AnimatedTransform::new(&frames).unwrap();
            let bounds = animation.motion_bounds(&unit);
            let (t0, t1) = animation.time_range();
            for i in 0..=1000 {
                let m = animation.at(t0 + (t1 - t0) * f64::from(i) / 1000.0);
                for c in 0..8 {
                    let corner = DVec3::new(
                        if c & 1 == 0 { -1.0 } else { 1.0 },
                        if c & 2 == 0 { -1.0 } else { 1.0 },
                        if c & 4 == 0 { -1.0 } else { 1.0 },
                    );
                    let p = m.transform_point3(corner).as_vec3();
                    assert!(
                        p.cmpge(bounds.min).all() && p.cmple(bounds.max).all(),
                        "{p} at step {i} outside {bounds:?} for {frames:?}"
                    );
                }
            }
        }
    }
}
