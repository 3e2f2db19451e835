//! What the integrators need of a camera: the rays it sends ([`CameraRay`]) and how a point is
//! connected to it ([`CameraConnection`]). The camera itself is the scene's.

use geometry::Ray;
use glam::{Vec2, Vec3};

/// A camera ray: it starts on the near clipping plane and sees only surfaces closer than
/// `t_max` (world units along `ray.dir`), the far clipping plane; past it lies the environment,
/// as in Mitsuba's sensors. Rays after the first bounce are unbounded.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraRay {
    /// The ray, unit direction.
    pub ray: Ray,
    /// Distance along the ray to the far clipping plane (world units; may be infinite).
    pub t_max: f32,
    /// Density per steradian of the ray's direction among the rays of one camera sample in
    /// every pixel of the rendered image: 1 / (A cos³θ), as in [`CameraConnection::importance`]
    /// (sr⁻¹). Zero for a camera that light paths do not connect to (the orthographic one).
    pub pdf_dir: f32,
    /// The point of the aperture the ray passes through (world space; the pinhole without a
    /// lens), where [`Self::importance_at`] measures distances from.
    pub eye: Vec3,
}

impl CameraRay {
    /// A camera ray that is not clipped, from a camera that light paths do not connect to.
    #[inline]
    pub fn unbounded(ray: Ray) -> Self {
        Self {
            ray,
            t_max: f32::INFINITY,
            pdf_dir: 0.0,
            eye: ray.origin,
        }
    }

    /// The camera's importance at the point `p` on the ray, as [`CameraConnection::importance`]
    /// gives it for a light path reaching `p` through the same aperture point:
    /// 1 / (A cos³θ r²) (m⁻² sr⁻¹).
    #[inline]
    pub fn importance_at(&self, p: Vec3) -> f32 {
        self.pdf_dir / (p - self.eye).length_squared()
    }
}

/// Where a surface point appears to the camera (through one point of its aperture), and what a
/// path reaching it is worth there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraConnection {
    /// The film position the point projects to, in pixels ((0, 0) is the top-left corner).
    pub film: Vec2,
    /// Where the connecting shadow ray ends: the point of the camera's near plane on the line to
    /// the camera (world space), so that what the camera's rays cannot see does not block it.
    pub target: Vec3,
    /// The camera's importance W_e times |cos θ| at the camera over the squared distance, in
    /// units that make `weight · f · cos · importance` the point's contribution to one pixel
    /// sample: 1 / (A cos³θ r²), with A the area of the image plane at unit distance, r the
    /// distance to the aperture point and θ the angle off the view axis there.
    pub importance: f32,
}

/// What light paths need to know of the camera they connect to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CameraTraits {
    /// Whether each connection goes through a point of an aperture (a thin lens), which a light
    /// path then draws.
    pub has_lens: bool,
    /// Whether the camera moves while the shutter is open, so that light paths draw a time.
    pub moves: bool,
}
