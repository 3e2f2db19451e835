//! Axis-aligned bounding boxes.

use glam::Vec3;

/// An axis-aligned box in world units, `min` and `max` corners inclusive.
///
/// The empty box ([`Aabb::EMPTY`]) has `min = +inf` and `max = -inf`, so that growing it by any
/// point or box gives that point or box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Smallest corner.
    pub min: Vec3,
    /// Largest corner.
    pub max: Vec3,
}

impl Aabb {
    /// The empty box: contains nothing, and is the identity of [`Aabb::union`].
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::INFINITY,
        max: Vec3::NEG_INFINITY,
    };

    /// The box with corners `min` and `max` (not reordered).
    pub fn new(min: Vec3, max: Vec3) -> Self {
        Self { min, max }
    }

    /// The smallest box containing all `points` ([`Aabb::EMPTY`] for none).
    pub fn from_points(points: impl IntoIterator<Item = Vec3>) -> Self {
        points.into_iter().fold(Self::EMPTY, Self::grow)
    }

    /// The smallest box containing `self` and the point `p`.
    pub fn grow(self, p: Vec3) -> Self {
        Self {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// The smallest box containing both boxes.
    pub fn union(self, other: Aabb) -> Self {
        Self {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// True when the box contains no point (some `min` component exceeds its `max`).
    pub fn is_empty(&self) -> bool {
        self.min.cmpgt(self.max).any()
    }

    /// True when `p` lies inside the box or on its boundary.
    pub fn contains(&self, p: Vec3) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }

    /// Edge lengths `max - min` in world units (negative for the empty box).
    pub fn diagonal(&self) -> Vec3 {
        self.max - self.min
    }

    /// Centre point.
    pub fn center(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }

    /// Surface area in world units squared (zero for the empty box).
    pub fn surface_area(&self) -> f32 {
        if self.is_empty() {
            return 0.0;
        }
        let d = self.diagonal();
        2.0 * (d.x * d.y + d.y * d.z + d.z * d.x)
    }

    /// Whether the ray from `origin` along `dir` (any non-zero length) passes through the box
    /// for some `t` in [0, `t_max`]: the slab test, its far distances grown by 3 γ-units so
    /// that rounding never misses a box the exact ray enters (pbrt-v4's `IntersectP`).
    pub fn hit_by(&self, origin: Vec3, dir: Vec3, t_max: f32) -> bool {
        let inverse = dir.recip();
        let (a, b) = ((self.min - origin) * inverse, (self.max - origin) * inverse);
        // A zero direction coordinate gives ±∞ (or NaN at a slab face: then the slab is kept).
        let near = a.min(b);
        let far = a.max(b) * (1.0 + 2.0 * crate::gamma(3.0));
        let t0 = [near.x, near.y, near.z]
            .into_iter()
            .filter(|t| !t.is_nan())
            .fold(0.0f32, f32::max);
        let t1 = [far.x, far.y, far.z]
            .into_iter()
            .filter(|t| !t.is_nan())
            .fold(t_max, f32::min);
        t0 <= t1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_box_is_identity_of_union() {
        let b = Aabb::new(Vec3::new(-1.0, 0.0, 2.0), Vec3::new(1.0, 3.0, 4.0));
        assert_eq!(Aabb::EMPTY.union(b), b);
        assert!(Aabb::EMPTY.is_empty());
        assert!(!Aabb::EMPTY.contains(Vec3::ZERO));
        assert_eq!(Aabb::EMPTY.surface_area(), 0.0);
    }

    #[test]
    fn from_points_bounds_every_point() {
        let pts = [
            Vec3::new(1.0, -2.0, 0.5),
            Vec3::new(-3.0, 4.0, 0.0),
            Vec3::ONE,
        ];
        let b = Aabb::from_points(pts);
        assert_eq!(b.min, Vec3::new(-3.0, -2.0, 0.0));
        assert_eq!(b.max, Vec3::new(1.0, 4.0, 1.0));
        assert!(pts.iter().all(|&p| b.contains(p)));
        assert_eq!(b.surface_area(), 2.0 * (4.0 * 6.0 + 6.0 * 1.0 + 1.0 * 4.0));
    }

    #[test]
    fn hit_by_sees_rays_through_the_box_and_misses_the_others() {
        let b = Aabb::new(Vec3::new(-1.0, -1.0, 2.0), Vec3::new(1.0, 1.0, 4.0));
        assert!(b.hit_by(Vec3::ZERO, Vec3::Z, f32::INFINITY));
        assert!(
            !b.hit_by(Vec3::ZERO, Vec3::Z, 1.5),
            "stops short of the box"
        );
        assert!(
            !b.hit_by(Vec3::ZERO, Vec3::NEG_Z, f32::INFINITY),
            "behind the origin"
        );
        assert!(!b.hit_by(Vec3::new(2.0, 0.0, 0.0), Vec3::Z, f32::INFINITY));
        // Axis-parallel along a face, and from inside.
        assert!(b.hit_by(Vec3::new(1.0, 0.0, 0.0), Vec3::Z, f32::INFINITY));
        assert!(b.hit_by(Vec3::new(0.0, 0.0, 3.0), Vec3::X, 0.1));
        assert!(b.hit_by(Vec3::new(0.0, 0.0, 3.0), Vec3::new(0.0, 0.0, 5.0), 0.01));
    }
}
