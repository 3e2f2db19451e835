//! `<shape>`: obj, ply, serialized, rectangle, cube, disk, cylinder and sphere, with their BSDF
//! and area emitter.

use glam::{DMat3, DMat4, DVec3};

use super::bsdf::BsdfTable;
use super::emitter::area_emitter;
use super::{unexpected_child, unknown_type};
use crate::desc::{Geometry, MeshDesc, ShapeDesc, SphereDesc};
use crate::error::{Loc, Result};
use crate::mesh::canonical::{cube, cylinder, disk, rectangle};
use crate::mesh::obj::read_obj;
use crate::mesh::place::{Mirroring, Shading, place};
use crate::mesh::ply::read_ply;
use crate::mesh::serialized::read_serialized;
use crate::params::{Params, Placement};
use crate::xml::tree::{Child, ObjectNode};

/// The shape plugins this loader understands.
const SUPPORTED: [&str; 8] = [
    "obj",
    "ply",
    "serialized",
    "rectangle",
    "cube",
    "disk",
    "sphere",
    "cylinder",
];

/// Interprets a `<shape>` element, placed relative to `origin` (world space: its `to_world`
/// followed by a translation by `-origin`, in double precision); its BSDF goes into `bsdfs`.
pub(crate) fn shape<'a>(
    node: &'a ObjectNode,
    bsdfs: &mut BsdfTable<'a>,
    origin: DVec3,
) -> Result<ShapeDesc> {
    if !SUPPORTED.contains(&node.plugin.as_str()) {
        return Err(unknown_type(node, &SUPPORTED));
    }
    let mut bsdf = None;
    let mut emitter = None;
    for child in &node.children {
        let allowed = "one <bsdf> or <ref id=\"...\"/> to a bsdf, and one <emitter type=\"area\"> or <ref> to one";
        // A reference names a BSDF, or an area emitter declared at the top level.
        let (object, reference) = match child {
            Child::Object(object) => (Some(object), None),
            Child::Ref(reference) => (bsdfs.referenced_emitter(reference), Some(reference)),
        };
        match (object, reference) {
            (Some(object), _) if object.tag == "emitter" && emitter.is_none() => {
                emitter = Some(area_emitter(object)?);
            }
            (Some(object), None) if object.tag == "bsdf" && bsdf.is_none() => {
                bsdf = Some(bsdfs.add(object)?);
            }
            (None, Some(reference)) if bsdf.is_none() => {
                bsdf = Some(bsdfs.reference(reference)?);
            }
            _ => return Err(unexpected_child(node, child, allowed)),
        }
    }

    let mut params = Params::new(node);
    // A moving shape keeps its geometry in object space and its motion beside it.
    let (to_world, motion) = match params.placement("to_world")? {
        None => (DMat4::IDENTITY, None),
        Some(Placement::Fixed(m)) => (m, None),
        Some(Placement::Animated(animation)) => {
            if animation.mirrors() {
                return Err(params
                    .loc_of("to_world")
                    .error("an animated to_world must not mirror (use flip_normals)"));
            }
            (DMat4::IDENTITY, Some(animation.translated(-origin)))
        }
    };
    let to_world_loc = params.loc_of("to_world");
    check_invertible(&to_world, to_world_loc)?;
    let to_world = if motion.is_some() {
        to_world
    } else {
        DMat4::from_translation(-origin) * to_world
    };
    let flip_normals = params.boolean_or("flip_normals", false)?;
    let geometry = match node.plugin.as_str() {
        "sphere" => Geometry::Sphere(sphere(&mut params, &to_world, flip_normals)?),
        "cylinder" => {
            let object_to_world = to_world * cylinder_frame(&mut params)?;
            let placed = place(
                cylinder(),
                &object_to_world,
                flip_normals,
                Shading::Smooth,
                Mirroring::KeepsSides,
            )
            .map_err(|e| to_world_loc.error(e))?;
            Geometry::Mesh(placed)
        }
        plugin => {
            let (mesh, shading) = match plugin {
                "obj" | "ply" | "serialized" => mesh_file(&mut params, plugin)?,
                "rectangle" => (rectangle(), Shading::Flat),
                "disk" => (disk(), Shading::Flat),
                _ => {
                    // Accepted for Mitsuba compatibility: the cube is flat-shaded either way.
                    params.boolean_or("face_normals", false)?;
                    (cube(), Shading::Flat)
                }
            };
            let mirroring = if matches!(plugin, "obj" | "ply" | "serialized") {
                Mirroring::TurnsSides
            } else {
                Mirroring::KeepsSides
            };
            let placed = place(mesh, &to_world, flip_normals, shading, mirroring)
                .map_err(|e| to_world_loc.error(e))?;
            Geometry::Mesh(placed)
        }
    };
    params.finish()?;
    Ok(ShapeDesc {
        plugin: node.plugin.clone(),
        id: node.id.clone(),
        geometry,
        bsdf: match (bsdf, &emitter) {
            (Some(index), _) => index,
            // Mitsuba gives an emitter without a BSDF a black one: it emits but reflects nothing.
            (None, Some(_)) => bsdfs.black_bsdf(),
            (None, None) => bsdfs.default_bsdf(),
        },
        emitter,
        motion,
    })
}

/// Fails unless `m` is finite and invertible.
pub(crate) fn check_invertible(m: &DMat4, loc: &Loc) -> Result<()> {
    let linear = DMat3::from_mat4(*m);
    let scale = linear.x_axis.length() * linear.y_axis.length() * linear.z_axis.length();
    let det = linear.determinant();
    let singular = det.abs() <= 1e-12 * scale || det.is_nan();
    if !m.is_finite() || singular || !linear.inverse().is_finite() {
        return Err(loc.error("to_world is not invertible (a zero scale?)"));
    }
    Ok(())
}

/// An `obj`, `ply` or `serialized` mesh (mesh `shape_index` of the file) read from `filename`
/// (relative to the scene file's directory).
fn mesh_file(params: &mut Params, plugin: &str) -> Result<(MeshDesc, Shading)> {
    let (filename, loc) = params.string("filename")?.ok_or_else(|| {
        params
            .loc()
            .error("missing required parameter \"filename\"")
    })?;
    let face_normals = params.boolean_or("face_normals", false)?;
    let flip_tex_coords =
        plugin != "serialized" && params.boolean_or("flip_tex_coords", plugin == "obj")?;
    let shape_index = if plugin == "serialized" {
        params.integer_in("shape_index", 0, 0, i64::from(u32::MAX))? as u32
    } else {
        0
    };
    let dir = loc.file.parent().unwrap_or(std::path::Path::new(""));
    let path = dir.join(filename);
    if !path.is_file() {
        return Err(loc.error(format!("mesh file \"{}\" not found", path.display())));
    }
    let result = match plugin {
        "obj" => read_obj(&path, flip_tex_coords),
        "ply" => read_ply(&path),
        _ => read_serialized(&path, shape_index),
    };
    let mut mesh = result.map_err(|e| {
        loc.error(format!(
            "cannot load {} file \"{}\": {e}",
            plugin.to_uppercase(),
            path.display()
        ))
    })?;
    if plugin == "ply"
        && flip_tex_coords
        && let Some(uvs) = mesh.uvs.as_mut()
    {
        for uv in uvs {
            uv.y = 1.0 - uv.y;
        }
    }
    if mesh.triangles.is_empty() {
        return Err(loc.error(format!(
            "mesh file \"{}\" contains no faces",
            path.display()
        )));
    }
    let shading = if face_normals {
        Shading::Flat
    } else {
        Shading::Smooth
    };
    Ok((mesh, shading))
}

/// The cylinder's `p0` (default origin), `p1` (default +z) and `radius` (default 1) as the
/// transform of the unit cylinder: Mitsuba's translate(p0) · to_frame(p1 − p0) · scale(r, r, |p1 −
/// p0|), the frame built around the axis as Mitsuba's `coordinate_system` builds it.
fn cylinder_frame(params: &mut Params) -> Result<DMat4> {
    let p0 = params.point("p0")?.unwrap_or(DVec3::ZERO);
    let p1 = params.point("p1")?.unwrap_or(DVec3::Z);
    let radius = params.float_or("radius", 1.0)?;
    if !(radius > 0.0 && radius.is_finite()) {
        return Err(params
            .loc_of("radius")
            .error(format!("radius must be positive, got {radius}")));
    }
    let axis = p1 - p0;
    let length = axis.length();
    if !(length > 0.0 && length.is_finite()) {
        return Err(params
            .loc_of("p1")
            .error("p0 and p1 must be distinct finite points"));
    }
    let n = axis / length;
    // Duff et al. 2017, "Building an orthonormal basis, revisited" (Mitsuba's coordinate_system).
    let sign = 1.0_f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    let s = DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    let t = DVec3::new(b, sign + n.y * n.y * a, -n.y);
    Ok(DMat4::from_translation(p0)
        * DMat4::from_cols(s.extend(0.0), t.extend(0.0), n.extend(0.0), glam::DVec4::W)
        * DMat4::from_scale(DVec3::new(radius, radius, length)))
}

/// A sphere placed by `to_world`, which may only rotate, translate and scale uniformly.
fn sphere(params: &mut Params, to_world: &DMat4, flip_normals: bool) -> Result<SphereDesc> {
    let center = params.point("center")?.unwrap_or(DVec3::ZERO);
    let radius = params.float_or("radius", 1.0)?;
    if radius <= 0.0 {
        return Err(params
            .loc_of("radius")
            .error(format!("radius must be positive, got {radius}")));
    }
    place_sphere(center, radius, flip_normals, to_world)
        .map_err(|message| params.loc_of("to_world").error(message))
}

/// The sphere of `center` and `radius` moved by `to_world`, or why it cannot be: the transform
/// may only rotate, translate and scale uniformly, and not mirror.
pub(crate) fn place_sphere(
    center: DVec3,
    radius: f64,
    flip_normals: bool,
    to_world: &DMat4,
) -> std::result::Result<SphereDesc, &'static str> {
    let linear = DMat3::from_mat4(*to_world);
    let gram = linear.transpose() * linear;
    let scale_sq = gram.x_axis.x;
    let uniform = (gram - DMat3::from_diagonal(DVec3::splat(scale_sq)))
        .to_cols_array()
        .iter()
        .all(|d| d.abs() <= 1e-5 * scale_sq);
    if !uniform {
        return Err("a sphere's to_world may only rotate, translate and scale uniformly");
    }
    if linear.determinant() < 0.0 {
        return Err("a sphere's to_world must not mirror (use flip_normals to turn it inside out)");
    }
    let world_center = to_world.transform_point3(center).as_vec3();
    let world_radius = (radius * scale_sq.sqrt()) as f32;
    let radius_ok = world_radius.is_finite() && world_radius > 0.0;
    if !world_center.is_finite() || !radius_ok {
        return Err("the sphere's world-space center or radius is out of range");
    }
    // The rotation is the linear part over its scale; its inverse is its transpose.
    let to_local = (linear / scale_sq.sqrt()).transpose().as_mat3();
    Ok(SphereDesc {
        center: world_center,
        radius: world_radius,
        flip_normals,
        to_local,
    })
}
