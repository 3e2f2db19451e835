//! The EXR that `strata render` and `strata merge` write: the image for viewers, plus what
//! `strata merge` needs to add renders exactly and to refuse what does not belong together.
//!
//! # Layout
//!
//! One part, scan lines top row first, RLE-compressed: the low limbs of the exact sums below
//! are as good as random, which deflate (ZIP) spends most of its time failing to compress (a
//! 1920 × 1080 render took 8 s to write); run-length coding takes a seventh of the time for a
//! file a quarter larger, and still folds the limbs that are zero.
//!
//! - `R`, `G`, `B` (float32): the image, as [`crate::image::Image::write_exr`] writes it.
//! - `strata.count` (uint): per pixel, the samples in its sums (finite samples only).
//! - `strata.sum.R0` … `strata.sum.R3`, and the same for `G` and `B` (uint): per pixel and
//!   channel, the exact sum of its samples ([`ExactSum`], an `i128` in fixed point with
//!   [`crate::film::EXACT_FRACTION_BITS`] fractional bits), split into four 32-bit limbs, `0`
//!   the least significant (two's complement).
//! - `strata.splat.R0` … `strata.splat.B3` (uint), only when light paths were traced: the exact
//!   sums of the light paths' splats, in the same form.
//! - `strata.filtered.R0` … `strata.filtered.B3` and `strata.filtered.W0` … `strata.filtered.W3`
//!   (uint), only when camera samples were splatted by a filter wider than a pixel: per pixel
//!   the exact sums of the splatted samples and of their expected weights
//!   ([`crate::film::FilteredSum`]), in the same form. The sample sums above then hold each
//!   pixel's own samples, unweighted.
//!
//! And two header attributes:
//!
//! - `spp` (int): samples per pixel behind the image (over all the sample ranges below).
//! - `strata` (string): lines of `key: value`, in this order:
//!   - `format: strata-film 1` ([`FORMAT`]);
//!   - `scene:` the scene's fingerprint ([`crate::fingerprint::scene_fingerprint`]: its content
//!     with every included file, mesh and texture it reads);
//!   - `settings:` everything besides the scene and seed that decides the value of sample `i` of
//!     a pixel ([`render_settings`]: Strata's version, image size and filter, light transport
//!     with all its switches, sampler kind and, for the samplers whose numbers depend on it, the
//!     sample count their pattern is laid out for, adaptive sampling on or off);
//!   - `samples:` the sample indices in the sums, by sampler seed, as half-open ranges
//!     ([`SampleRanges`], e.g. `seed 7: 0..16 32..48; seed 9: 0..64`);
//!   - `light_paths:` how many light paths were traced into the splat sums.
//!
//! The image size is the EXR's own (its data window) and is part of the settings too.
//!
//! The two attributes sit in the layer's and in the image's attribute maps, one each: the EXR
//! writer orders each map's entries by a per-process random hash, so a second attribute in
//! either would make two runs' files differ in their bytes.

use std::collections::BTreeMap;
use std::fmt;
use std::ops::Range;
use std::path::Path;

use exr::compression::Compression;
use exr::image::Blocks;
use exr::meta::attribute::{AttributeValue, Text};
use exr::prelude::{
    AnyChannel, AnyChannels, Encoding, FlatSamples, Image as ExrImage, Layer, LayerAttributes,
    LineOrder, ReadChannels, ReadLayers, WritableImage, read,
};

use crate::atomic_write::write_atomically;
use crate::film::{ExactSum, Film, FilteredSum, PixelSum, Splats};
use crate::image::SPP_ATTRIBUTE;
use crate::plan::RenderPlan;
use scene::SceneDesc;

/// The header attribute (a string) that records how a film was rendered.
pub const RECORD_ATTRIBUTE: &str = "strata";

/// The first line's value in [`RECORD_ATTRIBUTE`]: the version of this layout.
pub const FORMAT: &str = "strata-film 1";

/// Channel of the per-pixel sample counts.
const COUNT_CHANNEL: &str = "strata.count";

/// Prefix of the exact sample sums' channels.
const SUM_PREFIX: &str = "strata.sum";

/// Prefix of the exact splat sums' channels.
const SPLAT_PREFIX: &str = "strata.splat";

/// Prefix of the splatted camera samples' channels.
const FILTERED_PREFIX: &str = "strata.filtered";

/// The colour channels' names, in the order of [`ExactSum`]'s components.
const COLOURS: [&str; 3] = ["R", "G", "B"];

/// The sample indices a film's sums hold, by sampler seed: for each seed a sorted list of
/// disjoint, non-adjacent, non-empty half-open ranges (adjacent ones are joined).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SampleRanges {
    by_seed: BTreeMap<u32, Vec<Range<u32>>>,
}

impl SampleRanges {
    /// Sample indices `range` of `seed` (nothing when the range is empty).
    pub fn single(seed: u32, range: Range<u32>) -> Self {
        let mut ranges = Self::default();
        ranges.insert(seed, range);
        ranges
    }

    /// Adds `range` of `seed`, joining it with the ranges it overlaps or touches.
    fn insert(&mut self, seed: u32, range: Range<u32>) {
        if range.is_empty() {
            return;
        }
        let list = self.by_seed.entry(seed).or_default();
        let (mut start, mut end) = (range.start, range.end);
        list.retain(|r| {
            let joins = r.start <= end && start <= r.end;
            if joins {
                start = start.min(r.start);
                end = end.max(r.end);
            }
            !joins
        });
        let at = list.partition_point(|r| r.start < start);
        list.insert(at, start..end);
    }

    /// Adds every range of `other`.
    pub fn union(&mut self, other: &SampleRanges) {
        for (&seed, list) in &other.by_seed {
            for range in list {
                self.insert(seed, range.clone());
            }
        }
    }

    /// A seed and sample range that both hold, if any.
    pub fn overlap(&self, other: &SampleRanges) -> Option<(u32, Range<u32>)> {
        for (seed, mine) in &self.by_seed {
            let Some(theirs) = other.by_seed.get(seed) else {
                continue;
            };
            for a in mine {
                for b in theirs {
                    let (start, end) = (a.start.max(b.start), a.end.min(b.end));
                    if start < end {
                        return Some((*seed, start..end));
                    }
                }
            }
        }
        None
    }

    /// Samples per pixel over all seeds and ranges.
    pub fn total(&self) -> u64 {
        self.by_seed
            .values()
            .flatten()
            .map(|r| u64::from(r.end - r.start))
            .sum()
    }

    /// The seeds and their ranges, seeds in increasing order.
    pub fn iter(&self) -> impl Iterator<Item = (u32, &[Range<u32>])> {
        self.by_seed
            .iter()
            .map(|(&seed, list)| (seed, list.as_slice()))
    }

    /// Parses the form [`fmt::Display`] writes: `seed S: A..B C..D; seed T: …` (or `none`).
    pub fn parse(text: &str) -> Result<Self, String> {
        let mut ranges = Self::default();
        if text.trim() == "none" {
            return Ok(ranges);
        }
        for entry in text.split(';') {
            let bad = || format!("\"{}\" is not \"seed S: START..END …\"", entry.trim());
            let (seed, list) = entry
                .trim()
                .strip_prefix("seed ")
                .and_then(|rest| rest.split_once(':'))
                .ok_or_else(bad)?;
            let seed: u32 = seed.trim().parse().map_err(|_| bad())?;
            let mut any = false;
            for range in list.split_whitespace() {
                let (start, end) = range.split_once("..").ok_or_else(bad)?;
                let (start, end): (u32, u32) = (
                    start.parse().map_err(|_| bad())?,
                    end.parse().map_err(|_| bad())?,
                );
                if start >= end {
                    return Err(format!("{range} is an empty sample range"));
                }
                ranges.insert(seed, start..end);
                any = true;
            }
            if !any {
                return Err(bad());
            }
        }
        Ok(ranges)
    }
}

impl fmt::Display for SampleRanges {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.by_seed.is_empty() {
            return f.write_str("none");
        }
        for (i, (seed, list)) in self.iter().enumerate() {
            if i > 0 {
                f.write_str("; ")?;
            }
            write!(f, "seed {seed}:")?;
            for range in list {
                write!(f, " {}..{}", range.start, range.end)?;
            }
        }
        Ok(())
    }
}

/// How a film was rendered: what [`RECORD_ATTRIBUTE`] holds besides the light path count (which
/// the film carries).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RenderRecord {
    /// The scene's fingerprint ([`crate::fingerprint::scene_fingerprint`]).
    pub scene: String,
    /// The sample-deciding settings ([`render_settings`]).
    pub settings: String,
    /// The sample indices in the film's sums.
    pub samples: SampleRanges,
}

/// Everything besides the scene's content and the seed that decides the value of sample `i` of
/// a pixel, as one line: Strata's version, the film (size, crop, filter), the light transport
/// with every switch (`max_depth`, Russian roulette, MIS, light selection, light tracing, path
/// reuse, …), the sampler kind and, where its numbers depend on it
/// ([`SamplerKind::pattern_depends_on_sample_count`](sampling::SamplerKind::pattern_depends_on_sample_count)), the sample count its pattern is laid out for, and
/// whether adaptive sampling was on. The render budget is left out: renders of different sample
/// ranges of one render have the same settings.
pub fn render_settings(plan: &RenderPlan, desc: &SceneDesc) -> String {
    let pattern = if plan.sampler.pattern_depends_on_sample_count() {
        format!(" pattern {}", plan.sampler_spp)
    } else {
        String::new()
    };
    // Filters wider than a pixel splat camera samples (`crate::filter::Splatter`); renders
    // that importance-sampled them instead do not belong with these.
    let splat = if matches!(desc.film.filter, scene::FilterDesc::Box) {
        ""
    } else {
        "; splat"
    };
    format!(
        "strata {}; film {:?}; {:?}; sampler {:?}{pattern}; adaptive {}{splat}",
        env!("CARGO_PKG_VERSION"),
        desc.film,
        plan.transport,
        plan.sampler,
        if plan.adaptive { "on" } else { "off" }
    )
}

/// Writes `film` and `record` to `path` in the layout of this module's documentation,
/// atomically (see [`crate::atomic_write::write_atomically`]). An error (naming the file) when
/// the record does not fit an EXR header or the file cannot be written.
pub fn write_film_exr(path: &Path, film: &Film, record: &RenderRecord) -> Result<(), String> {
    let named = |reason: String| format!("cannot write image '{}': {reason}", path.display());
    let spp = i32::try_from(record.samples.total()).map_err(|_| {
        named(format!(
            "{} samples per pixel do not fit the EXR header's int",
            record.samples.total()
        ))
    })?;
    let text = record_text(record, film.light_paths());
    let text = Text::new_or_none(&text)
        .ok_or_else(|| named(format!("the render record is not Latin-1 text: {text}")))?;
    let image = film.to_image();
    let mut channels = Vec::new();
    for (c, name) in COLOURS.iter().enumerate() {
        let values = image.data.iter().map(|v| v.to_array()[c]).collect();
        channels.push(AnyChannel::new(*name, FlatSamples::F32(values)));
    }
    let counts = film.pixels().iter().map(|p| p.count).collect();
    channels.push(AnyChannel::new(COUNT_CHANNEL, FlatSamples::U32(counts)));
    let sums: Vec<ExactSum> = film.pixels().iter().map(|p| p.sum).collect();
    push_exact_channels(&mut channels, SUM_PREFIX, &sums);
    if film.light_paths() > 0 {
        push_exact_channels(&mut channels, SPLAT_PREFIX, film.splat_sums().0);
    }
    if let Some(filtered) = film.filtered() {
        let sums: Vec<ExactSum> = filtered.iter().map(|f| f.sum).collect();
        push_exact_channels(&mut channels, FILTERED_PREFIX, &sums);
        for limb in 0..4 {
            let values = filtered
                .iter()
                .map(|f| (f.weight[0] as u128 >> (32 * limb)) as u32)
                .collect();
            channels.push(AnyChannel::new(
                format!("{FILTERED_PREFIX}.W{limb}").as_str(),
                FlatSamples::U32(values),
            ));
        }
    }
    let mut attributes = LayerAttributes::default();
    attributes
        .other
        .insert(Text::from(SPP_ATTRIBUTE), AttributeValue::I32(spp));
    let encoding = Encoding {
        compression: Compression::RLE,
        blocks: Blocks::ScanLines,
        line_order: LineOrder::Increasing,
    };
    let size = (film.width() as usize, film.height() as usize);
    let layer = Layer::new(
        size,
        attributes,
        encoding,
        AnyChannels::sort(channels.into()),
    );
    let mut exr_image = ExrImage::from_layer(layer);
    exr_image
        .attributes
        .other
        .insert(Text::from(RECORD_ATTRIBUTE), AttributeValue::Text(text));
    write_atomically(path, |writer| exr_image.write().to_unbuffered(writer))
        .map_err(|e: exr::error::Error| named(e.to_string()))
}

/// The text of [`RECORD_ATTRIBUTE`].
fn record_text(record: &RenderRecord, light_paths: u64) -> String {
    format!(
        "format: {FORMAT}\nscene: {}\nsettings: {}\nsamples: {}\nlight_paths: {light_paths}",
        record.scene, record.settings, record.samples
    )
}

/// Appends the four limb channels of each colour of `sums` (`PREFIX.R0` … `PREFIX.B3`).
fn push_exact_channels(
    channels: &mut Vec<AnyChannel<FlatSamples>>,
    prefix: &str,
    sums: &[ExactSum],
) {
    for (c, colour) in COLOURS.iter().enumerate() {
        for limb in 0..4 {
            let values = sums
                .iter()
                .map(|s| (s.0[c] as u128 >> (32 * limb)) as u32)
                .collect();
            channels.push(AnyChannel::new(
                format!("{prefix}.{colour}{limb}").as_str(),
                FlatSamples::U32(values),
            ));
        }
    }
}

/// Reads a film and its record written by [`write_film_exr`]. The film's sums of squares are
/// not stored, so they read as zero (its variance estimates are meaningless); its image, counts,
/// exact sums and light paths are those written. Errors name the file and say what is missing.
pub fn read_film_exr(path: &Path) -> Result<(Film, RenderRecord), String> {
    let named = |reason: String| format!("'{}': {reason}", path.display());
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_file(path)
        .map_err(|e| format!("cannot read image '{}': {e}", path.display()))?;
    let text = image
        .attributes
        .other
        .get(&Text::from(RECORD_ATTRIBUTE))
        .or_else(|| {
            image
                .layer_data
                .attributes
                .other
                .get(&Text::from(RECORD_ATTRIBUTE))
        });
    let Some(AttributeValue::Text(text)) = text else {
        return Err(named(format!(
            "no \"{RECORD_ATTRIBUTE}\" header attribute: not written by this version of strata \
             render or strata merge, so it cannot be checked or merged exactly"
        )));
    };
    let (record, light_paths) = parse_record(&text.to_string()).map_err(named)?;
    let size = image.layer_data.size;
    let (width, height) = (
        u32::try_from(size.width()).map_err(|_| named("too wide".to_string()))?,
        u32::try_from(size.height()).map_err(|_| named("too high".to_string()))?,
    );
    let channels = &image.layer_data.channel_data.list;
    let find = |name: &str| -> Result<&[u32], String> {
        let channel = channels
            .iter()
            .find(|c| c.name.to_string() == name)
            .ok_or_else(|| named(format!("no channel \"{name}\"")))?;
        match &channel.sample_data {
            FlatSamples::U32(values) => Ok(values),
            _ => Err(named(format!("channel \"{name}\" is not of type uint"))),
        }
    };
    let exact = |prefix: &str| -> Result<Vec<ExactSum>, String> {
        let mut limbs = Vec::with_capacity(12);
        for colour in COLOURS {
            for limb in 0..4 {
                limbs.push(find(&format!("{prefix}.{colour}{limb}"))?);
            }
        }
        let pixels = limbs[0].len();
        Ok((0..pixels)
            .map(|i| {
                ExactSum([0, 1, 2].map(|c| {
                    let bits = (0..4).fold(0u128, |bits, limb| {
                        bits | u128::from(limbs[4 * c + limb][i]) << (32 * limb)
                    });
                    bits as i128
                }))
            })
            .collect())
    };
    let counts = find(COUNT_CHANNEL)?;
    let sums = exact(SUM_PREFIX)?;
    let pixels: Vec<PixelSum> = sums
        .into_iter()
        .zip(counts)
        .map(|(sum, &count)| PixelSum {
            sum,
            count,
            ..PixelSum::default()
        })
        .collect();
    let pixel_count = pixels.len();
    let splat_sums = if light_paths > 0 {
        exact(SPLAT_PREFIX)?
    } else {
        vec![ExactSum::default(); pixel_count]
    };
    let splats = Splats {
        sums: splat_sums,
        sums_sq: vec![ExactSum::default(); pixel_count],
        light_paths,
    };
    let has_filtered = channels
        .iter()
        .any(|c| c.name.to_string() == format!("{FILTERED_PREFIX}.W0"));
    let filtered = if has_filtered {
        let mut weight_limbs = Vec::with_capacity(4);
        for limb in 0..4 {
            weight_limbs.push(find(&format!("{FILTERED_PREFIX}.W{limb}"))?);
        }
        exact(FILTERED_PREFIX)?
            .into_iter()
            .enumerate()
            .map(|(i, sum)| {
                let bits = (0..4).fold(0u128, |bits, limb| {
                    bits | u128::from(weight_limbs[limb][i]) << (32 * limb)
                });
                FilteredSum {
                    sum,
                    weight: [bits as i128, 0],
                    ..FilteredSum::default()
                }
            })
            .collect()
    } else {
        Vec::new()
    };
    let film = Film::from_parts(width, height, pixels, splats)
        .and_then(|film| film.with_filtered(filtered))
        .ok_or_else(|| named("channel sizes do not match the image size".to_string()))?;
    Ok((film, record))
}

/// Parses the text of [`RECORD_ATTRIBUTE`] into the record and the light path count.
fn parse_record(text: &str) -> Result<(RenderRecord, u64), String> {
    let mut fields = BTreeMap::new();
    for line in text.lines() {
        let (key, value) = line
            .split_once(": ")
            .ok_or_else(|| format!("header line \"{line}\" is not \"key: value\""))?;
        fields.insert(key, value);
    }
    let field = |key: &str| {
        fields
            .get(key)
            .copied()
            .ok_or_else(|| format!("the \"{RECORD_ATTRIBUTE}\" header has no \"{key}\" line"))
    };
    let format = field("format")?;
    if format != FORMAT {
        return Err(format!(
            "written in the layout \"{format}\"; this strata reads \"{FORMAT}\""
        ));
    }
    let scene = field("scene")?.to_string();
    let settings = field("settings")?.to_string();
    let samples = SampleRanges::parse(field("samples")?)
        .map_err(|e| format!("its \"samples\" header line: {e}"))?;
    let light_paths = field("light_paths")?
        .parse()
        .map_err(|e| format!("its \"light_paths\" header line: {e}"))?;
    let record = RenderRecord {
        scene,
        settings,
        samples,
    };
    Ok((record, light_paths))
}

#[cfg(test)]
mod tests {
    use glam::{UVec2, Vec3};

    use super::*;
    use crate::image::Image;

    #[test]
    fn sample_ranges_join_find_overlaps_and_round_trip_as_text() {
        let mut ranges = SampleRanges::single(7, 4..8);
        ranges.union(&SampleRanges::single(7, 0..4));
        ranges.union(&SampleRanges::single(7, 10..12));
        ranges.union(&SampleRanges::single(3, 0..16));
        ranges.union(&SampleRanges::single(3, 5..5));
        assert_eq!(ranges.to_string(), "seed 3: 0..16; seed 7: 0..8 10..12");
        assert_eq!(ranges.total(), 16 + 8 + 2);
        assert_eq!(SampleRanges::parse(&ranges.to_string()).unwrap(), ranges);
        assert_eq!(
            ranges.overlap(&SampleRanges::single(7, 11..20)),
            Some((7, 11..12))
        );
        assert_eq!(ranges.overlap(&SampleRanges::single(7, 8..10)), None);
        assert_eq!(ranges.overlap(&SampleRanges::single(9, 0..100)), None);
        // Filling the gap joins the ranges into one.
        ranges.union(&SampleRanges::single(7, 8..10));
        assert_eq!(ranges.to_string(), "seed 3: 0..16; seed 7: 0..12");
        assert_eq!(SampleRanges::default().to_string(), "none");
        assert_eq!(
            SampleRanges::parse("none").unwrap(),
            SampleRanges::default()
        );
        for bad in [
            "seed x: 0..4",
            "seed 1: 4..4",
            "seed 1:",
            "0..4",
            "seed 1: 0-4",
        ] {
            assert!(SampleRanges::parse(bad).is_err(), "{bad}");
        }
    }

    /// A film with negative, tiny, huge and splatted sums, and its record.
    fn film_and_record(light_paths: u64) -> (Film, RenderRecord) {
        let mut film = Film::new(3, 2);
        film.add(UVec2::new(0, 0), Vec3::new(-1.5, 1e-20, 3e20));
        film.add(UVec2::new(0, 0), Vec3::new(0.1, 2.0, 7.0));
        film.add(UVec2::new(2, 1), Vec3::splat(1.0 / 3.0));
        if light_paths > 0 {
            film.add_splat(UVec2::new(1, 1), Vec3::new(0.25, -3e-9, 4e4));
            film.add_light_paths(light_paths);
        }
        let record = RenderRecord {
            scene: "0123456789abcdef".to_string(),
            settings: "strata 0; film …".replace('…', "x"),
            samples: SampleRanges::single(5, 2..4),
        };
        (film, record)
    }

    #[test]
    fn films_round_trip_every_bit_of_their_exact_sums() {
        let dir = tempfile::tempdir().unwrap();
        for light_paths in [0, 6] {
            let path = dir.path().join(format!("f{light_paths}.exr"));
            let (film, record) = film_and_record(light_paths);
            write_film_exr(&path, &film, &record).unwrap();
            let (read, read_record) = read_film_exr(&path).unwrap();
            assert_eq!(read_record, record);
            assert_eq!(read.light_paths(), light_paths);
            assert_eq!(read.splat_sums().0, film.splat_sums().0);
            for (a, b) in read.pixels().iter().zip(film.pixels()) {
                assert_eq!((a.sum, a.count), (b.sum, b.count));
            }
            assert_eq!(read.to_image(), film.to_image());
            // Viewers and `strata diff` see the image and the sample count.
            let (image, spp) = Image::read_exr_with_spp(&path).unwrap();
            assert_eq!((image, spp), (film.to_image(), Some(2)));
        }
        let (film, _) = film_and_record(0);
        assert!(
            film.pixels()[0].sum.0[0] < 0 && film.pixels()[0].sum.0[2] > 1i128 << 100,
            "the test covers negative sums and the top limb"
        );
    }

    #[test]
    fn splatted_sums_round_trip_every_bit() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("filtered.exr");
        let (film, record) = film_and_record(0);
        let mut filtered = vec![FilteredSum::default(); 6];
        filtered[1].add(Vec3::new(-1.5, 1e-3, 3e20), 0.25, 0.2);
        filtered[1].add(Vec3::new(0.5, 2.0, 7.0), -0.01, 0.01);
        filtered[5].add(Vec3::splat(1.0 / 3.0), 0.0, 1e-3);
        let film = film.with_filtered(filtered.clone()).unwrap();
        write_film_exr(&path, &film, &record).unwrap();
        let (read, _) = read_film_exr(&path).unwrap();
        let read_filtered = read.filtered().expect("splatted sums are read back");
        for (a, b) in read_filtered.iter().zip(&filtered) {
            assert_eq!((a.sum, a.weight[0]), (b.sum, b.weight[0]));
        }
        assert_eq!(read.to_image(), film.to_image());
        assert!(read_film_exr(&dir.path().join("none.exr")).is_err());
    }

    #[test]
    fn the_file_has_the_same_bytes_every_time() {
        let dir = tempfile::tempdir().unwrap();
        let (film, record) = film_and_record(6);
        let (a, b) = (dir.path().join("a.exr"), dir.path().join("b.exr"));
        write_film_exr(&a, &film, &record).unwrap();
        write_film_exr(&b, &film, &record).unwrap();
        assert!(std::fs::read(&a).unwrap() == std::fs::read(&b).unwrap());
    }

    #[test]
    fn plain_or_broken_records_are_refused_by_file_name() {
        let dir = tempfile::tempdir().unwrap();
        let plain = dir.path().join("plain.exr");
        Image::new(3, 2).write_exr_with_spp(&plain, 4).unwrap();
        let message = read_film_exr(&plain).unwrap_err();
        assert!(
            message.contains("plain.exr") && message.contains("no \"strata\""),
            "{message}"
        );
        for (broken, complaint) in [
            ("format: strata-film 0", "layout"),
            ("format: strata-film 1\nscene: x", "no \"settings\""),
            (
                "format: strata-film 1\nscene: x\nsettings: y\nsamples: seed 1: 2..1\nlight_paths: 0",
                "empty",
            ),
            (
                "format: strata-film 1\nscene: x\nsettings: y\nsamples: none\nlight_paths: -1",
                "light_paths",
            ),
            ("garbage", "key: value"),
        ] {
            let error = parse_record(broken).unwrap_err();
            assert!(error.contains(complaint), "{broken}: {error}");
        }
    }
}
