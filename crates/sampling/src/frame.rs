//! Orthonormal frames for moving directions between world and local (z-up) coordinates.

use glam::Vec3;

/// An orthonormal basis whose third axis is a given unit normal; local coordinates are z-up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// First tangent.
    pub s: Vec3,
    /// Second tangent, `n × s`.
    pub t: Vec3,
    /// The normal: the local +z axis.
    pub n: Vec3,
}

impl Frame {
    /// A frame around the unit vector `n`, built without branches on near-zero components
    /// (Duff et al. 2017, "Building an Orthonormal Basis, Revisited").
    #[inline]
    pub fn from_normal(n: Vec3) -> Self {
        let sign = 1.0_f32.copysign(n.z);
        let a = -1.0 / (sign + n.z);
        let b = n.x * n.y * a;
        let s = Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
        let t = Vec3::new(b, sign + n.y * n.y * a, -n.y);
        Self { s, t, n }
    }

    /// The frame around the unit normal `n` whose first tangent is `dp_du` made perpendicular to
    /// `n` (Gram–Schmidt) and normalised, as Mitsuba builds its shading frame from ∂p/∂u; the
    /// frame of [`Self::from_normal`] when `dp_du` is zero, not finite or parallel to `n` (within
    /// 10⁻⁵ of its length).
    pub fn from_normal_and_tangent(n: Vec3, dp_du: Vec3) -> Self {
        let s = dp_du - n * n.dot(dp_du);
        // Parallel within rounding: what is left is noise, not a direction.
        if !s.is_finite() || s.length_squared() <= 1e-10 * dp_du.length_squared() {
            return Self::from_normal(n);
        }
        let s = s.normalize();
        Self {
            s,
            t: n.cross(s),
            n,
        }
    }

    /// The frame mirrored through its tangent plane: the same tangents and the opposite normal
    /// (left-handed). A vector's local coordinates in it are those in `self` with z negated,
    /// exactly.
    #[inline]
    pub fn mirrored(&self) -> Self {
        Self {
            s: self.s,
            t: self.t,
            n: -self.n,
        }
    }

    /// Expresses the world-space vector `v` in this frame.
    #[inline]
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.s), v.dot(self.t), v.dot(self.n))
    }

    /// Expresses the local vector `v` in world space.
    #[inline]
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.s * v.x + self.t * v.y + self.n * v.z
    }
}
