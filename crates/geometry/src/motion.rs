//! Motion during the shutter: where a moving shape is at the time a ray is traced.
//!
//! A ray's time ([`crate::Ray::time`]) is a fraction of the shutter interval, 0 when the shutter
//! opens and 1 when it closes, so that a camera sample draws it uniformly from [0, 1) like any
//! other sampler dimension. [`Motion`] turns it into scene time, `open + time · (close − open)`
//! in double precision (a shutter of 1e-9 at time 1e3 still resolves), and evaluates the shape's
//! [`AnimatedTransform`] there. The resulting [`Placement`] carries a moving shape's geometry,
//! stored in object space, to world space and back: rays go to object space, hits and light
//! samples come back, their error bounds grown by what the transform can add.

use glam::{DMat3, DMat4, Vec3};

use crate::{Aabb, AnimatedTransform};

/// A shape's object-to-world transform over the shutter interval.
#[derive(Clone, Debug, PartialEq)]
pub struct Motion {
    transform: AnimatedTransform,
    open: f64,
    duration: f64,
}

impl Motion {
    /// The motion `transform` describes (in scene time) seen through a shutter open from
    /// `shutter[0]` to `shutter[1]` (scene time, `shutter[0] ≤ shutter[1]`). A shutter that
    /// opens and closes at once sees the shape where it is at that time.
    pub fn new(transform: AnimatedTransform, shutter: [f64; 2]) -> Self {
        Self {
            transform,
            open: shutter[0],
            duration: (shutter[1] - shutter[0]).max(0.0),
        }
    }

    /// Whether the shape can be seen in more than one place: the shutter stays open for a
    /// while and the transform changes during it.
    pub fn moves(&self) -> bool {
        let (first, last) = self.transform.time_range();
        self.duration > 0.0 && first < self.open + self.duration && last > self.open
    }

    /// The scene time of the ray time `time` (a fraction of the shutter interval).
    #[inline]
    pub fn scene_time(&self, time: f32) -> f64 {
        self.open + self.duration * f64::from(time)
    }

    /// Where the shape is at ray time `time` (a fraction of the shutter interval).
    #[inline]
    pub fn at(&self, time: f32) -> Placement {
        Placement::new(self.transform.at(self.scene_time(time)))
    }

    /// A box (world units) holding the object-space `bounds` at every time of the shutter.
    pub fn bounds(&self, bounds: &Aabb) -> Aabb {
        self.transform.motion_bounds(bounds)
    }
}

/// Relative rounding of one `f32` result (half an ulp, doubled for safety).
const F32_ROUNDING: f32 = f32::EPSILON;

/// A moving shape's transform at one time: object space to world space and back, in double
/// precision.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    to_world: DMat4,
    to_object: DMat4,
    /// The absolute values of the linear part of `to_world`, for error bounds.
    abs_linear: DMat3,
    /// |det L| of the linear part `L` of `to_world`.
    det: f64,
}

impl Placement {
    /// The placement of the object-to-world matrix `to_world` (affine and invertible).
    pub fn new(to_world: DMat4) -> Self {
        let linear = DMat3::from_mat4(to_world);
        Self {
            to_world,
            to_object: to_world.inverse(),
            abs_linear: DMat3::from_cols(
                linear.x_axis.abs(),
                linear.y_axis.abs(),
                linear.z_axis.abs(),
            ),
            det: linear.determinant().abs(),
        }
    }

    /// The object-to-world matrix.
    #[inline]
    pub fn to_world(&self) -> DMat4 {
        self.to_world
    }

    /// The object-space point `p` in world space.
    #[inline]
    pub fn point_to_world(&self, p: Vec3) -> Vec3 {
        self.to_world.transform_point3(p.as_dvec3()).as_vec3()
    }

    /// The world-space point `p` in object space.
    #[inline]
    pub fn point_to_object(&self, p: Vec3) -> Vec3 {
        self.to_object.transform_point3(p.as_dvec3()).as_vec3()
    }

    /// The object-space vector `v` in world space (not normalised).
    #[inline]
    pub fn vector_to_world(&self, v: Vec3) -> Vec3 {
        self.to_world.transform_vector3(v.as_dvec3()).as_vec3()
    }

    /// The world-space vector `v` in object space (not normalised).
    #[inline]
    pub fn vector_to_object(&self, v: Vec3) -> Vec3 {
        self.to_object.transform_vector3(v.as_dvec3()).as_vec3()
    }

    /// The object-space unit normal `n` in world space (by the inverse transpose), unit length.
    #[inline]
    pub fn normal_to_world(&self, n: Vec3) -> Vec3 {
        let m = DMat3::from_mat4(self.to_object).transpose();
        (m * n.as_dvec3()).normalize_or_zero().as_vec3()
    }

    /// The world-space unit normal `n` in object space, unit length.
    #[inline]
    pub fn normal_to_object(&self, n: Vec3) -> Vec3 {
        let m = DMat3::from_mat4(self.to_world).transpose();
        (m * n.as_dvec3()).normalize_or_zero().as_vec3()
    }

    /// How much the transform stretches area at a surface point with world-space unit normal
    /// `n`: dA_world / dA_object = |det L| / |Lᵀ n| (Nanson's formula, `L` the linear part).
    #[inline]
    pub fn area_scale(&self, n: Vec3) -> f32 {
        let m = DMat3::from_mat4(self.to_world).transpose();
        (self.det / (m * n.as_dvec3()).length()) as f32
    }

    /// How much the transform stretches volume, |det L| (`L` its linear part).
    #[inline]
    pub fn volume_scale(&self) -> f32 {
        self.det as f32
    }

    /// A bound (world units, per coordinate) on the error of `p_world`, the rounded world
    /// image of the object-space point `p` whose coordinates are within `p_error` of the
    /// surface: the error carried through the linear part, the rounding of the object-space
    /// point's own coordinates carried likewise (the object-space ray it came from was
    /// rounded too), and the rounding of the result.
    #[inline]
    pub fn error_to_world(&self, p: Vec3, p_error: Vec3, p_world: Vec3) -> Vec3 {
        let object = p_error + F32_ROUNDING * p.abs();
        let carried = (self.abs_linear * object.as_dvec3()).as_vec3();
        2.0 * carried + F32_ROUNDING * p_world.abs()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DQuat, DVec3};

    fn spinning() -> Motion {
        let keyframes = [
            (0.0, DMat4::from_translation(DVec3::new(1.0, 0.0, 0.0))),
            (
                1.0,
                DMat4::from_scale_rotation_translation(
                    DVec3::splat(2.0),
                    DQuat::from_rotation_y(1.0),
                    DVec3::new(1.0, 2.0, 0.0),
                ),
            ),
        ];
        Motion::new(
            AnimatedTransform::new(&keyframes).expect("valid keyframes"),
            [0.0, 1.0],
        )
    }

    #[test]
    fn points_normals_and_vectors_go_there_and_back() {
        let placement = spinning().at(0.37);
        let p = Vec3::new(0.3, -1.2, 2.5);
        let back = placement.point_to_object(placement.point_to_world(p));
        assert!(back.abs_diff_eq(p, 1e-5), "{back:?}");
        let n = Vec3::new(0.0, 0.6, 0.8);
        let t = Vec3::new(1.0, 0.0, 0.0); // a tangent of n
        let (n_w, t_w) = (placement.normal_to_world(n), placement.vector_to_world(t));
        assert!(n_w.dot(t_w).abs() < 1e-5, "the normal stays normal");
        assert!((n_w.length() - 1.0).abs() < 1e-6);
        assert!(placement.normal_to_object(n_w).abs_diff_eq(n, 1e-5));
    }

    #[test]
    fn area_scale_is_the_ratio_of_a_parallelograms_areas() {
        // A stretch along x only: a face normal to y grows by sx · sz, one normal to x by sy · sz.
        let m = DMat4::from_scale(DVec3::new(3.0, 0.5, 2.0));
        let placement = Placement::new(m);
        assert!((placement.area_scale(Vec3::Y) - 6.0).abs() < 1e-5);
        assert!((placement.area_scale(Vec3::X) - 1.0).abs() < 1e-5);
        let spun = spinning().at(0.8);
        let (a, b) = (Vec3::new(0.2, 0.0, 0.1), Vec3::new(0.0, 0.3, -0.1));
        let ratio = spun
            .vector_to_world(a)
            .cross(spun.vector_to_world(b))
            .length()
            / a.cross(b).length();
        let n = spun.normal_to_world(a.cross(b).normalize());
        assert!((spun.area_scale(n) - ratio).abs() < 1e-4 * ratio);
    }

    #[test]
    fn ray_times_span_the_shutter_in_double_precision() {
        let keyframes = [
            (1e3, DMat4::IDENTITY),
            (1e3 + 1e-9, DMat4::from_translation(DVec3::X)),
        ];
        let motion = Motion::new(
            AnimatedTransform::new(&keyframes).expect("valid keyframes"),
            [1e3, 1e3 + 1e-9],
        );
        assert!(motion.moves());
        let halfway = motion.at(0.5).point_to_world(Vec3::ZERO);
        assert!((halfway.x - 0.5).abs() < 1e-3, "{halfway:?}");
        let closed = Motion::new(
            AnimatedTransform::new(&keyframes).expect("valid keyframes"),
            [1e3, 1e3],
        );
        assert!(!closed.moves(), "a closed shutter sees one time");
        let before = Motion::new(
            AnimatedTransform::new(&keyframes).expect("valid keyframes"),
            [0.0, 1.0],
        );
        assert!(
            !before.moves(),
            "the shutter closes before the motion starts"
        );
    }
}
