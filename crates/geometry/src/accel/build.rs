//! Gathering the primitives of all shapes and building the hierarchy over them.

use glam::{Vec3, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::aabb::Aabb as BvhAabb;
use obvhs::bvh2::Bvh2;
use obvhs::bvh2::reinsertion::ReinsertionOptimizer;
use obvhs::ploc::PlocBuilder;

use super::collapse::collapse;
use super::node::{ChildRef, Node};
use super::prim::{Geometry, PrimInfo, direction_of};
use crate::sphere::SphereGeom;
use crate::triangle::TriangleCoords;
use crate::triangle4::Triangle4;
use crate::{Aabb, Shape};

/// The most triangles a leaf holds (one packet).
const MAX_LEAF: u32 = 4;

/// The built hierarchy and its primitives.
pub(crate) struct Built {
    pub nodes: Vec<Node>,
    pub stack_need: usize,
    pub geometry: Geometry,
    /// Ids of the triangles of packet `p` at `4 p .. 4 p + 4` ([`PrimInfo::UNUSED`] for unused
    /// lanes).
    pub triangle_infos: Vec<PrimInfo>,
    /// Ids of the spheres, by sphere index.
    pub sphere_infos: Vec<PrimInfo>,
    pub bounds: Aabb,
}

/// One primitive's geometry, before it goes into a packet or the sphere list.
#[derive(Clone, Copy)]
enum Prim {
    Triangle(TriangleCoords),
    Sphere(SphereGeom),
}

/// Builds the hierarchy over every usable primitive of `shapes`.
///
/// # Panics
/// If a mesh fails `TriangleMesh::validate`.
pub(crate) fn build(shapes: &[Shape]) -> Built {
    let mut geoms = Vec::new();
    let mut infos = Vec::new();
    let mut boxes = Vec::new();
    for (shape_index, shape) in shapes.iter().enumerate() {
        let shape_index = u32::try_from(shape_index).expect("fewer than 2^32 shapes");
        match shape {
            Shape::Mesh(mesh) => {
                if let Err(err) = mesh.validate() {
                    panic!("shape {shape_index}: {err}");
                }
                for prim in 0..mesh.triangle_count() {
                    let [p0, p1, p2] = mesh.triangle(prim);
                    if !(p0.is_finite() && p1.is_finite() && p2.is_finite()) {
                        continue;
                    }
                    // Zero-area triangles have no normal; no ray should hit them.
                    let Some(ng) = direction_of((p1 - p0).cross(p2 - p0)) else {
                        continue;
                    };
                    let v = [p0, p1, p2].map(Vec3A::from);
                    geoms.push(Prim::Triangle(TriangleCoords::new(v)));
                    infos.push(PrimInfo {
                        shape: shape_index,
                        prim: u32::try_from(prim).expect("fewer than 2^32 triangles per mesh"),
                        ng,
                        p_error: crate::triangle_point_error([p0, p1, p2]),
                    });
                    boxes.push(BvhAabb::new(
                        v[0].min(v[1]).min(v[2]),
                        v[0].max(v[1]).max(v[2]),
                    ));
                }
            }
            Shape::Sphere(sphere) => {
                let b = sphere.bounds();
                if !(sphere.radius > 0.0 && b.min.is_finite() && b.max.is_finite()) {
                    continue;
                }
                geoms.push(Prim::Sphere(SphereGeom {
                    center: sphere.center.into(),
                    radius: sphere.radius,
                }));
                infos.push(PrimInfo {
                    shape: shape_index,
                    prim: 0,
                    ng: Vec3::ZERO,
                    p_error: crate::sphere_point_error(sphere.center, sphere.radius),
                });
                boxes.push(BvhAabb::new(b.min.into(), b.max.into()));
            }
        }
    }

    let bounds = boxes.iter().fold(Aabb::EMPTY, |acc, b| {
        acc.union(Aabb::new(b.min.into(), b.max.into()))
    });
    let padded: Vec<BvhAabb> = boxes
        .iter()
        .enumerate()
        .map(|(i, b)| tie_breaking_pad(i, b))
        .collect();
    let mut built = Built {
        nodes: Vec::new(),
        stack_need: 0,
        geometry: Geometry::default(),
        triangle_infos: Vec::new(),
        sphere_infos: Vec::new(),
        bounds,
    };
    let mut bvh2 = binary(&padded);
    fit_to(&mut bvh2, &boxes);
    let tree = collapse(
        &bvh2,
        MAX_LEAF,
        |i| matches!(geoms[i as usize], Prim::Triangle(_)),
        |prims| {
            let prim = |i: &u32| geoms[*i as usize];
            let info = |i: &u32| infos[*i as usize];
            if let [i] = prims
                && let Prim::Sphere(sphere) = prim(i)
            {
                built.geometry.spheres.push(sphere);
                built.sphere_infos.push(info(i));
                return ChildRef::sphere(built.geometry.spheres.len() - 1);
            }
            let triangles = prims.iter().map(|i| match prim(i) {
                Prim::Triangle(tri) => tri,
                Prim::Sphere(_) => unreachable!("spheres do not share leaves"),
            });
            built.geometry.packets.push(Triangle4::new(triangles));
            built.triangle_infos.extend(prims.iter().map(info));
            built
                .triangle_infos
                .resize(4 * built.geometry.packets.len(), PrimInfo::UNUSED);
            ChildRef::triangles(built.geometry.packets.len() - 1, prims.len())
        },
    );
    built.nodes = tree.nodes;
    built.stack_need = tree.stack_need;
    built
}

/// obvhs' binary BVH over `boxes` with the settings of its `medium_build` (PLOC, then SAH-driven
/// reinsertion).
fn binary(boxes: &[BvhAabb]) -> Bvh2 {
    let params = BvhBuildParams::medium_build();
    let count = u32::try_from(boxes.len()).expect("fewer than 2^32 primitives");
    let mut bvh2 = PlocBuilder::with_capacity(boxes.len()).build(
        params.ploc_search_distance,
        boxes,
        (0..count).collect(),
        params.sort_precision,
        params.search_depth_threshold,
    );
    ReinsertionOptimizer::default().run(&mut bvh2, params.reinsertion_batch_ratio, None);
    bvh2
}

/// Every box of `bvh2` fitted to the primitives under it, `boxes` (by primitive index): the
/// builder's boxes are padded to break its ties ([`tie_breaking_pad`]), but traversal is faster on
/// tight ones: fewer of them overlap, and a ray leaving a flat surface a few ulps off it (see
/// [`crate::offset_ray_origin`]) starts outside that surface's own box, which padding makes up to
/// 1e-4 of its size thick, instead of entering it and testing its triangles again.
fn fit_to(bvh2: &mut Bvh2, boxes: &[BvhAabb]) {
    for index in 0..bvh2.nodes.len() {
        let node = &bvh2.nodes[index];
        if node.is_leaf() {
            let first = node.first_index as usize;
            let fitted = bvh2.primitive_indices[first..first + node.prim_count as usize]
                .iter()
                .fold(BvhAabb::empty(), |b, &i| b.union(&boxes[i as usize]));
            bvh2.nodes[index].set_aabb(fitted);
        }
    }
    bvh2.refit_all();
}

/// Box `b` of primitive `i`, grown by a pseudo-random fraction of `1e-4` of its size (plus a few
/// ulps of its position), for the build only (the built tree is fitted to the unpadded boxes,
/// see [`fit_to`]).
///
/// obvhs' PLOC builder pairs each node with the last of equally good neighbours, so identical
/// boxes (duplicate primitives) and evenly spaced equal boxes (a row of equal spheres) merge one
/// pair per pass: quadratic build time and, for duplicates, a chain-shaped tree thousands of levels
/// deep. Distinct sizes break the ties. Growing a box never loses a hit.
fn tie_breaking_pad(i: usize, b: &BvhAabb) -> BvhAabb {
    let hash = (i as u32 ^ 0x5bd1_e995).wrapping_mul(0x9e37_79b9);
    let hash = (hash ^ (hash >> 15)).wrapping_mul(0x85eb_ca6b);
    let fraction = (hash >> 8) as f32 / (1u32 << 24) as f32;
    let size = (b.max - b.min).max_element();
    let magnitude = b.min.abs().max(b.max.abs()).max_element();
    let pad = fraction * (1e-4 * size + 4.0 * f32::EPSILON * magnitude);
    BvhAabb::new(b.min - pad, b.max + pad)
}
