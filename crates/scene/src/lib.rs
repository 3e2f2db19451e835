//! Loads scenes written in a subset of Mitsuba 3's XML format into a plain [`SceneDesc`].
//!
//! The description is data only — world-space triangle meshes and spheres, BSDF and light
//! parameters, camera, film, sampler and integrator settings with Mitsuba's defaults filled in —
//! so that the same file renders in Mitsuba 3 and in Strata. Turning it into runtime objects is
//! left to the renderer.
//!
//! ```no_run
//! let overrides = vec![("spp".to_string(), "64".to_string())];
//! match scene::parse_file("scenes/cornell.xml".as_ref(), &overrides) {
//!     Ok(desc) => println!("{} shapes, {} bsdfs", desc.shapes.len(), desc.bsdfs.len()),
//!     Err(e) => eprintln!("{e}"), // scenes/cornell.xml:12:5: <shape type="foo">: unknown shape type ...
//! }
//! ```
//!
//! # What is supported
//! - `<default name value>` and `$name` substitution in every attribute (`\$` is a literal `$`);
//!   overrides passed to [`parse_file`] win over defaults and must be used by the file.
//! - `<include filename>`, `<ref id>` to BSDFs (forward references allowed), property tags
//!   `float integer boolean string point vector rgb spectrum transform` (a `<spectrum>` must be a
//!   single value), and `translate rotate scale lookat matrix` inside `<transform>`, composed in
//!   document order.
//! - `integrator`: path (and volpath, volpathmis: the path tracer, since no scene Strata reads
//!   has media), direct. `sensor`: perspective, thinlens, orthographic. `film`: hdrfilm.
//!   `rfilter`: box, tent, gaussian, mitchell, catmullrom, lanczos. `sampler`: independent,
//!   stratified, multijitter, ldsampler, orthogonal, and Strata's own by their command-line
//!   names (bluenoise, sobol). `shape`: obj, ply, rectangle, cube, disk,
//!   sphere, cylinder, shapegroup and instance (baked into world space).
//!   `bsdf`: diffuse, conductor, roughconductor, dielectric, roughdielectric, thindielectric,
//!   plastic, roughplastic, twosided, blendbsdf. `emitter`: area (in a shape), point, spot,
//!   directional, constant, envmap (OpenEXR images).
//!
//! Anything else — an unknown element, plugin or parameter, a malformed value, a missing mesh —
//! is a [`LoadError`] naming the file, line, column and element, never silently ignored.
//!
//! # Conventions
//! Meshes are baked into world space. A `to_world` that mirrors, or `flip_normals`, reverses the
//! triangle winding (both together cancel), and given vertex normals follow the inverse transpose
//! and are negated by `flip_normals`, so geometric and shading normals always agree: Mitsuba's
//! current `Mesh` behaviour. (Mitsuba 3.9's release instead kept the winding under mirroring
//! transforms, so there a mirrored mesh's geometric normal points against its shading normal.)
//! Meshes without normals get angle-weighted smooth normals unless `face_normals` is set, as in
//! Mitsuba. The disk is a fan of 128 triangles whose area equals the disk's, the cylinder a band
//! of 256 facets whose area equals the tube's.

#![warn(missing_docs)]

mod build;
mod camera;
mod cie_tables;
mod desc;
mod error;
mod exr_image;
mod features;
mod image_file;
mod ior;
mod jpeg_image;
pub mod limits;
mod loader;
mod mesh;
mod params;
mod plugins;
mod png_image;
mod rebase;
mod rgbe_image;
mod spectrum;
mod xml;

use std::path::Path;

pub use build::{RenderScene, build};
pub use camera::{Camera, ThinLens};
pub use desc::{
    AreaEmitterDesc, BsdfDesc, DirectDesc, EmitterDesc, FilmDesc, FilterDesc, FovAxis, Geometry,
    IntegratorDesc, IntegratorPreset, MeshDesc, MicrofacetDistribution, Roughness, SamplerDesc,
    SceneDesc, SensorDesc, ShapeDesc, SphereDesc, ThinLensDesc, UnknownIntegrator,
};
pub use error::LoadError;
pub use features::SceneFeatures;

/// Loads the Mitsuba 3 scene file at `path`.
///
/// `overrides` are `(name, value)` pairs for `$name` parameters (the `-D name=value` of a command
/// line); they take precedence over `<default>` elements, and one the file never uses is an error.
/// Relative mesh and include paths are resolved against the directory of the file that names them.
pub fn parse_file(path: &Path, overrides: &[(String, String)]) -> Result<SceneDesc, LoadError> {
    loader::load(path, overrides)
}

/// Loads a scene from `text`, the contents of a Mitsuba 3 scene file, as [`parse_file`] would load
/// it from `path`: `path` names the file in error messages, and relative mesh and include paths are
/// resolved against its directory. `text` need not be valid UTF-8 (that is reported as an error).
pub fn parse_bytes(
    text: &[u8],
    path: &Path,
    overrides: &[(String, String)],
) -> Result<SceneDesc, LoadError> {
    loader::load_text(path, text, overrides)
}

/// Reads the scene file at `path` (at most [`limits::MAX_SCENE_FILE_BYTES`]) for
/// [`parse_bytes`]; the error names the file.
pub fn read_scene_file(path: &Path) -> Result<Vec<u8>, LoadError> {
    limits::read_at_most(path, limits::MAX_SCENE_FILE_BYTES).map_err(|e| LoadError {
        file: path.to_path_buf(),
        line: 0,
        column: 0,
        element: String::new(),
        message: format!("cannot read \"{}\": {e}", path.display()),
    })
}

/// Parses the contents of a Wavefront OBJ file (the whole file is one mesh, in the file's own
/// coordinates, not yet placed in the world). `flip_tex_coords` replaces v by 1 − v, Mitsuba's
/// default for OBJ. Errors start with the 1-based line (`line N: …`).
pub fn parse_obj(bytes: &[u8], flip_tex_coords: bool) -> Result<MeshDesc, String> {
    mesh::obj::parse_obj(bytes, flip_tex_coords)
}

/// Parses the contents of a PLY file (ascii or binary), in the file's own coordinates. The header's
/// element counts are checked against the data's length before anything is allocated.
pub fn parse_ply(bytes: &[u8]) -> Result<MeshDesc, String> {
    mesh::ply::parse_ply(bytes)
}

/// Loads the scene file at `path` (see [`parse_file`]) and builds it into a [`RenderScene`].
pub fn load(path: &Path, overrides: &[(String, String)]) -> Result<RenderScene, LoadError> {
    build(parse_file(path, overrides)?)
}
