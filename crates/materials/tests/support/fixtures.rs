//! BSDFs and directions shared by the test binaries.

use glam::Vec3;
use materials::{Bsdf, ComplexIor, Microfacet, MicrofacetKind, RoughConductor};

/// Roughness values the rough conductor is tested at: near-specular, medium, very rough.
pub const ALPHAS: [f32; 3] = [0.05, 0.3, 0.8];

/// Incidence angles in degrees: normal, oblique, grazing.
pub const INCIDENCE_DEGREES: [f32; 3] = [0.0, 45.0, 85.0];

/// A gold-like complex index of refraction (RGB), so the Fresnel term varies per channel.
pub fn gold() -> ComplexIor {
    ComplexIor::new(
        Vec3::new(0.143, 0.374, 1.442),
        Vec3::new(3.983, 2.385, 1.603),
    )
}

/// The unit direction at `degrees` from +z in the xz-plane (positive x), above the surface.
pub fn incidence(degrees: f32) -> Vec3 {
    let theta = degrees.to_radians();
    Vec3::new(theta.sin(), 0.0, theta.cos())
}

/// A rough conductor of `kind` and `alpha` with complex index `ior` and white specular reflectance.
pub fn rough_conductor(kind: MicrofacetKind, alpha: f32, ior: ComplexIor) -> Bsdf {
    let distribution = Microfacet::new(kind, alpha).expect("test roughness is finite");
    Bsdf::from(RoughConductor::new(distribution, ior, Vec3::ONE))
}
