//! BSDFs for Strata, each following the Mitsuba 3 plugin of the same name.
//!
//! # Conventions
//! - Everything works in the **local shading frame**: +z is the shading normal.
//! - `wo` and `wi` both point **away** from the surface. `wo` is the direction towards the
//!   camera (where the path came from), `wi` the direction the path continues in (towards
//!   the light). In Mitsuba's names, `wo` here is `si.wi` and `wi` here is `bs.wo`.
//! - [`Bsdf::eval`] returns the BSDF value f(wo, wi) per steradian, in RGB, **without** the
//!   cosine factor; the estimator weight of a sample is `f · |cos θi| / pdf`.
//! - Transport is radiance transport (paths start at the camera): refraction scales
//!   radiance by 1/η² as Mitsuba does in `TransportMode::Radiance`.
//! - Delta lobes (mirrors, smooth glass) are invisible to [`Bsdf::eval`] and
//!   [`Bsdf::pdf_solid_angle`] (both give 0) and are reached only through [`Bsdf::sample`];
//!   see [`BsdfSample`] for what `f` and `pdf_solid_angle` then mean.
//!
//! # Example
//! ```
//! use glam::{Vec2, Vec3};
//! use materials::{Bsdf, Diffuse};
//!
//! let bsdf = Bsdf::from(Diffuse::new(Vec3::splat(0.5)));
//! let wo = Vec3::new(0.0, 0.6, 0.8);
//! let s = bsdf.sample(wo, 0.3, Vec2::new(0.25, 0.75)).expect("upper hemisphere");
//! let weight = s.f * s.wi.z.abs() / s.pdf_solid_angle;
//! assert!((weight - Vec3::splat(0.5)).abs().max_element() < 1e-5);
//! ```

#![warn(missing_docs)]

mod bitmap;
mod blend;
mod bsdf;
mod bump_map;
mod conductor;
mod dielectric;
mod diffuse;
mod error;
mod flags;
pub mod fresnel;
pub mod microfacet;
mod normal_map;
mod perturbed;
mod plastic;
mod quadrature;
mod rough_conductor;
mod rough_dielectric;
mod rough_plastic;
mod special;
mod thin_dielectric;
mod two_sided;

pub use bitmap::{BitmapTexture, TextureFilter, TextureWrap};
pub use blend::Blend;
pub use bsdf::{Bsdf, BsdfSample, DeltaLobes};
pub use bump_map::BumpMap;
pub use conductor::Conductor;
pub use dielectric::Dielectric;
pub use diffuse::Diffuse;
pub use error::MaterialError;
pub use flags::BsdfFlags;
pub use fresnel::ComplexIor;
pub use microfacet::{Microfacet, MicrofacetKind};
pub use normal_map::NormalMap;
pub use perturbed::{AdapterOptions, SurfacePoint};
pub use plastic::Plastic;
pub use rough_conductor::{LOBE_WEIGHT_FLOOR, RoughConductor};
pub use rough_dielectric::RoughDielectric;
pub use rough_plastic::RoughPlastic;
pub use thin_dielectric::ThinDielectric;
pub use two_sided::TwoSided;
