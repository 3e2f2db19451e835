//! `strata merge A.exr B.exr … --out C.exr`: adds up renders of disjoint samples of one render
//! (made by separate processes or machines) into the image of all their samples, exactly, and
//! refuses inputs that do not belong together.
//!
//! # Why the sum is exact
//!
//! A pixel's value is `S / n + (N / L) · P`: `S` the sum of its `n` finite samples, `P` the sum
//! of the light paths' splats onto it, `L` the light paths traced (one per `samples_per_path`
//! pixel samples with light tracing, else none) and `N` the pixel count. The film keeps `S` and
//! `P` exactly, in fixed point ([`crate::film::ExactSum`]), and `n` and `L` are integers, so they do not depend
//! on the order in which samples were added: a render of sample indices `[0, a)` and one of
//! `[a, b)` have sums that add up to those of one render of `[0, b)`, bit for bit. Every sample
//! depends only on (scene, settings, seed, pixel, sample index) — the samplers index their
//! patterns by sample index, light paths are keyed by the pixel sample they belong to, and path
//! reuse combines the paths of one block at one sample index — so the samples themselves are
//! the same whichever process renders them, and whatever its thread count.
//!
//! Each EXR that `strata render` writes therefore carries, besides the image, the per-pixel
//! exact sums and counts, the light path count, and a record of the scene's fingerprint, the
//! settings and the sample ranges by seed (the layout is documented in [`crate::film_exr`]).
//! `strata merge` reads those, adds them in integer arithmetic, recomputes the image exactly as
//! a render does, and writes it in the same layout with the union of the sample ranges, so a
//! merged file can be merged again, and `merge` of `--samples 0..a`, `a..b`, `b..N` (any order)
//! is the very file `--spp N` writes. The fixed point has limits (a step of 2⁻⁴⁸ and sums up to
//! 2⁷⁹ per pixel; see [`crate::film::EXACT_FRACTION_BITS`]); sums of squares are not carried, so
//! the merged film has no variance estimate.
//!
//! # What is refused (exit status 2, naming the files)
//!
//! - a file without the record (not written by `strata render` or `strata merge`);
//! - a file given twice, or two inputs that hold the same sample index of the same seed
//!   (overlapping ranges: a task rendered twice would count its samples twice);
//! - inputs of different scenes (fingerprints), settings or image sizes. The settings include
//!   the sample count the sampler's pattern is laid out for where the sampler's numbers depend
//!   on it (stratified and blue noise: `--spp 8` and `--spp 16` renders do not merge; they are
//!   different patterns, and with one seed their samples would be correlated).
//!
//! Renders with different seeds of the same scene and settings are independent renders of the
//! same image, and are merged: the result pools all their samples (each pixel the mean of all of
//! them, the light paths' share over all light paths).
//!
//! Gaps are accepted: inputs whose ranges of a seed leave indices out (`0..4` and `8..16`) give
//! the image of the samples they hold, and the output records exactly those ranges
//! (`seed 1: 0..4 8..16`), so a later merge with `4..8` completes the render. Every sample of
//! every sampler is uniformly distributed on its own (the patterns are randomly permuted per
//! pixel), so any set of sample indices gives an unbiased image; only a complete range `0..N`
//! is the same as the `--spp N` render.

use std::path::{Path, PathBuf};

use crate::commands::CommandError;
use crate::film::Film;
use crate::film_exr::{RenderRecord, read_film_exr};

/// One input of a merge: a film, how it was rendered, and the file it came from (for messages).
#[derive(Clone, Debug, PartialEq)]
pub struct Piece {
    /// The file the piece was read from.
    pub path: PathBuf,
    /// Its sums.
    pub film: Film,
    /// What rendered it.
    pub record: RenderRecord,
}

/// Reads the render EXR at `path` (see [`crate::film_exr`]); bad input when it is unreadable or
/// was not written by `strata render` or `strata merge`.
pub fn read_piece(path: &Path) -> Result<Piece, CommandError> {
    let (film, record) = read_film_exr(path).map_err(CommandError::BadInput)?;
    Ok(Piece {
        path: path.to_path_buf(),
        film,
        record,
    })
}

/// The sum of `pieces`, with the union of their sample ranges: bad input (naming the files)
/// unless they are of one scene, settings and size, hold disjoint samples, and hold some.
pub fn merge(pieces: &[Piece]) -> Result<(Film, RenderRecord), CommandError> {
    let first = pieces
        .first()
        .ok_or_else(|| CommandError::BadInput("nothing to merge".to_string()))?;
    let name = |piece: &Piece| format!("'{}'", piece.path.display());
    for piece in &pieces[1..] {
        check_belongs(first, piece)?;
    }
    for (i, a) in pieces.iter().enumerate() {
        for b in &pieces[i + 1..] {
            if same_file(&a.path, &b.path) {
                return Err(CommandError::BadInput(format!(
                    "{} is given twice: its samples would count twice",
                    name(a)
                )));
            }
            if let Some((seed, range)) = a.record.samples.overlap(&b.record.samples) {
                return Err(CommandError::BadInput(format!(
                    "{} and {} both hold samples {}..{} of seed {seed}: merged, they would count \
                     twice (a task rendered twice?); merge each sample range once",
                    name(a),
                    name(b),
                    range.start,
                    range.end
                )));
            }
        }
    }
    let mut film = first.film.clone();
    let mut record = first.record.clone();
    for piece in &pieces[1..] {
        film.merge(&piece.film)
            .map_err(|e| CommandError::BadInput(format!("{}: {e}", name(piece))))?;
        record.samples.union(&piece.record.samples);
    }
    let total = record.samples.total();
    if total == 0 {
        return Err(CommandError::BadInput(
            "the inputs hold no samples".to_string(),
        ));
    }
    if i32::try_from(total).is_err() {
        return Err(CommandError::BadInput(format!(
            "the inputs hold {total} samples per pixel in all, more than an EXR header records"
        )));
    }
    Ok((film, record))
}

/// Bad input unless `piece` renders the same scene, with the same settings and size, as
/// `first`; the message names the first difference of size, scene and settings.
fn check_belongs(first: &Piece, piece: &Piece) -> Result<(), CommandError> {
    let (a, b) = (first.path.display(), piece.path.display());
    // The size first: the fingerprint and the settings include it, and would name a vaguer
    // difference.
    let size = |p: &Piece| (p.film.width(), p.film.height());
    if size(piece) != size(first) {
        return Err(CommandError::BadInput(format!(
            "'{b}' is {}x{} pixels but '{a}' is {}x{}",
            size(piece).0,
            size(piece).1,
            size(first).0,
            size(first).1
        )));
    }
    if piece.record.scene != first.record.scene {
        return Err(CommandError::BadInput(format!(
            "'{b}' and '{a}' are renders of different scenes (fingerprints {} and {}): the \
             scene files, a file they include, or a mesh or texture they read differ",
            piece.record.scene, first.record.scene
        )));
    }
    if piece.record.settings != first.record.settings {
        return Err(CommandError::BadInput(format!(
            "'{b}' and '{a}' were rendered with different settings (integrator, sampler, \
             sample count of the sampler's pattern, size or filter):\n  {b}: {}\n  {a}: {}",
            piece.record.settings, first.record.settings
        )));
    }
    Ok(())
}

/// Whether `a` and `b` name one file (after resolving links and relative parts, where they can
/// be resolved).
fn same_file(a: &Path, b: &Path) -> bool {
    match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(a), Ok(b)) => a == b,
        _ => a == b,
    }
}

/// Reads and merges the render EXRs at `paths` (see [`merge`]).
pub fn merge_files(paths: &[PathBuf]) -> Result<(Film, RenderRecord), CommandError> {
    let pieces = paths
        .iter()
        .map(|p| read_piece(p))
        .collect::<Result<Vec<_>, _>>()?;
    merge(&pieces)
}

#[cfg(test)]
mod tests {
    use glam::{UVec2, Vec3};

    use super::*;
    use crate::film_exr::SampleRanges;

    /// A 2 × 1 piece named `name` holding samples `range` of `seed`, each sample of index `i`
    /// worth `i / 3` (in pixel 0) with a light path splat on pixel 1.
    fn piece(name: &str, seed: u32, range: std::ops::Range<u32>) -> Piece {
        let mut film = Film::new(2, 1);
        for i in range.clone() {
            film.add(UVec2::new(0, 0), Vec3::splat(i as f32 / 3.0));
            film.add_splat(UVec2::new(1, 0), Vec3::new(0.1 * i as f32, 1.0, 0.0));
            film.add_light_paths(1);
        }
        Piece {
            path: PathBuf::from(name),
            film,
            record: RenderRecord {
                scene: "scene".to_string(),
                settings: "settings".to_string(),
                samples: SampleRanges::single(seed, range),
            },
        }
    }

    #[test]
    fn disjoint_pieces_in_any_order_sum_to_the_whole() {
        let whole = piece("whole", 1, 0..10);
        let parts = [
            piece("a", 1, 0..3),
            piece("b", 1, 3..7),
            piece("c", 1, 7..10),
        ];
        for order in [[0, 1, 2], [2, 0, 1], [1, 2, 0]] {
            let pieces: Vec<Piece> = order.iter().map(|&i| parts[i].clone()).collect();
            let (film, record) = merge(&pieces).unwrap();
            assert_eq!(film.to_image(), whole.film.to_image(), "{order:?}");
            assert_eq!(record, whole.record);
        }
        // Two seeds pool: gaps and seeds are recorded as they are.
        let (film, record) = merge(&[
            piece("a", 1, 0..3),
            piece("b", 2, 0..3),
            piece("c", 1, 5..6),
        ])
        .unwrap();
        assert_eq!(
            record.samples.to_string(),
            "seed 1: 0..3 5..6; seed 2: 0..3"
        );
        assert_eq!(film.pixel(UVec2::new(0, 0)).count, 7);
        assert_eq!(film.light_paths(), 7);
    }

    #[test]
    fn what_does_not_belong_together_is_refused_by_name() {
        let refused = |pieces: &[Piece], needle: &str| {
            let error = merge(pieces).unwrap_err();
            assert_eq!(error.exit_code(), 2);
            assert!(error.to_string().contains(needle), "{error}");
        };
        refused(
            &[piece("a.exr", 1, 0..4), piece("a.exr", 1, 4..8)],
            "'a.exr' is given twice",
        );
        refused(
            &[
                piece("a.exr", 1, 0..4),
                piece("b.exr", 2, 0..4),
                piece("c.exr", 1, 3..6),
            ],
            "'a.exr' and 'c.exr' both hold samples 3..4 of seed 1",
        );
        let mut other_scene = piece("b.exr", 1, 4..8);
        other_scene.record.scene = "other".to_string();
        refused(
            &[piece("a.exr", 1, 0..4), other_scene],
            "'b.exr' and 'a.exr' are renders of different scenes",
        );
        let mut other_settings = piece("b.exr", 1, 4..8);
        other_settings.record.settings = "other".to_string();
        refused(
            &[piece("a.exr", 1, 0..4), other_settings],
            "different settings",
        );
        let mut other_size = piece("b.exr", 1, 4..8);
        other_size.film = Film::new(1, 2);
        refused(
            &[piece("a.exr", 1, 0..4), other_size],
            "'b.exr' is 1x2 pixels",
        );
        refused(&[], "nothing to merge");
        refused(&[piece("a.exr", 1, 0..0)], "no samples");
    }
}
