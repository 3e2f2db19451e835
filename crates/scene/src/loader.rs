//! The scene level: which elements a `<scene>` holds and how they become a [`SceneDesc`].

use std::path::Path;

use glam::DVec3;

use crate::desc::SceneDesc;
use crate::error::Result;
use crate::params::Params;
use crate::plugins::bsdf::BsdfTable;
use crate::plugins::emitter::scene_emitter;
use crate::plugins::instance::ShapeGroups;
use crate::plugins::integrator::integrator;
use crate::plugins::sensor::{Camera, sensor};
use crate::plugins::shape::shape;
use crate::plugins::{child_loc, unexpected_child};
use crate::xml::tree::{Child, ObjectNode, parse_scene_file, parse_scene_text};

/// What a `<scene>` may contain, for messages.
const SCENE_CHILDREN: &str =
    "<integrator>, <sensor>, <shape>, <bsdf>, <emitter type=\"point|constant\">";

/// Loads the scene at `path` (see [`crate::parse_file`]).
pub(crate) fn load(path: &Path, overrides: &[(String, String)]) -> Result<SceneDesc> {
    let root = parse_scene_file(path, overrides)?;
    interpret_scene(path, &root)
}

/// Loads the scene whose file contents are `text`, as if read from `path`.
pub(crate) fn load_text(
    path: &Path,
    text: &[u8],
    overrides: &[(String, String)],
) -> Result<SceneDesc> {
    let root = parse_scene_text(path, text, overrides)?;
    interpret_scene(path, &root)
}

fn interpret_scene(path: &Path, root: &ObjectNode) -> Result<SceneDesc> {
    Params::new(root).finish()?;
    let mut bsdfs = BsdfTable::new(root);
    let mut integrator_desc = None;
    let mut camera: Option<Camera> = None;
    let mut emitters = Vec::new();

    // Top-level BSDFs first, in document order, so that they keep their order in the table.
    for child in &root.children {
        if let Child::Object(object) = child
            && object.tag == "bsdf"
        {
            bsdfs.add(object)?;
        }
    }
    // The first sensor is read ahead: its position is the origin of the description's frame,
    // subtracted from every position in double precision as it is placed. Its errors are
    // reported in document order below (the frame is then the world's, unused).
    let mut first_camera = root.children.iter().find_map(|child| match child {
        Child::Object(object) if object.tag == "sensor" => Some(sensor(object)),
        _ => None,
    });
    let origin = match &first_camera {
        Some(Ok(first)) => first.sensor.position,
        _ => DVec3::ZERO,
    };
    let mut groups = ShapeGroups::new(root)?;
    let mut shapes = Vec::new();
    for child in &root.children {
        let Child::Object(object) = child else {
            return Err(child_loc(child).error(
                "a <ref> at the top level of a scene is not supported; reference BSDFs from shapes",
            ));
        };
        match object.tag.as_str() {
            // Top-level BSDFs are read above; textures when a BSDF references them.
            "bsdf" | "texture" => {}
            "integrator" if integrator_desc.is_none() => {
                integrator_desc = Some(integrator(object)?);
            }
            "integrator" => {
                return Err(object.loc.error("a scene can have only one <integrator>"));
            }
            // The first sensor is rendered, as by Mitsuba's `mi.render` and its command line
            // without `--sensor`; later ones are read for their errors only.
            "sensor" if camera.is_none() => {
                camera = Some(
                    first_camera
                        .take()
                        .expect("the first sensor was read ahead")?,
                );
            }
            "sensor" => {
                sensor(object)?;
            }
            // A shape group is placed by its instances only.
            "shape" if object.plugin == "shapegroup" => {}
            "shape" if object.plugin == "instance" => {
                shapes.extend(groups.instance(object, &mut bsdfs, origin)?);
            }
            "shape" => shapes.push(shape(object, &mut bsdfs, origin)?),
            // An area emitter with an id emits from the shapes that reference it.
            "emitter" if object.plugin == "area" && object.id.is_some() => {}
            "emitter" => emitters.push(scene_emitter(object, origin)?),
            "film" | "sampler" => {
                return Err(object.loc.error(format!(
                    "<{}> must be nested inside the <sensor>",
                    object.tag
                )));
            }
            "rfilter" => {
                return Err(object
                    .loc
                    .error("<rfilter> must be nested inside the <film>"));
            }
            _ => return Err(unexpected_child(root, child, SCENE_CHILDREN)),
        }
    }
    let integrator_desc = integrator_desc.ok_or_else(|| {
        root.loc
            .error("the scene has no <integrator> (Mitsuba requires one; e.g. <integrator type=\"path\"/>)")
    })?;
    let camera = camera.ok_or_else(|| root.loc.error("the scene has no <sensor>"))?;
    Ok(SceneDesc {
        source: path.to_path_buf(),
        integrator: integrator_desc,
        sensor: camera.sensor,
        film: camera.film,
        sampler: camera.sampler,
        shapes,
        bsdfs: bsdfs.into_bsdfs(),
        emitters,
    })
}
