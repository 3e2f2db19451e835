//! Sampler dimensions a scene may not need: drawn only when it does.

use sampling::Sampler;

/// The sampler's next 1D number if `drawn`, otherwise 0.5 without drawing. For a number only
/// some scenes need (a light to choose among several, a lobe to choose for a dielectric): a
/// scene that does not need it neither pays for the dimension nor shifts the ones after it.
#[inline]
pub(crate) fn next_1d_if(sampler: &mut impl Sampler, drawn: bool) -> f32 {
    if drawn { sampler.next_1d() } else { 0.5 }
}
