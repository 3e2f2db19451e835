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
