//! Warps: maps from the unit square to a domain, each as a triple of `sample_*` (u ↦ point),
//! `*_pdf` (density of that point in the domain's measure) and `invert_*` (point ↦ u).
//!
//! Directions are unit vectors in a local z-up frame; `u` is in [0, 1)², and inputs up to
//! 1 − ε give finite points on the domain.

mod cone;
mod disk;
mod hemisphere;
mod sphere;
mod triangle;
mod turn;

pub use cone::{invert_uniform_cone, sample_uniform_cone, uniform_cone_pdf};
pub use disk::{concentric_disk_pdf, invert_concentric_disk, sample_concentric_disk};
pub use hemisphere::{
    cosine_hemisphere_pdf, invert_cosine_hemisphere, invert_uniform_hemisphere,
    sample_cosine_hemisphere, sample_uniform_hemisphere, uniform_hemisphere_pdf,
};
pub use sphere::{invert_uniform_sphere, sample_uniform_sphere, uniform_sphere_pdf};
pub use triangle::{invert_uniform_triangle, sample_uniform_triangle, uniform_triangle_pdf};
pub use turn::sin_cos_turn;

use std::f32::consts::TAU;

/// The azimuth of (x, y) as a fraction of a full turn, in [0, 1).
#[inline]
pub(crate) fn azimuth_fraction(x: f32, y: f32) -> f32 {
    let fraction = y.atan2(x) / TAU;
    let wrapped = if fraction < 0.0 {
        fraction + 1.0
    } else {
        fraction
    };
    // `-tiny + 1.0` rounds to 1.0; keep the result inside [0, 1).
    if wrapped >= 1.0 { 0.0 } else { wrapped }
}

/// `sqrt` that treats tiny negative rounding error as zero.
#[inline]
pub(crate) fn safe_sqrt(x: f32) -> f32 {
    x.max(0.0).sqrt()
}
