//! Triangles, sampled uniformly by area.

use glam::{Vec2, Vec3};

/// Barycentric coordinates (b0, b1, b2) of a point uniform by area on any triangle:
/// b0 = 1 − √u.x, b1 = u.y √u.x, b2 = 1 − b0 − b1 (area-preserving).
#[inline]
pub fn sample_uniform_triangle(u: Vec2) -> Vec3 {
    let su = u.x.sqrt();
    let b0 = 1.0 - su;
    let b1 = u.y * su;
    Vec3::new(b0, b1, (1.0 - b0 - b1).max(0.0))
}

/// Density of [`sample_uniform_triangle`] per unit area on a triangle of the given area: 1 / area.
#[inline]
pub fn uniform_triangle_pdf(area: f32) -> f32 {
    1.0 / area
}

/// The `u` that [`sample_uniform_triangle`] maps to the barycentric coordinates `b`.
#[inline]
pub fn invert_uniform_triangle(b: Vec3) -> Vec2 {
    let su = (1.0 - b.x).clamp(0.0, 1.0);
    let v = if su > 0.0 {
        (b.y / su).clamp(0.0, 1.0)
    } else {
        0.0
    };
    Vec2::new(su * su, v)
}
