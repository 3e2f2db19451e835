//! A tileable blue-noise dither array made by Ulichney's void-and-cluster method (1993).

use crate::rng::Rng;
use std::sync::LazyLock;

/// Log₂ of the tile's side.
pub(crate) const TILE_LOG2: u32 = 6;
/// The tile's side in pixels.
pub(crate) const TILE_SIZE: u32 = 1 << TILE_LOG2;
/// The number of pixels (and of distinct ranks) in the tile.
const TILE_PIXELS: usize = (TILE_SIZE * TILE_SIZE) as usize;
/// Standard deviation, in pixels, of the Gaussian that measures clustering (Ulichney's value).
const SIGMA: f32 = 1.5;
/// The seed of the initial random pattern: the tile is the same in every run and on every machine.
const INITIAL_PATTERN_SEED: u32 = 0x0B1E_4015;

/// A 64 × 64 toroidal array holding each rank 0..4096 once, arranged so that the pixels of any rank
/// threshold form a blue-noise pattern: the values have little low-frequency energy in screen space.
pub(crate) struct BlueNoiseTile {
    ranks: Box<[u16]>,
}

impl BlueNoiseTile {
    /// The rank, in [0, 4096), at tile pixel (x, y); coordinates wrap around.
    #[inline]
    pub(crate) fn rank(&self, x: u32, y: u32) -> u32 {
        let index = ((y & (TILE_SIZE - 1)) << TILE_LOG2) | (x & (TILE_SIZE - 1));
        u32::from(self.ranks[index as usize])
    }
}

/// The process-wide tile, built on first use (a few milliseconds).
pub(crate) fn blue_noise_tile() -> &'static BlueNoiseTile {
    static TILE: LazyLock<BlueNoiseTile> = LazyLock::new(void_and_cluster);
    &TILE
}

/// Clustering energy: each set pixel adds a toroidally wrapped Gaussian to the energy of every pixel.
struct Energy {
    kernel: Vec<f32>,
    values: Vec<f32>,
}

impl Energy {
    fn new() -> Self {
        let size = TILE_SIZE as i32;
        let mut kernel = vec![0.0; TILE_PIXELS];
        for y in 0..size {
            for x in 0..size {
                let dx = x.min(size - x) as f32;
                let dy = y.min(size - y) as f32;
                kernel[(y * size + x) as usize] =
                    (-(dx * dx + dy * dy) / (2.0 * SIGMA * SIGMA)).exp();
            }
        }
        Self {
            kernel,
            values: vec![0.0; TILE_PIXELS],
        }
    }

    /// Adds (`sign` = 1) or removes (`sign` = −1) the Gaussian of a point at pixel `at`.
    fn splat(&mut self, at: usize, sign: f32) {
        let mask = TILE_SIZE as usize - 1;
        let (ax, ay) = (at & mask, at >> TILE_LOG2);
        for (i, value) in self.values.iter_mut().enumerate() {
            let dx = (i & mask).wrapping_sub(ax) & mask;
            let dy = (i >> TILE_LOG2).wrapping_sub(ay) & mask;
            *value += sign * self.kernel[(dy << TILE_LOG2) | dx];
        }
    }

    /// The set pixel with the highest energy: the centre of the tightest cluster.
    fn tightest_cluster(&self, set: &[bool]) -> usize {
        self.extreme(set, true, |a, b| a > b)
    }

    /// The unset pixel with the lowest energy: the centre of the largest void.
    fn largest_void(&self, set: &[bool]) -> usize {
        self.extreme(set, false, |a, b| a < b)
    }

    fn extreme(&self, set: &[bool], wanted: bool, better: impl Fn(f32, f32) -> bool) -> usize {
        let mut best = usize::MAX;
        for (i, (&value, &is_set)) in self.values.iter().zip(set).enumerate() {
            if is_set == wanted && (best == usize::MAX || better(value, self.values[best])) {
                best = i;
            }
        }
        best
    }
}

/// Builds the tile: a random 10 % pattern is relaxed by moving points from the tightest cluster to
/// the largest void until that no longer changes anything; ranks below its size are then given by
/// removing the tightest cluster repeatedly, and ranks above by filling the largest void repeatedly.
/// (Filling the largest void of the set pixels is the same as removing the tightest cluster of the
/// unset ones, because the two energies sum to a constant, so Ulichney's phases 2 and 3 are one loop.)
fn void_and_cluster() -> BlueNoiseTile {
    let initial_count = TILE_PIXELS / 10;
    let mut rng = Rng::new(INITIAL_PATTERN_SEED);
    let mut set = vec![false; TILE_PIXELS];
    let mut energy = Energy::new();
    let mut placed = 0;
    while placed < initial_count {
        let at = rng.next_below(TILE_PIXELS as u32) as usize;
        if !set[at] {
            set[at] = true;
            energy.splat(at, 1.0);
            placed += 1;
        }
    }
    for _ in 0..TILE_PIXELS {
        let cluster = energy.tightest_cluster(&set);
        set[cluster] = false;
        energy.splat(cluster, -1.0);
        let void = energy.largest_void(&set);
        set[void] = true;
        energy.splat(void, 1.0);
        if void == cluster {
            break;
        }
    }

    let mut ranks = vec![0_u16; TILE_PIXELS].into_boxed_slice();
    let initial_set = set.clone();
    let initial_energy = energy.values.clone();
    for rank in (0..initial_count).rev() {
        let cluster = energy.tightest_cluster(&set);
        set[cluster] = false;
        energy.splat(cluster, -1.0);
        ranks[cluster] = rank as u16;
    }
    set = initial_set;
    energy.values = initial_energy;
    for rank in initial_count..TILE_PIXELS {
        let void = energy.largest_void(&set);
        set[void] = true;
        energy.splat(void, 1.0);
        ranks[void] = rank as u16;
    }
    BlueNoiseTile { ranks }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tile_holds_every_rank_once() {
        let tile = blue_noise_tile();
        let mut seen = vec![false; TILE_PIXELS];
        for y in 0..TILE_SIZE {
            for x in 0..TILE_SIZE {
                let r = tile.rank(x, y) as usize;
                assert!(!seen[r], "rank {r} appears twice");
                seen[r] = true;
            }
        }
        assert_eq!(tile.rank(TILE_SIZE + 3, 2 * TILE_SIZE + 5), tile.rank(3, 5));
    }

    #[test]
    fn neighbouring_ranks_differ_more_than_random() {
        // Blue noise puts dissimilar values next to each other: the mean absolute rank difference of
        // horizontal neighbours is far above the 1/3 · 4096 of an unstructured (white-noise) array.
        let tile = blue_noise_tile();
        let mut total = 0.0_f64;
        for y in 0..TILE_SIZE {
            for x in 0..TILE_SIZE {
                total += f64::from(tile.rank(x, y).abs_diff(tile.rank(x + 1, y)));
            }
        }
        let mean = total / TILE_PIXELS as f64 / TILE_PIXELS as f64;
        assert!(
            mean > 0.4,
            "mean neighbour difference {mean} of the rank range"
        );
    }
}
