//! A linear RGB floating-point image, its EXR input/output and 8-bit sRGB PNG output.

mod exr_file;
mod png_file;

use std::fmt;
use std::path::PathBuf;

use glam::Vec3;

pub use exr_file::SPP_ATTRIBUTE;
pub use png_file::linear_to_srgb8;

/// A linear RGB image stored row-major, top row first: pixel `(x, y)` is
/// `data[y * width + x]`. Every operation that reads `data` expects `width * height` pixels.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Linear RGB pixel values, row-major, top row first.
    pub data: Vec<Vec3>,
}

/// Why an image could not be read or written.
#[derive(Debug)]
pub enum ImageError {
    /// `path` could not be read as an RGB image (missing, unreadable, not an EXR, no R, G, B
    /// channels): bad input.
    Read {
        /// The file that was being read.
        path: PathBuf,
        /// What went wrong.
        reason: String,
    },
    /// `path` could not be written. Nothing was left at `path`, and a file that was there
    /// before is untouched.
    Write {
        /// The file that was being written.
        path: PathBuf,
        /// What went wrong.
        reason: String,
    },
    /// The image's `data` does not hold `width * height` pixels.
    Dimensions {
        /// The declared width in pixels.
        width: u32,
        /// The declared height in pixels.
        height: u32,
        /// The number of pixels actually stored.
        len: usize,
    },
}

impl fmt::Display for ImageError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Read { path, reason } => {
                write!(f, "cannot read image '{}': {reason}", path.display())
            }
            Self::Write { path, reason } => {
                write!(f, "cannot write image '{}': {reason}", path.display())
            }
            Self::Dimensions { width, height, len } => {
                write!(
                    f,
                    "a {width}x{height} image needs {} pixels but holds {len}",
                    pixel_count(*width, *height)
                )
            }
        }
    }
}

impl std::error::Error for ImageError {}

/// `width * height` as a pixel count.
fn pixel_count(width: u32, height: u32) -> usize {
    width as usize * height as usize
}

impl Image {
    /// A black image of `width × height` pixels.
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            data: vec![Vec3::ZERO; pixel_count(width, height)],
        }
    }

    /// An image whose pixel `(x, y)` is `f(x, y)`, evaluated row by row from the top.
    pub fn from_fn(width: u32, height: u32, mut f: impl FnMut(u32, u32) -> Vec3) -> Self {
        let data = (0..height)
            .flat_map(|y| (0..width).map(move |x| (x, y)))
            .map(|(x, y)| f(x, y))
            .collect();
        Self {
            width,
            height,
            data,
        }
    }

    /// The value of pixel `(x, y)`; panics outside the image.
    pub fn pixel(&self, x: u32, y: u32) -> Vec3 {
        assert!(
            x < self.width && y < self.height,
            "pixel ({x}, {y}) outside {}x{}",
            self.width,
            self.height
        );
        self.data[y as usize * self.width as usize + x as usize]
    }

    /// An error unless `data` holds exactly `width * height` pixels.
    pub fn check_dimensions(&self) -> Result<(), ImageError> {
        if self.data.len() == pixel_count(self.width, self.height) {
            Ok(())
        } else {
            Err(ImageError::Dimensions {
                width: self.width,
                height: self.height,
                len: self.data.len(),
            })
        }
    }
}
