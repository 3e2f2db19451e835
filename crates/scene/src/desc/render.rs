//! Descriptions of how the scene is rendered: integrator, camera, film and sampler.

use std::fmt;
use std::str::FromStr;

use glam::{DVec3, Mat4};
use sampling::SamplerKind;

/// The integrator a user asks for, by `strata render --integrator NAME` or by a scene's
/// `<integrator type="NAME">`: one of Strata's presets, named by [`FromStr`] and [`Display`](fmt::Display)
/// (`reference`, `nee`, `mis`, `ris`, `auto`; `path`, Mitsuba's name for its path tracer, is
/// another name for `auto`). The flag overrides the scene's; Mitsuba's integrators (`path`,
/// `volpath`, `direct`, …) ask for `auto`.
///
/// A renderer resolves the preset, with the rest of [`IntegratorDesc`] and the scene's features,
/// into the light transport it runs (`render::plan::Transport`: the reference path tracer
/// or the path tracer with every switch set).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub enum IntegratorPreset {
    /// No tricks: uniform direction sampling, emission counted on hit (the oracle).
    Reference,
    /// BSDF sampling plus next event estimation with power-proportional light selection and
    /// Russian roulette, no MIS.
    Nee,
    /// `nee` plus MIS (power heuristic) between light and BSDF samples.
    Mis,
    /// `mis` with RIS light selection.
    Ris,
    /// The best of these for the scene, leaving out what it does not need (also `path`).
    #[default]
    Auto,
}

impl IntegratorPreset {
    /// Every preset, in the order the command line lists them.
    pub const ALL: [IntegratorPreset; 5] = [
        IntegratorPreset::Reference,
        IntegratorPreset::Nee,
        IntegratorPreset::Mis,
        IntegratorPreset::Ris,
        IntegratorPreset::Auto,
    ];

    /// Other names [`FromStr`] accepts, with the preset each names: `path`, Mitsuba's name for
    /// its path tracer, is `auto`.
    pub const ALIASES: [(&'static str, IntegratorPreset); 1] = [("path", IntegratorPreset::Auto)];

    /// The preset's name: `reference`, `nee`, `mis`, `ris` or `auto`.
    pub fn name(self) -> &'static str {
        match self {
            IntegratorPreset::Reference => "reference",
            IntegratorPreset::Nee => "nee",
            IntegratorPreset::Mis => "mis",
            IntegratorPreset::Ris => "ris",
            IntegratorPreset::Auto => "auto",
        }
    }
}

impl fmt::Display for IntegratorPreset {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for IntegratorPreset {
    type Err = UnknownIntegrator;

    /// The preset called `name` (exactly, as [`IntegratorPreset::name`] or
    /// [`IntegratorPreset::ALIASES`] spell it).
    fn from_str(name: &str) -> Result<Self, Self::Err> {
        IntegratorPreset::ALL
            .map(|preset| (preset.name(), preset))
            .into_iter()
            .chain(IntegratorPreset::ALIASES)
            .find(|&(known, _)| known == name)
            .map(|(_, preset)| preset)
            .ok_or_else(|| UnknownIntegrator(name.to_string()))
    }
}

/// A name that is not an [`IntegratorPreset`]'s; its message lists the names there are.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownIntegrator(pub String);

impl fmt::Display for UnknownIntegrator {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names: Vec<&str> = IntegratorPreset::ALL
            .map(IntegratorPreset::name)
            .into_iter()
            .chain(IntegratorPreset::ALIASES.map(|(name, _)| name))
            .collect();
        write!(
            f,
            "no integrator called '{}' (expected {} or {})",
            self.0,
            names[..names.len() - 1].join(", "),
            names[names.len() - 1]
        )
    }
}

impl std::error::Error for UnknownIntegrator {}

/// Mitsuba's `direct` integrator: direct illumination only, by `emitter_samples` light samples
/// and `bsdf_samples` BSDF samples at the camera ray's hit, combined by the power heuristic over
/// the counts. With at least one of each, the same expectation as a path tracer with
/// `max_depth` 2; zero of a kind leaves out what only that kind reaches (delta lights; what a
/// mirror or glass shows).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DirectDesc {
    /// Light samples per camera sample (Mitsuba's `emitter_samples`, default 1).
    pub emitter_samples: u32,
    /// BSDF samples per camera sample (Mitsuba's `bsdf_samples`, default 1).
    pub bsdf_samples: u32,
}

/// The `<integrator>` element with Mitsuba's defaults.
#[derive(Debug, Clone, PartialEq)]
pub struct IntegratorDesc {
    /// The preset the scene asks for: the one `type` names for Strata's presets, `auto` for
    /// Mitsuba's integrators.
    pub preset: IntegratorPreset,
    /// Mitsuba's `direct` integrator's sample counts, `None` for the path tracers. Direct
    /// lighting is rendered with whichever preset's techniques.
    pub direct: Option<DirectDesc>,
    /// Longest path in vertices after the camera (Mitsuba's meaning: 1 shows only directly visible
    /// emitters, 2 adds direct lighting); -1 means unlimited. Default -1; `direct` is always 2.
    pub max_depth: i32,
    /// Path depth at which Russian roulette starts (Mitsuba's `rr_depth`, default 5, at least 1).
    pub rr_depth: u32,
    /// Whether emitters seen directly by the camera are hidden (default false).
    pub hide_emitters: bool,
    /// Mitsuba's volumetric path tracers (`volpath`, `volpathmis`, `prbvolpath`): a pass straight
    /// through a null lobe (`null`, a mask's transparency, a thin dielectric's transmission) is
    /// not a path vertex and does not count towards `max_depth`. False for `path`, `prb`,
    /// `direct` and Strata's presets.
    pub skip_null_vertices: bool,
}

/// The image axis that a field of view applies to (`fov_axis`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FovAxis {
    /// The horizontal axis (Mitsuba's default when `fov` is given).
    X,
    /// The vertical axis.
    Y,
    /// The image diagonal (used for the focal-length default).
    Diagonal,
    /// The shorter image side.
    Smaller,
    /// The longer image side.
    Larger,
}

/// A thin lens (`<sensor type="thinlens">`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThinLensDesc {
    /// Lens radius in world units (0 behaves as a pinhole).
    pub aperture_radius: f32,
    /// Distance along the view direction that is in focus, world units (default: `far_clip`).
    pub focus_distance: f32,
}

/// The camera (`<sensor type="perspective">` or `"thinlens"`).
///
/// The camera looks down its local +z; its local +x is image-left and +y image-up (Mitsuba's
/// convention), and its `to_world` places it in the world (rotation and translation only; mirroring
/// is allowed, scaling is an error as in Mitsuba). The translation is kept apart, in double
/// precision, as `position`: the description's frame is centred on the camera.
#[derive(Debug, Clone, PartialEq)]
pub struct SensorDesc {
    /// Camera-to-scene-frame transform: the scene file's `to_world` without its translation (the
    /// scene frame is world space translated by `-position`), so the camera sits at the origin.
    pub to_world: Mat4,
    /// The camera's position in world space (world units, double precision): the translation of
    /// the scene file's `to_world`, subtracted from every position of the description.
    pub position: DVec3,
    /// Field of view in degrees along `fov_axis`, strictly between 0 and 180. Without `fov` it comes
    /// from `focal_length` (default 50 mm on 36×24 mm film) as Mitsuba does: a diagonal field of view.
    pub fov_deg: f32,
    /// The axis `fov_deg` refers to; use [`SensorDesc::x_fov_deg`] for the horizontal value.
    pub fov_axis: FovAxis,
    /// Near clip distance along the view direction, world units (default 0.01).
    pub near_clip: f32,
    /// Far clip distance along the view direction, world units (default 10000).
    pub far_clip: f32,
    /// The thin lens, `None` for a pinhole camera.
    pub lens: Option<ThinLensDesc>,
    /// Where the principal point lies relative to the film's centre, as fractions of the film's
    /// width and height (`perspective`'s `principal_point_offset_x` and `_y`, default 0): a
    /// film position `(u, v)` (fractions, from the top left) sees what the centred camera sees at
    /// `(u + x, v + y)`.
    pub principal_point_offset: [f32; 2],
    /// Mitsuba's `orthographic` sensor: parallel rays along the camera's +z from its near plane,
    /// over x ∈ [−1, 1] and y ∈ [−1/aspect, 1/aspect] of its frame (`to_world` may scale that
    /// region); the field of view, lens and principal point do not apply.
    pub orthographic: bool,
    /// The shutter's opening and closing times, `shutter_open` ≤ `shutter_close` (scene time
    /// units, both 0 by default as in Mitsuba 3): the interval a camera sample's time is drawn
    /// from once something in the scene moves.
    pub shutter: [f64; 2],
    /// For a moving camera (an `<animation>` as its `to_world`): its camera-to-scene-frame
    /// transform over time, translated like `to_world` by `-position` (`to_world` and `position`
    /// are then where it is when the shutter opens).
    pub motion: Option<geometry::AnimatedTransform>,
}

impl SensorDesc {
    /// The horizontal field of view in degrees for an image of `width`×`height` pixels, converted
    /// from `fov_deg` along `fov_axis` exactly as Mitsuba's `parse_fov` does.
    pub fn x_fov_deg(&self, width: u32, height: u32) -> f32 {
        let aspect = f64::from(width) / f64::from(height);
        let fov = f64::from(self.fov_deg).to_radians();
        let axis = match self.fov_axis {
            FovAxis::Smaller if aspect > 1.0 => FovAxis::Y,
            FovAxis::Smaller => FovAxis::X,
            FovAxis::Larger if aspect > 1.0 => FovAxis::X,
            FovAxis::Larger => FovAxis::Y,
            other => other,
        };
        let x_fov = match axis {
            FovAxis::Y => 2.0 * ((0.5 * fov).tan() * aspect).atan(),
            FovAxis::Diagonal => {
                let diagonal = 2.0 * (0.5 * fov).tan();
                let width = diagonal / (1.0 + 1.0 / (aspect * aspect)).sqrt();
                2.0 * (0.5 * width).atan()
            }
            _ => fov,
        };
        x_fov.to_degrees() as f32
    }
}

/// The pixel reconstruction filter (`<rfilter>`, Mitsuba default: gaussian with stddev 0.5).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FilterDesc {
    /// `box`: each sample counts for the pixel it falls in (radius 0.5 pixel).
    Box,
    /// `tent`: triangle filter of the given radius in pixels (default 1).
    Tent {
        /// Radius in pixels.
        radius: f32,
    },
    /// `gaussian`: Gaussian of the given standard deviation in pixels, cut off at 4 standard
    /// deviations (default stddev 0.5).
    Gaussian {
        /// Standard deviation in pixels.
        stddev: f32,
    },
    /// `mitchell`: the Mitchell–Netravali cubic of radius 2 pixels (defaults `B = C = 1/3`).
    Mitchell {
        /// Mitsuba's `B`.
        b: f32,
        /// Mitsuba's `C`.
        c: f32,
    },
    /// `catmullrom`: the Catmull–Rom cubic (Mitchell–Netravali with `B = 0`, `C = 1/2`).
    CatmullRom,
    /// `lanczos`: a windowed sinc of radius `lobes` pixels (default 3).
    Lanczos {
        /// Number of lobes, 1 to 16.
        lobes: u32,
    },
}

/// The film (`<film type="hdrfilm">`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FilmDesc {
    /// Width in pixels of the image rendered: the crop window's (`crop_width`), by default the
    /// whole film's (`width`, default 768).
    pub width: u32,
    /// Height in pixels of the image rendered: the crop window's (`crop_height`), by default the
    /// whole film's (`height`, default 576).
    pub height: u32,
    /// Width and height in pixels of the whole film, which the camera's view spans.
    pub full_size: [u32; 2],
    /// The crop window's top-left pixel in the whole film (`crop_offset_x`, `crop_offset_y`,
    /// default 0).
    pub crop_offset: [u32; 2],
    /// Reconstruction filter.
    pub filter: FilterDesc,
}

impl FilmDesc {
    /// The whole film resized to `width` × `height` pixels, without a crop window.
    pub fn resized(self, width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            full_size: [width, height],
            crop_offset: [0, 0],
            ..self
        }
    }
}

/// The `<sampler>` element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SamplerDesc {
    /// The Strata sampler nearest to the file's Mitsuba sampler: `stratified`, `multijitter`
    /// and `orthogonal` are [`SamplerKind::Stratified`], `ldsampler` (a scrambled (0, 2)-sequence)
    /// is [`SamplerKind::Sobol`]; any other [`SamplerKind`] name (`bluenoise`, `sobol`) is that
    /// sampler, as on the command line. `None` for `independent`, Mitsuba's default, which nearly every
    /// Mitsuba file writes and which so carries no intent (also when the file has no
    /// `<sampler>`): a renderer then uses independent samples unless it picks its own (`strata
    /// render`'s `auto` takes Sobol).
    pub kind: Option<SamplerKind>,
    /// Samples per pixel as written in the file (default 4); see
    /// [`SamplerDesc::mitsuba_sample_count`] for the count Mitsuba actually renders.
    pub sample_count: u32,
    /// The samples per pixel Mitsuba renders the file's sampler with: `stratified` rounds
    /// `sample_count` up to a square, `multijitter` to a near-square product, `ldsampler` to a
    /// square of a power of two and `orthogonal` to the square of a prime.
    pub mitsuba_sample_count: u64,
    /// Seed offset (default 0).
    pub seed: u32,
}
