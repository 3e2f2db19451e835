//! Limits on what a scene may ask for, so that a hostile or mistyped file is refused with a clear
//! error instead of exhausting memory or rendering for ever.

/// Most pixels a film may have (width × height): 2²⁵, e.g. 8192 × 4096 or 8K UHD. The renderer
/// keeps about 56 bytes of sums per pixel, so this bounds the film to about 1.9 GB.
pub const MAX_FILM_PIXELS: u64 = 1 << 25;

/// Most samples per pixel a sampler may ask for: 2²⁴ (about 16.8 million).
pub const MAX_SAMPLE_COUNT: u32 = 1 << 24;
