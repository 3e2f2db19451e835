//! Splitting the image into rectangular tiles, the units of parallel work.

use glam::UVec2;

/// The largest tile edge, in pixels.
pub const MAX_TILE_SIZE: u32 = 16;

/// The smallest tile edge that [`tile_size_for`] picks, in pixels.
pub const MIN_TILE_SIZE: u32 = 4;

/// A rectangle of pixels: `origin` is its top-left pixel, `size` its width and height in pixels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tile {
    /// Top-left pixel.
    pub origin: UVec2,
    /// Width and height in pixels (smaller than the tile size at the image's right and bottom).
    pub size: UVec2,
}

impl Tile {
    /// The tile's pixels, row by row from the top.
    pub fn pixels(&self) -> impl Iterator<Item = UVec2> + '_ {
        (0..self.size.y)
            .flat_map(move |y| (0..self.size.x).map(move |x| self.origin + UVec2::new(x, y)))
    }

    /// Number of pixels in the tile.
    pub fn pixel_count(&self) -> usize {
        self.size.x as usize * self.size.y as usize
    }
}

/// The tiles of edge `tile_size` (≥ 1) covering a `width × height` image exactly once, in
/// row-major order of tiles (left to right, then top to bottom); edge tiles are clipped.
pub fn tiles(width: u32, height: u32, tile_size: u32) -> Vec<Tile> {
    let step = tile_size.max(1);
    let mut out = Vec::new();
    for y in (0..height).step_by(step as usize) {
        for x in (0..width).step_by(step as usize) {
            out.push(Tile {
                origin: UVec2::new(x, y),
                size: UVec2::new(step.min(width - x), step.min(height - y)),
            });
        }
    }
    out
}

/// A tile edge for a `width × height` image on `threads` threads: [`MAX_TILE_SIZE`], halved
/// (down to [`MIN_TILE_SIZE`]) while there would be fewer than 8 tiles per thread, so small
/// images still keep every thread busy. The tile size never changes the rendered values.
pub fn tile_size_for(width: u32, height: u32, threads: usize) -> u32 {
    let mut size = MAX_TILE_SIZE;
    while size > MIN_TILE_SIZE
        && (width.div_ceil(size) as usize * height.div_ceil(size) as usize) < 8 * threads
    {
        size /= 2;
    }
    size
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiles_cover_every_pixel_exactly_once_in_order() {
        let (width, height) = (37, 21);
        let all = tiles(width, height, 16);
        assert_eq!(all.len(), 3 * 2);
        assert_eq!(
            all[1],
            Tile {
                origin: UVec2::new(16, 0),
                size: UVec2::new(16, 16)
            }
        );
        assert_eq!(
            all[5],
            Tile {
                origin: UVec2::new(32, 16),
                size: UVec2::new(5, 5)
            }
        );
        let mut seen = vec![0u32; (width * height) as usize];
        for tile in &all {
            assert_eq!(tile.pixels().count(), tile.pixel_count());
            for p in tile.pixels() {
                seen[(p.y * width + p.x) as usize] += 1;
            }
        }
        assert!(seen.iter().all(|&n| n == 1));
        let first: Vec<UVec2> = all[0].pixels().take(17).collect();
        assert_eq!(
            (first[15], first[16]),
            (UVec2::new(15, 0), UVec2::new(0, 1)),
            "row by row"
        );
    }

    #[test]
    fn empty_images_have_no_tiles() {
        assert!(tiles(0, 5, 16).is_empty());
        assert!(tiles(5, 0, 16).is_empty());
    }

    #[test]
    fn small_images_get_smaller_tiles() {
        assert_eq!(tile_size_for(1024, 1024, 2), 16);
        assert_eq!(tile_size_for(32, 32, 2), 8, "16 tiles of 8 for 2 threads");
        assert_eq!(tile_size_for(8, 8, 2), MIN_TILE_SIZE);
    }
}
