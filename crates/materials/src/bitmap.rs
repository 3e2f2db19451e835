//! Mitsuba's `bitmap` texture: an image of linear RGB texels looked up by surface coordinates,
//! with its `to_uv` transform, `filter_type` and `wrap_mode`.

use glam::{Affine2, Vec2, Vec3};

/// How a [`BitmapTexture`] is read between texel centres (Mitsuba's `filter_type`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TextureFilter {
    /// The texel the point falls in (`nearest`).
    Nearest,
    /// Bilinear interpolation of the four texels around the point, texel centres at
    /// ((i + ½) / width, (j + ½) / height) (`bilinear`, Mitsuba's default).
    Bilinear,
}

/// What a [`BitmapTexture`] shows outside [0, 1]² (Mitsuba's `wrap_mode`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TextureWrap {
    /// The image tiles the plane (`repeat`, Mitsuba's default).
    Repeat,
    /// The image tiles the plane mirrored at every edge (`mirror`).
    Mirror,
    /// The edge texels extend outwards (`clamp`).
    Clamp,
}

/// An RGB image used as a spatially varying parameter. Surface coordinates (u, v), moved by
/// `to_uv`, address it with u across and v down from the image's first row, as Mitsuba's do.
#[derive(Clone, Debug, PartialEq)]
pub struct BitmapTexture {
    width: usize,
    height: usize,
    /// Linear RGB, row by row from the image's first (top) row.
    texels: Vec<Vec3>,
    filter: TextureFilter,
    wrap: TextureWrap,
    to_uv: Affine2,
}

impl BitmapTexture {
    /// A texture of `width` × `height` linear RGB `texels` (row-major, first row at v = 0); an
    /// error naming the problem when the sizes disagree or a texel is not finite. Images narrower
    /// or lower than 2 texels are widened by repeating their last column or row, as Mitsuba does.
    pub fn new(
        width: usize,
        height: usize,
        texels: Vec<Vec3>,
        filter: TextureFilter,
        wrap: TextureWrap,
        to_uv: Affine2,
    ) -> Result<Self, String> {
        if width == 0 || height == 0 || texels.len() != width * height {
            return Err(format!(
                "{} texels for a {width} x {height} image",
                texels.len()
            ));
        }
        if let Some(i) = texels.iter().position(|t| !t.is_finite()) {
            return Err(format!(
                "texel ({}, {}) is not finite: {}",
                i % width,
                i / width,
                texels[i]
            ));
        }
        let (padded_width, padded_height) = (width.max(2), height.max(2));
        let texels = (0..padded_height)
            .flat_map(|y| (0..padded_width).map(move |x| (x.min(width - 1), y.min(height - 1))))
            .map(|(x, y)| texels[y * width + x])
            .collect();
        Ok(Self {
            width: padded_width,
            height: padded_height,
            texels,
            filter,
            wrap,
            to_uv,
        })
    }

    /// The mean luminance of the texels: what Mitsuba's `mean()` gives a texture's lobe-sampling
    /// weights.
    pub fn mean_luminance(&self) -> f32 {
        let sum: f64 = self.texels.iter().map(|&t| f64::from(luminance(t))).sum();
        (sum / self.texels.len() as f64) as f32
    }

    /// The luminance of [`Self::eval`] at `uv`: what Mitsuba's `eval_1` gives a scalar parameter
    /// (a blend's weight) from a colour image; a grey image's value.
    pub fn eval_luminance(&self, uv: Vec2) -> f32 {
        luminance(self.eval(uv))
    }

    /// The texture's linear RGB value at surface coordinates `uv` (before `to_uv`).
    pub fn eval(&self, uv: Vec2) -> Vec3 {
        let size = Vec2::new(self.width as f32, self.height as f32);
        let uv = self.to_uv.transform_point2(uv);
        match self.filter {
            TextureFilter::Nearest => {
                let p = (uv * size).floor();
                self.texel(p.x, p.y)
            }
            TextureFilter::Bilinear => {
                let p = uv * size - 0.5;
                let corner = p.floor();
                let w = p - corner;
                let (x, y) = (corner.x, corner.y);
                let top = self.texel(x, y).lerp(self.texel(x + 1.0, y), w.x);
                let bottom = self
                    .texel(x, y + 1.0)
                    .lerp(self.texel(x + 1.0, y + 1.0), w.x);
                top.lerp(bottom, w.y)
            }
        }
    }

    /// The gradient (∂/∂u, ∂/∂v) of [`Self::eval_luminance`] at surface coordinates `uv`, per
    /// unit of u and v: Mitsuba's `eval_1_grad`. With bilinear filtering the derivative of the
    /// interpolation of the four texels' luminances (the finite differences between neighbouring
    /// texels) by the texel coordinates, carried back through `to_uv`'s linear part and scaled by
    /// the resolution after it, in Mitsuba's order; zero with nearest filtering, which is flat
    /// within a texel.
    pub fn luminance_gradient(&self, uv: Vec2) -> Vec2 {
        if self.filter == TextureFilter::Nearest {
            return Vec2::ZERO;
        }
        let size = Vec2::new(self.width as f32, self.height as f32);
        let p = self.to_uv.transform_point2(uv) * size - 0.5;
        let corner = p.floor();
        let w = p - corner;
        let (x, y) = (corner.x, corner.y);
        let f00 = luminance(self.texel(x, y));
        let f10 = luminance(self.texel(x + 1.0, y));
        let f01 = luminance(self.texel(x, y + 1.0));
        let f11 = luminance(self.texel(x + 1.0, y + 1.0));
        let d_texel = Vec2::new(
            (1.0 - w.y) * (f10 - f00) + w.y * (f11 - f01),
            (1.0 - w.x) * (f01 - f00) + w.x * (f11 - f10),
        );
        size * self.to_uv.matrix2.transpose().mul_vec2(d_texel)
    }

    /// The texel at integer coordinates (x, y), which the wrap mode brings into the image.
    fn texel(&self, x: f32, y: f32) -> Vec3 {
        let x = wrap(x, self.width, self.wrap);
        let y = wrap(y, self.height, self.wrap);
        self.texels[y * self.width + x]
    }
}

/// The luminance of linear RGB with Mitsuba's weights (Rec. 709 primaries), which sum to 1.
fn luminance(rgb: Vec3) -> f32 {
    rgb.dot(Vec3::new(0.212_671, 0.715_160, 0.072_169))
}

/// The index in 0..`size` that `wrap_mode` gives the integer-valued coordinate `i` (which may
/// be far outside; NaN gives 0).
fn wrap(i: f32, size: usize, wrap_mode: TextureWrap) -> usize {
    let n = size as f32;
    let inside = match wrap_mode {
        TextureWrap::Clamp => i.clamp(0.0, n - 1.0),
        TextureWrap::Repeat => i.rem_euclid(n),
        TextureWrap::Mirror => {
            let period = i.rem_euclid(2.0 * n);
            if period >= n {
                2.0 * n - 1.0 - period
            } else {
                period
            }
        }
    };
    // `as` saturates, so an index rounded up to `size` by rem_euclid is kept inside.
    (inside as usize).min(size - 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Mitsuba 3.9.1's `bitmap` (scalar_rgb) evaluated at the coordinates below on a 4 × 2
    /// sRGB PNG whose row 0 is red, green, sRGB 128 grey, black and row 1 blue, black, black,
    /// white, decoded to linear here as Mitsuba decodes it (grey 128 is 0.21586).
    fn probe(filter: TextureFilter, wrap: TextureWrap) -> BitmapTexture {
        let grey = Vec3::splat(0.215_861);
        let texels = vec![
            Vec3::X,
            Vec3::Y,
            grey,
            Vec3::ZERO,
            Vec3::Z,
            Vec3::ZERO,
            Vec3::ZERO,
            Vec3::ONE,
        ];
        BitmapTexture::new(4, 2, texels, filter, wrap, Affine2::IDENTITY).unwrap()
    }

    /// A lookup: surface coordinates and Mitsuba's five values there.
    type Lookup = ((f32, f32), [[f32; 3]; 5]);

    /// Per lookup: the surface coordinates, then Mitsuba's bilinear values with repeat, clamp
    /// and mirror wrapping, then its nearest values with repeat and with clamp (mirror gave
    /// the same as clamp at these points), printed to 5 decimals.
    #[rustfmt::skip]
    const MITSUBA: [Lookup; 7] = [
        ((0.125, 0.25), [[1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0]]),
        ((0.25, 0.25), [[0.5, 0.5, 0.0], [0.5, 0.5, 0.0], [0.5, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 1.0, 0.0]]),
        ((0.0, 0.5), [[0.5, 0.25, 0.5], [0.5, 0.0, 0.5], [0.5, 0.0, 0.5], [0.0, 0.0, 1.0], [0.0, 0.0, 1.0]]),
        ((-0.1, 0.1), [[0.34, 0.27, 0.3], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]),
        ((1.05, 0.9), [[0.42, 0.21, 0.7], [1.0, 1.0, 1.0], [1.0, 1.0, 1.0], [0.0, 0.0, 1.0], [1.0, 1.0, 1.0]]),
        ((0.3, 0.75), [[0.0, 0.0, 0.3], [0.0, 0.0, 0.3], [0.0, 0.0, 0.3], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]),
        ((2.3, -0.6), [[0.21, 0.49, 0.09], [0.0, 0.0, 0.0], [0.09, 0.21, 0.21], [0.0, 1.0, 0.0], [0.0, 0.0, 0.0]]),
    ];

    #[test]
    fn lookups_match_mitsuba_for_every_filter_and_wrap_mode() {
        use TextureFilter::{Bilinear, Nearest};
        use TextureWrap::{Clamp, Mirror, Repeat};
        let modes = [
            (Bilinear, Repeat),
            (Bilinear, Clamp),
            (Bilinear, Mirror),
            (Nearest, Repeat),
            (Nearest, Clamp),
        ];
        for (column, (filter, wrap)) in modes.into_iter().enumerate() {
            let texture = probe(filter, wrap);
            for ((u, v), expected) in MITSUBA {
                let want = Vec3::from(expected[column]);
                let got = texture.eval(Vec2::new(u, v));
                // 2e-5 covers Mitsuba's values' rounding to 5 decimals.
                assert!(
                    (got - want).abs().max_element() < 2e-5,
                    "{filter:?} {wrap:?} at ({u}, {v}): {got} against Mitsuba's {want}"
                );
            }
        }
        let mirrored = probe(Nearest, Mirror);
        let clamped = probe(Nearest, Clamp);
        for ((u, v), _) in MITSUBA {
            let uv = Vec2::new(u, v);
            assert_eq!(mirrored.eval(uv), clamped.eval(uv), "nearest at {uv}");
        }
    }

    #[test]
    fn to_uv_moves_the_lookup() {
        let texels = vec![Vec3::X, Vec3::Y, Vec3::Z, Vec3::ONE];
        let scaled = Affine2::from_scale(Vec2::splat(2.0));
        let texture = BitmapTexture::new(
            2,
            2,
            texels,
            TextureFilter::Nearest,
            TextureWrap::Repeat,
            scaled,
        )
        .unwrap();
        // (0.3, 0.1) scaled to (0.6, 0.2): column 1, row 0.
        assert_eq!(texture.eval(Vec2::new(0.3, 0.1)), Vec3::Y);
        // (0.3, 0.3) scaled to (0.6, 0.6): column 1, row 1.
        assert_eq!(texture.eval(Vec2::new(0.3, 0.3)), Vec3::ONE);
    }

    #[test]
    fn a_single_texel_is_constant_everywhere() {
        let colour = Vec3::new(0.2, 0.4, 0.6);
        let texture = BitmapTexture::new(
            1,
            1,
            vec![colour],
            TextureFilter::Bilinear,
            TextureWrap::Repeat,
            Affine2::IDENTITY,
        )
        .unwrap();
        for uv in [(0.0, 0.0), (0.5, 0.5), (0.99, 0.01), (-3.7, 12.2)] {
            let got = texture.eval(Vec2::new(uv.0, uv.1));
            assert!((got - colour).abs().max_element() < 1e-6, "{got} at {uv:?}");
        }
        assert!((texture.mean_luminance() - luminance(colour)).abs() < 1e-6);
        assert!((texture.eval_luminance(Vec2::new(0.3, 0.6)) - luminance(colour)).abs() < 1e-6);
        assert!((luminance(Vec3::ONE) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn bad_sizes_and_values_are_errors() {
        let new = |w, h, texels| {
            BitmapTexture::new(
                w,
                h,
                texels,
                TextureFilter::Bilinear,
                TextureWrap::Repeat,
                Affine2::IDENTITY,
            )
        };
        assert!(new(2, 2, vec![Vec3::ONE; 3]).is_err());
        assert!(new(0, 0, Vec::new()).is_err());
        let err = new(2, 1, vec![Vec3::ONE, Vec3::new(f32::NAN, 0.0, 0.0)]).unwrap_err();
        assert!(err.contains("(1, 0)"), "{err}");
    }

    #[test]
    fn wrapping_far_outside_stays_in_range() {
        for mode in [TextureWrap::Repeat, TextureWrap::Mirror, TextureWrap::Clamp] {
            for i in [-1e9_f32, -7.0, -1.0, 0.0, 3.0, 4.0, 1e9, f32::NAN] {
                assert!(wrap(i, 4, mode) < 4, "{mode:?} {i}");
            }
        }
        assert_eq!(wrap(-1.0, 4, TextureWrap::Repeat), 3);
        assert_eq!(wrap(-1.0, 4, TextureWrap::Mirror), 0);
        assert_eq!(wrap(4.0, 4, TextureWrap::Mirror), 3);
        assert_eq!(wrap(9.0, 4, TextureWrap::Mirror), 1);
    }
}
