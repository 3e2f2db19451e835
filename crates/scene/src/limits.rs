//! Limits on what a scene may ask for, so that a hostile or mistyped file is refused with a clear
//! error instead of exhausting memory or rendering for ever.

/// Most pixels a film may have (width × height): 2²⁵, e.g. 8192 × 4096 or 8K UHD. The renderer
/// keeps about 56 bytes of sums per pixel, so this bounds the film to about 1.9 GB.
pub const MAX_FILM_PIXELS: u64 = 1 << 25;

/// Most samples per pixel a sampler may ask for: 2²⁴ (about 16.8 million).
pub const MAX_SAMPLE_COUNT: u32 = 1 << 24;

/// Most light or BSDF samples the `direct` integrator may take per camera sample: 2¹⁶.
pub const MAX_DIRECT_SAMPLES: i64 = 1 << 16;

/// Most lobes a `lanczos` reconstruction filter may have (its radius in pixels is the count).
pub const MAX_LANCZOS_LOBES: u32 = 16;

/// Longest scene (or included) XML file read, bytes: 64 MiB. Reading stops there, so naming a
/// device such as `/dev/zero` as the scene cannot exhaust memory.
pub const MAX_SCENE_FILE_BYTES: u64 = 64 << 20;

/// Reads at most `limit` bytes of the file at `path`; an error if it holds more.
pub(crate) fn read_at_most(path: &std::path::Path, limit: u64) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let mut bytes = Vec::new();
    std::fs::File::open(path)?
        .take(limit + 1)
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("longer than {limit} bytes"),
        ));
    }
    Ok(bytes)
}
