//! A ray from the camera with the distance it may travel before the far clipping plane.

use geometry::Ray;

/// A camera ray: it starts on the near clipping plane and sees only surfaces closer than
/// `t_max` (world units along `ray.dir`), the far clipping plane; past it lies the environment,
/// as in Mitsuba's sensors. Rays after the first bounce are unbounded.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraRay {
    /// The ray, unit direction.
    pub ray: Ray,
    /// Distance along the ray to the far clipping plane (world units; may be infinite).
    pub t_max: f32,
}

impl CameraRay {
    /// A camera ray that is not clipped.
    pub fn unbounded(ray: Ray) -> Self {
        Self {
            ray,
            t_max: f32::INFINITY,
        }
    }
}
