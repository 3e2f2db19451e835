//! `<shape type="shapegroup">` and `<shape type="instance">`: shapes declared once and placed
//! many times. Strata bakes every instance into world space.

use std::collections::HashMap;

use glam::{DMat4, DVec3};

use super::bsdf::BsdfTable;
use super::shape::{check_invertible, place_sphere, shape};
use super::unexpected_child;
use crate::desc::{Geometry, ShapeDesc};
use crate::error::Result;
use crate::mesh::place::{Mirroring, Shading, place};
use crate::params::Params;
use crate::xml::tree::{Child, ObjectNode};

/// The scene's shape groups by id, each group's shapes read once, when an instance first needs
/// them.
pub(crate) struct ShapeGroups<'a> {
    nodes: HashMap<&'a str, &'a ObjectNode>,
    read: HashMap<&'a str, Vec<ShapeDesc>>,
}

impl<'a> ShapeGroups<'a> {
    /// The `shapegroup` shapes among `root`'s children; an error for one without an id.
    pub fn new(root: &'a ObjectNode) -> Result<Self> {
        let mut nodes = HashMap::new();
        for child in &root.children {
            if let Child::Object(object) = child
                && object.tag == "shape"
                && object.plugin == "shapegroup"
            {
                let id = object
                    .id
                    .as_deref()
                    .ok_or_else(|| object.loc.error("a shapegroup needs an id"))?;
                nodes.insert(id, object);
            }
        }
        Ok(Self {
            nodes,
            read: HashMap::new(),
        })
    }

    /// The shapes of the `instance` element `node`: its group's shapes moved by its `to_world`
    /// (default identity), relative to `origin` (world space; subtracted in double precision).
    pub fn instance(
        &mut self,
        node: &'a ObjectNode,
        bsdfs: &mut BsdfTable<'a>,
        origin: DVec3,
    ) -> Result<Vec<ShapeDesc>> {
        let [Child::Ref(reference)] = node.children.as_slice() else {
            let allowed = "one <ref id=\"...\"/> to a shapegroup";
            return Err(match node.children.first() {
                Some(child) => unexpected_child(node, child, allowed),
                None => node.loc.error(format!("an instance needs {allowed}")),
            });
        };
        let mut params = Params::new(node);
        let to_world = params.transform("to_world")?.unwrap_or(DMat4::IDENTITY);
        let to_world_loc = params.loc_of("to_world");
        check_invertible(&to_world, to_world_loc)?;
        let to_world = DMat4::from_translation(-origin) * to_world;
        params.finish()?;
        let id = reference.id.as_str();
        let Some(&group) = self.nodes.get(id) else {
            return Err(reference
                .loc
                .error(format!("no shapegroup with id \"{id}\"")));
        };
        if !self.read.contains_key(id) {
            let shapes = group_shapes(group, bsdfs)?;
            self.read.insert(id, shapes);
        }
        self.read[id]
            .iter()
            .map(|shape| {
                let geometry = match &shape.geometry {
                    Geometry::Mesh(mesh) => {
                        let shading = if mesh.normals.is_some() {
                            Shading::Smooth
                        } else {
                            Shading::Flat
                        };
                        Geometry::Mesh(
                            place(
                                mesh.clone(),
                                &to_world,
                                false,
                                shading,
                                Mirroring::KeepsSides,
                            )
                            .map_err(|e| to_world_loc.error(e))?,
                        )
                    }
                    Geometry::Sphere(sphere) => Geometry::Sphere(
                        place_sphere(
                            sphere.center.as_dvec3(),
                            f64::from(sphere.radius),
                            sphere.flip_normals,
                            &to_world,
                        )
                        .map_err(|e| to_world_loc.error(e))?,
                    ),
                };
                Ok(ShapeDesc {
                    geometry,
                    ..shape.clone()
                })
            })
            .collect()
    }
}

/// The shapes of the `shapegroup` element `group`, in its own frame (their `to_world` applied);
/// groups may not nest or emit, as in Mitsuba.
fn group_shapes<'a>(group: &'a ObjectNode, bsdfs: &mut BsdfTable<'a>) -> Result<Vec<ShapeDesc>> {
    Params::new(group).finish()?;
    let mut shapes = Vec::new();
    for child in &group.children {
        let Child::Object(object) = child else {
            return Err(unexpected_child(group, child, "<shape> elements"));
        };
        if object.tag != "shape" {
            return Err(unexpected_child(group, child, "<shape> elements"));
        }
        if matches!(object.plugin.as_str(), "shapegroup" | "instance") {
            return Err(object
                .loc
                .error("a shapegroup cannot hold shapegroups or instances"));
        }
        let shape = shape(object, bsdfs, DVec3::ZERO)?;
        if shape.emitter.is_some() {
            return Err(object
                .loc
                .error("a shapegroup's shapes cannot emit (Mitsuba does not instance emitters)"));
        }
        if shape.motion.is_some() {
            return Err(object.loc.error(
                "a shapegroup's shapes cannot move (<animation>): animate a shape of its own",
            ));
        }
        shapes.push(shape);
    }
    Ok(shapes)
}
