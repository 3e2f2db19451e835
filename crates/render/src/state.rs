//! Saved render state (`strata render --state PATH`, continued by `--resume PATH`): the film's
//! per-pixel sums, the samples done, and what they were rendered with.
//!
//! The file is one line of JSON (a [`StateHeader`]) and a newline, followed by every pixel's
//! sums, row-major, top row first: `sum` r, g, b as little-endian `i128` fixed point
//! ([`crate::film::ExactSum`]), `sum_sq` r, g, b as little-endian `f64`, then `count` as a
//! little-endian `u32`, then the light paths' splat sums r, g, b and their squares' as
//! little-endian `i128` fixed point ([`PIXEL_BYTES`] bytes per pixel). When the film splats
//! camera samples ([`StateHeader::filtered`]), every pixel's [`crate::film::FilteredSum`]
//! follows, row-major: its sum and sum of squares r, g, b and its two weight sums, all as
//! little-endian `i128` fixed point ([`FILTERED_BYTES`] bytes per pixel). Resuming adds new
//! samples and splats to exactly these sums, so a render stopped and resumed any number of times
//! gives the same bits as one uninterrupted render.

use std::io::{BufRead, BufReader, Read};
use std::path::Path;

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::atomic_write::{WriteError, write_bytes_atomically};
use crate::driver::{NonFiniteCounts, ResumePoint};
use crate::film::{ExactSum, Film, FilteredSum, PixelSum, Splats};

/// What identifies the state format in [`StateHeader::format`].
pub const FORMAT: &str = "strata-render-state";

/// The state format's version in [`StateHeader::version`].
pub const VERSION: u32 = 3;

/// Bytes per pixel after the header: the exact sum (three `i128`), the sum of squares (three
/// `f64`) and a `u32` count, then the light paths' exact splat sums (three `i128`) and sums of
/// squares (three `i128`).
pub const PIXEL_BYTES: usize = SPLATS_OFFSET + 6 * 16;

/// Bytes per pixel of the splatted camera samples, when there are any: sum and sum of squares
/// (three `i128` each) and the two weight sums (`i128`).
pub const FILTERED_BYTES: usize = 8 * 16;

/// Where in a pixel's bytes its splat sums start.
const SPLATS_OFFSET: usize = 3 * 16 + 3 * 8 + 4;

/// Longest header line accepted when reading, bytes.
const MAX_HEADER_BYTES: usize = 1 << 16;

/// The JSON line that opens a state file.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct StateHeader {
    /// Always [`FORMAT`].
    pub format: String,
    /// Always [`VERSION`].
    pub version: u32,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Samples per pixel in the sums (the next sample index of every pixel).
    pub spp: u32,
    /// Passes those samples took.
    pub passes: u32,
    /// Samples left out as NaN.
    pub nan_count: u64,
    /// Samples left out as infinite.
    pub inf_count: u64,
    /// Light paths traced into the film (one per [`integrators::LightTracing::samples_per_path`]
    /// pixel samples with light tracing, else 0).
    pub light_paths: u64,
    /// Whether the film splats camera samples (a filter wider than a pixel), so that its
    /// splatted sums follow the pixel sums. Absent (false) in files written before splatting
    /// existed, whose layout is that of a film without splatted sums.
    #[serde(default)]
    pub filtered: bool,
    /// Sample count the sampler's pattern is laid out for; a resumed render keeps it.
    pub sampler_spp: u32,
    /// [`crate::fingerprint::scene_fingerprint`] of the scene: its content, including the mesh
    /// files it reads.
    pub scene_hash: String,
    /// The render settings that decide every sample's value (transport, sampler, seed, film
    /// size and filter), in a readable form; a resumed render must have the same.
    pub settings: String,
}

/// A render's saved state: its header and its film.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderState {
    /// Counts and settings.
    pub header: StateHeader,
    /// The per-pixel sums.
    pub film: Film,
}

impl RenderState {
    /// The point a resumed render continues from.
    pub fn resume_point(&self) -> ResumePoint {
        ResumePoint {
            film: self.film.clone(),
            spp: self.header.spp,
            passes: self.header.passes,
            non_finite: NonFiniteCounts {
                nan: self.header.nan_count,
                inf: self.header.inf_count,
            },
        }
    }

    /// The file's bytes: header line, newline, pixel sums.
    pub fn to_bytes(&self) -> Vec<u8> {
        // A struct of numbers and strings always serialises.
        let mut bytes = serde_json::to_vec(&self.header).expect("StateHeader serialises to JSON");
        bytes.push(b'\n');
        bytes.reserve(self.film.pixels().len() * PIXEL_BYTES);
        let (splat_sums, splat_sums_sq) = self.film.splat_sums();
        for ((pixel, splat_sum), splat_sum_sq) in
            self.film.pixels().iter().zip(splat_sums).zip(splat_sums_sq)
        {
            for v in pixel.sum.0 {
                bytes.extend_from_slice(&v.to_le_bytes());
            }
            for v in pixel.sum_sq.to_array() {
                bytes.extend_from_slice(&v.to_le_bytes());
            }
            bytes.extend_from_slice(&pixel.count.to_le_bytes());
            for v in splat_sum.0.into_iter().chain(splat_sum_sq.0) {
                bytes.extend_from_slice(&v.to_le_bytes());
            }
        }
        for sums in self.film.filtered().unwrap_or_default() {
            for v in sums
                .sum
                .0
                .into_iter()
                .chain(sums.sum_sq.0)
                .chain(sums.weight)
            {
                bytes.extend_from_slice(&v.to_le_bytes());
            }
        }
        bytes
    }

    /// Writes the state to `path` atomically: a reader sees the old file or the whole new one.
    pub fn write(&self, path: &Path) -> Result<(), WriteError> {
        write_bytes_atomically(path, &self.to_bytes())
    }

    /// Parses a state file's bytes. The pixel data must have exactly the size the header's width
    /// and height call for, which is checked before anything is allocated for it.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, String> {
        let end = bytes
            .iter()
            .take(MAX_HEADER_BYTES)
            .position(|&b| b == b'\n')
            .ok_or("not a Strata render state (no header line)")?;
        let header = parse_header(&bytes[..end])?;
        decode(header, &bytes[end + 1..])
    }

    /// Reads the state file at `path`, reading no more than its header says it holds; errors
    /// name the file.
    pub fn read(path: &Path) -> Result<Self, String> {
        let named = |e: String| format!("render state '{}': {e}", path.display());
        let file = std::fs::File::open(path)
            .map_err(|e| format!("cannot read render state '{}': {e}", path.display()))?;
        let mut reader = BufReader::new(file);
        let mut line = Vec::new();
        (&mut reader)
            .take(MAX_HEADER_BYTES as u64)
            .read_until(b'\n', &mut line)
            .map_err(|e| named(e.to_string()))?;
        if line.pop() != Some(b'\n') {
            return Err(named(
                "not a Strata render state (no header line)".to_string(),
            ));
        }
        let header = parse_header(&line).map_err(named)?;
        let mut data = Vec::new();
        reader
            .take(data_bytes(&header) as u64 + 1)
            .read_to_end(&mut data)
            .map_err(|e| named(e.to_string()))?;
        decode(header, &data).map_err(named)
    }
}

/// Parses and checks the header line (without its newline).
fn parse_header(line: &[u8]) -> Result<StateHeader, String> {
    let header: StateHeader = serde_json::from_slice(line)
        .map_err(|e| format!("not a Strata render state (bad header: {e})"))?;
    if header.format != FORMAT || header.version != VERSION {
        return Err(format!(
            "not a Strata render state of version {VERSION} (format \"{}\", version {})",
            header.format, header.version
        ));
    }
    let pixels = u64::from(header.width) * u64::from(header.height);
    if pixels == 0 || pixels > scene::limits::MAX_FILM_PIXELS {
        return Err(format!(
            "a {}x{} image is outside the supported sizes",
            header.width, header.height
        ));
    }
    Ok(header)
}

/// Bytes of pixel sums a checked `header` calls for.
fn data_bytes(header: &StateHeader) -> usize {
    let per_pixel = PIXEL_BYTES + if header.filtered { FILTERED_BYTES } else { 0 };
    header.width as usize * header.height as usize * per_pixel
}

/// The state of `header` with the pixel sums in `data`, which must have exactly their size.
fn decode(header: StateHeader, data: &[u8]) -> Result<RenderState, String> {
    let expected = data_bytes(&header);
    if data.len() != expected {
        return Err(format!(
            "truncated or corrupt: {} bytes of pixel sums where a {}x{} image needs {expected}",
            data.len(),
            header.width,
            header.height
        ));
    }
    let count = header.width as usize * header.height as usize;
    let (data, filtered_data) = data.split_at(count * PIXEL_BYTES);
    let mut pixels = Vec::with_capacity(count);
    let mut splats = Splats {
        sums: Vec::with_capacity(count),
        sums_sq: Vec::with_capacity(count),
        light_paths: header.light_paths,
    };
    for bytes in data.chunks_exact(PIXEL_BYTES) {
        pixels.push(read_pixel(bytes));
        splats.sums.push(read_exact(&bytes[SPLATS_OFFSET..]));
        splats
            .sums_sq
            .push(read_exact(&bytes[SPLATS_OFFSET + 48..]));
    }
    let filtered = filtered_data
        .chunks_exact(FILTERED_BYTES)
        .map(|bytes| {
            let weight = |i: usize| {
                let mut b = [0u8; 16];
                b.copy_from_slice(&bytes[96 + 16 * i..112 + 16 * i]);
                i128::from_le_bytes(b)
            };
            FilteredSum {
                sum: read_exact(bytes),
                sum_sq: read_exact(&bytes[48..]),
                weight: [weight(0), weight(1)],
            }
        })
        .collect();
    let film = Film::from_parts(header.width, header.height, pixels, splats)
        .and_then(|film| film.with_filtered(filtered))
        .ok_or("pixel count does not match the size")?;
    Ok(RenderState { header, film })
}

/// An exact sum from the first 48 of `bytes` (three little-endian `i128`).
fn read_exact(bytes: &[u8]) -> ExactSum {
    ExactSum([0, 1, 2].map(|c| {
        let mut b = [0u8; 16];
        b.copy_from_slice(&bytes[16 * c..16 * c + 16]);
        i128::from_le_bytes(b)
    }))
}

/// One pixel's sample sums from the first [`SPLATS_OFFSET`] of its [`PIXEL_BYTES`] bytes.
fn read_pixel(bytes: &[u8]) -> PixelSum {
    let f = |i: usize| {
        let start = 48 + 8 * i;
        let mut b = [0u8; 8];
        b.copy_from_slice(&bytes[start..start + 8]);
        f64::from_le_bytes(b)
    };
    let mut count = [0u8; 4];
    count.copy_from_slice(&bytes[72..76]);
    PixelSum {
        sum: read_exact(bytes),
        sum_sq: DVec3::new(f(0), f(1), f(2)),
        count: u32::from_le_bytes(count),
    }
}

#[cfg(test)]
mod tests {
    use glam::{UVec2, Vec3};

    use super::*;

    fn state() -> RenderState {
        let mut film = Film::new(3, 2);
        film.add(UVec2::new(1, 0), Vec3::new(0.1, 2.5, 1e-30));
        film.add(UVec2::new(1, 0), Vec3::new(3.0, -0.0, 7.0));
        film.add(UVec2::new(2, 1), Vec3::splat(1.0 / 3.0));
        film.add_splat(UVec2::new(0, 1), Vec3::new(0.25, 1e-9, 3e4));
        film.add_light_paths(6);
        RenderState {
            header: StateHeader {
                format: FORMAT.to_string(),
                version: VERSION,
                width: 3,
                height: 2,
                spp: 2,
                passes: 2,
                nan_count: 1,
                inf_count: 0,
                light_paths: 6,
                filtered: false,
                sampler_spp: 16,
                scene_hash: "0123456789abcdef".to_string(),
                settings: "mis".to_string(),
            },
            film,
        }
    }

    #[test]
    fn round_trips_every_bit() {
        let state = state();
        assert_eq!(RenderState::from_bytes(&state.to_bytes()).unwrap(), state);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("s.state");
        state.write(&path).unwrap();
        assert_eq!(RenderState::read(&path).unwrap(), state);
    }

    #[test]
    fn splatted_sums_round_trip_every_bit() {
        let mut state = state();
        let mut sums = FilteredSum::default();
        sums.add(Vec3::new(0.1, 2.5, 1e-30), 0.3, 0.123);
        sums.add(Vec3::new(-4.0, 1e5, 7.0), -0.01, 1e-9);
        let mut filtered = vec![FilteredSum::default(); 6];
        filtered[4] = sums;
        state.film = state.film.with_filtered(filtered).unwrap();
        state.header.filtered = true;
        let bytes = state.to_bytes();
        assert_eq!(RenderState::from_bytes(&bytes).unwrap(), state);
        let truncated = RenderState::from_bytes(&bytes[..bytes.len() - 1]).unwrap_err();
        assert!(truncated.contains("truncated"), "{truncated}");
    }

    #[test]
    fn corrupt_files_are_refused_without_allocating() {
        let bytes = state().to_bytes();
        let truncated = RenderState::from_bytes(&bytes[..bytes.len() - 1]).unwrap_err();
        assert!(truncated.contains("truncated"), "{truncated}");
        assert!(RenderState::from_bytes(b"garbage").is_err());
        assert!(RenderState::from_bytes(b"{}\n").is_err());
        let huge = String::from_utf8_lossy(&bytes)
            .replacen("\"width\":3", "\"width\":4000000000", 1)
            .into_bytes();
        let message = RenderState::from_bytes(&huge).unwrap_err();
        assert!(message.contains("outside the supported"), "{message}");
        let other = String::from_utf8_lossy(&bytes)
            .replacen(FORMAT, "something-else", 1)
            .into_bytes();
        assert!(RenderState::from_bytes(&other).is_err());
        let missing = RenderState::read(Path::new("/nonexistent/x.state")).unwrap_err();
        assert!(missing.contains("x.state"), "{missing}");
    }
}
