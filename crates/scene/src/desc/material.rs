//! Descriptions of materials and lights.

use glam::{Mat3, Vec3};
use materials::BitmapTexture;
use std::sync::Arc;

/// The roughness of a microfacet BSDF: α along the shading frame's first tangent (∂p/∂u) and
/// along its second, Mitsuba's `alpha_u` and `alpha_v` (both `alpha` when isotropic), positive.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Roughness {
    /// α along the first tangent.
    pub u: f32,
    /// α along the second tangent.
    pub v: f32,
}

impl Roughness {
    /// The same α in every direction.
    pub fn isotropic(alpha: f32) -> Self {
        Self { u: alpha, v: alpha }
    }
}

/// Microfacet normal distribution of a rough conductor.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MicrofacetDistribution {
    /// Beckmann (Mitsuba's default for `roughconductor`).
    Beckmann,
    /// GGX / Trowbridge–Reitz.
    Ggx,
}

/// A BSDF (`<bsdf type="...">`). Every BSDF except `TwoSided` is one-sided, as in Mitsuba: seen
/// from the back (against the shading normal) it is black. Colours are linear RGB.
#[derive(Debug, Clone, PartialEq)]
pub enum BsdfDesc {
    /// `diffuse`: Lambertian reflection.
    Diffuse {
        /// Albedo, each channel in [0, 1] (default 0.5).
        reflectance: Vec3,
    },
    /// `conductor`: smooth metal, a perfect mirror weighted by the conductor Fresnel term.
    /// `material="none"` (the default) is eta = 0, k = 1, whose Fresnel reflectance is exactly 1;
    /// `Ag`, `Al`, `Au`, `Cr`, `Cu` give Mitsuba's measured metals converted to RGB.
    Conductor {
        /// Real part of the relative index of refraction, per channel.
        eta: Vec3,
        /// Imaginary part (absorption), per channel.
        k: Vec3,
        /// Multiplier on the reflected light, each channel in [0, 1] (default 1).
        specular_reflectance: Vec3,
    },
    /// `roughconductor`: microfacet metal.
    RoughConductor {
        /// Microfacet distribution (default Beckmann).
        distribution: MicrofacetDistribution,
        /// Roughness (default α = 0.1), possibly anisotropic.
        alpha: Roughness,
        /// Real part of the relative index of refraction, per channel.
        eta: Vec3,
        /// Imaginary part (absorption), per channel.
        k: Vec3,
        /// Multiplier on the reflected light, each channel in [0, 1] (default 1).
        specular_reflectance: Vec3,
    },
    /// `dielectric`: smooth glass-like interface with reflection and refraction.
    Dielectric {
        /// Index of refraction inside (on the side opposite the normal), default bk7 = 1.5046.
        int_ior: f32,
        /// Index of refraction outside, default air = 1.000277.
        ext_ior: f32,
        /// Multiplier on reflection, each channel in [0, 1] (default 1).
        specular_reflectance: Vec3,
        /// Multiplier on transmission, each channel in [0, 1] (default 1).
        specular_transmittance: Vec3,
    },
    /// `roughdielectric`: a rough glass-like interface, reflecting and refracting by microfacets.
    RoughDielectric {
        /// Microfacet distribution (default Beckmann).
        distribution: MicrofacetDistribution,
        /// Roughness (default α = 0.1), possibly anisotropic.
        alpha: Roughness,
        /// Index of refraction inside (on the side opposite the normal), default bk7 = 1.5046.
        int_ior: f32,
        /// Index of refraction outside, default air = 1.000277.
        ext_ior: f32,
        /// Multiplier on reflection, each channel in [0, 1] (default 1).
        specular_reflectance: Vec3,
        /// Multiplier on transmission, each channel in [0, 1] (default 1).
        specular_transmittance: Vec3,
    },
    /// `thindielectric`: a thin pane of a dielectric, reflecting and letting light straight
    /// through.
    ThinDielectric {
        /// Index of refraction of the pane, default bk7 = 1.5046.
        int_ior: f32,
        /// Index of refraction around it, default air = 1.000277.
        ext_ior: f32,
        /// Multiplier on reflection, each channel in [0, 1] (default 1).
        specular_reflectance: Vec3,
        /// Multiplier on transmission, each channel in [0, 1] (default 1).
        specular_transmittance: Vec3,
    },
    /// `plastic`: a diffuse base under a smooth dielectric coating.
    Plastic {
        /// Index of refraction of the coating, default polypropylene = 1.49.
        int_ior: f32,
        /// Index of refraction outside, default air = 1.000277.
        ext_ior: f32,
        /// Albedo of the base, each channel in [0, 1] (default 0.5).
        diffuse_reflectance: Vec3,
        /// Multiplier on the coating's reflection, each channel in [0, 1] (default 1).
        specular_reflectance: Vec3,
        /// Whether internal scattering shifts the base's colour (Mitsuba's `nonlinear`,
        /// default false).
        nonlinear: bool,
    },
    /// `roughplastic`: a diffuse base under a rough dielectric coating.
    RoughPlastic {
        /// Microfacet distribution of the coating (default Beckmann).
        distribution: MicrofacetDistribution,
        /// Roughness α of the coating (default 0.1), positive.
        alpha: f32,
        /// Index of refraction of the coating, default polypropylene = 1.49.
        int_ior: f32,
        /// Index of refraction outside, default air = 1.000277.
        ext_ior: f32,
        /// Albedo of the base, each channel in [0, 1] (default 0.5).
        diffuse_reflectance: Vec3,
        /// Multiplier on the coating's reflection, each channel in [0, 1] (default 1).
        specular_reflectance: Vec3,
        /// Whether internal scattering shifts the base's colour (default false).
        nonlinear: bool,
    },
    /// `blendbsdf`: `(1 − weight)` of `first` plus `weight` of `second`.
    Blend {
        /// The BSDF at weight 0 (the first nested one).
        first: Box<BsdfDesc>,
        /// The BSDF at weight 1.
        second: Box<BsdfDesc>,
        /// The blend weight in [0, 1].
        weight: f32,
    },
    /// A BSDF whose one textured parameter is a `checkerboard` texture: `even` is the BSDF
    /// with the texture's `color0` in its place, `odd` with its `color1`; with (u, v) = `to_uv`
    /// applied to a hit's surface coordinates, `odd` applies where exactly one of the fractional
    /// parts of u and v exceeds ½ (Mitsuba's pattern).
    Checkerboard {
        /// The BSDF where the pattern shows `color0`.
        even: Box<BsdfDesc>,
        /// The BSDF where it shows `color1`.
        odd: Box<BsdfDesc>,
        /// Mitsuba's `to_uv` as two rows: u' = row 0 · (u, v, 1), v' = row 1 · (u, v, 1)
        /// (default identity).
        to_uv: [[f32; 3]; 2],
    },
    /// A BSDF whose diffuse albedo is a `bitmap` texture: `base`, with its albedo the texture's
    /// mean luminance (which Mitsuba's lobe-sampling weights use), and at each hit the texture's
    /// value in its place. `base` is `diffuse`, `plastic`, `roughplastic`, or a `twosided` of those.
    DiffuseBitmap {
        /// The BSDF with the texture's mean as its albedo.
        base: Box<BsdfDesc>,
        /// The texture.
        texture: Arc<BitmapTexture>,
    },
    /// A `blendbsdf` (or `mask`) with `bitmap` textures: its weight a bitmap's luminance
    /// (clamped to [0, 1]), either BSDF's diffuse albedo a bitmap, or both. `base` is the blend
    /// with each texture's mean in its place (the weight's mean luminance, a BSDF's albedo as
    /// [`BsdfDesc::DiffuseBitmap`] has it), and at each hit the textures' values take their places.
    TexturedBlend {
        /// The blend with the textures' means.
        base: Box<BsdfDesc>,
        /// The texture of the weight, if any.
        weight: Option<Arc<BitmapTexture>>,
        /// The textures of the first and the second BSDF's diffuse albedos, if any.
        reflectances: [Option<Arc<BitmapTexture>>; 2],
    },
    /// A BSDF that its plugin's reader built at once from the XML parameters (see the plugin list
    /// in the loader): new plugins need no variant of their own here nor a case in the scene
    /// builder.
    Built(materials::Bsdf),
    /// `twosided`: `front` on the front side and `back` on the back side (the back side sees the
    /// BSDF as if the surface were turned around). With one nested BSDF, `back` equals `front`.
    TwoSided {
        /// BSDF of the side the normal points to.
        front: Box<BsdfDesc>,
        /// BSDF of the other side.
        back: Box<BsdfDesc>,
    },
}

impl BsdfDesc {
    /// Mitsuba's BSDF for shapes that name none: diffuse with reflectance 0.5.
    pub fn default_diffuse() -> Self {
        BsdfDesc::Diffuse {
            reflectance: Vec3::splat(0.5),
        }
    }
}

/// An area light attached to a shape (`<emitter type="area">` inside `<shape>`). It emits only
/// from the front side (the side the shape's normal points to), as in Mitsuba.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AreaEmitterDesc {
    /// Emitted radiance, linear RGB, W/(m²·sr) per channel (default 1).
    pub radiance: Vec3,
    /// How often light sampling chooses this emitter relative to the others (Mitsuba's
    /// `sampling_weight`, positive, default 1): it multiplies the selection weight and changes
    /// only the noise.
    pub sampling_weight: f32,
}

/// A light that is not attached to a shape.
#[derive(Debug, Clone, PartialEq)]
pub enum EmitterDesc {
    /// `point`: an isotropic point light.
    Point {
        /// Position (`position`, or the translation of `to_world`; default the world's origin),
        /// relative to the camera ([`crate::SensorDesc::position`]).
        position: Vec3,
        /// Radiant intensity, linear RGB, W/sr per channel (default 1).
        intensity: Vec3,
        /// Selection weight, as [`AreaEmitterDesc::sampling_weight`].
        sampling_weight: f32,
    },
    /// `spot`: a point light shining along its axis, with Mitsuba's angular falloff.
    Spot {
        /// Position (the translation of `to_world`; default the world's origin), relative to the
        /// camera ([`crate::SensorDesc::position`]).
        position: Vec3,
        /// The linear part of `to_world`, whose +z column is the axis (default identity).
        axes: Mat3,
        /// Radiant intensity on the axis, linear RGB, W/sr per channel (default 1).
        intensity: Vec3,
        /// Angle from the axis beyond which nothing is emitted, degrees in (0, 180] (default 20).
        cutoff_angle: f32,
        /// Angle up to which the full intensity is emitted, degrees ≥ 0 (default 3/4 of the
        /// cutoff); the falloff is linear in angle between the two.
        beam_width: f32,
        /// Selection weight, as [`AreaEmitterDesc::sampling_weight`].
        sampling_weight: f32,
    },
    /// `directional`: parallel light arriving from infinitely far away.
    Directional {
        /// Unit world direction in which the light travels (`direction`, or `to_world` applied to
        /// +z; default +z).
        direction: Vec3,
        /// Irradiance on a surface facing the light, linear RGB, W/m² per channel (default 1).
        irradiance: Vec3,
        /// Selection weight, as [`AreaEmitterDesc::sampling_weight`].
        sampling_weight: f32,
    },
    /// `constant`: radiance arriving uniformly from every direction at infinity.
    Constant {
        /// Radiance, linear RGB, W/(m²·sr) per channel (default 1).
        radiance: Vec3,
        /// Selection weight, as [`AreaEmitterDesc::sampling_weight`].
        sampling_weight: f32,
    },
    /// `envmap`: radiance at infinity from a latitude-longitude image (read from its
    /// `filename` when the scene is parsed).
    EnvMap {
        /// Texels per row of the image.
        width: u32,
        /// Rows of the image.
        height: u32,
        /// Linear RGB radiance, W/(m²·sr) per channel, row-major from the top row.
        texels: Vec<Vec3>,
        /// Multiplier on the image (default 1).
        scale: f32,
        /// The linear part of `to_world`, which turns the map's frame (+y up) into the world's
        /// (default identity).
        to_world: Mat3,
        /// Selection weight, as [`AreaEmitterDesc::sampling_weight`].
        sampling_weight: f32,
    },
}

impl EmitterDesc {
    /// The emitter's selection weight ([`AreaEmitterDesc::sampling_weight`]).
    pub fn sampling_weight(&self) -> f32 {
        match *self {
            EmitterDesc::Point {
                sampling_weight, ..
            }
            | EmitterDesc::Spot {
                sampling_weight, ..
            }
            | EmitterDesc::Directional {
                sampling_weight, ..
            }
            | EmitterDesc::Constant {
                sampling_weight, ..
            }
            | EmitterDesc::EnvMap {
                sampling_weight, ..
            } => sampling_weight,
        }
    }

    /// The position of a light at a point (world units; relative to the camera once the
    /// description is built), `None` for lights at infinity: what moving the scene's origin
    /// moves.
    pub(crate) fn position_mut(&mut self) -> Option<&mut Vec3> {
        match self {
            EmitterDesc::Point { position, .. } | EmitterDesc::Spot { position, .. } => {
                Some(position)
            }
            EmitterDesc::Directional { .. }
            | EmitterDesc::Constant { .. }
            | EmitterDesc::EnvMap { .. } => None,
        }
    }
}
