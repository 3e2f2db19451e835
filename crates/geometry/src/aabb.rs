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
}
