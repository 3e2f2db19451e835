//! Errors for BSDF parameters that cannot describe a material.

use std::fmt;

/// A BSDF parameter that is out of range; the scene loader reports it with the element's location.
#[derive(Clone, Debug, PartialEq)]
pub enum MaterialError {
    /// An index of refraction that is not a finite positive number.
    InvalidIor {
        /// The parameter's Mitsuba name (`int_ior` or `ext_ior`).
        name: &'static str,
        /// The value given.
        value: f32,
    },
    /// A roughness that is NaN or infinite (finite values are clamped like Mitsuba's).
    InvalidRoughness {
        /// The value given.
        value: f32,
    },
    /// `twosided` around a BSDF that transmits light, which Mitsuba also rejects.
    TransmissiveTwoSided,
    /// A `blendbsdf` weight outside [0, 1].
    InvalidBlendWeight {
        /// The value given.
        value: f32,
    },
}

impl fmt::Display for MaterialError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidIor { name, value } => write!(
                f,
                "`{name}` must be a finite positive index of refraction, got {value}"
            ),
            Self::InvalidRoughness { value } => {
                write!(f, "`alpha` must be a finite number, got {value}")
            }
            Self::InvalidBlendWeight { value } => {
                write!(f, "`weight` must be in [0, 1], got {value}")
            }
            Self::TransmissiveTwoSided => write!(
                f,
                "`twosided` can only wrap a reflecting BSDF (diffuse, conductor, roughconductor, plastic), not a dielectric"
            ),
        }
    }
}

impl std::error::Error for MaterialError {}

/// The relative index `int_ior / ext_ior` of an interface, or [`MaterialError::InvalidIor`] naming
/// the first index that is not a finite positive number.
pub(crate) fn relative_ior(int_ior: f32, ext_ior: f32) -> Result<f32, MaterialError> {
    for (name, value) in [("int_ior", int_ior), ("ext_ior", ext_ior)] {
        if !(value.is_finite() && value > 0.0) {
            return Err(MaterialError::InvalidIor { name, value });
        }
    }
    Ok(int_ior / ext_ior)
}
