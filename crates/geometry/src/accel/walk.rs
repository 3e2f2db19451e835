//! Traversal of the 8-wide hierarchy: closest hit (nearest child first, skipping what lies beyond
//! the closest hit so far) and any hit (stopping at the first), each over a stack of our choosing.

use super::node::{Child, ChildRef, Node, WIDTH};
use super::prim::{Found, Geometry};
use super::query::RayQuery;
use super::stack::Stack;

/// A child left for later, with the distance at which the ray enters its box.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Pending {
    child: ChildRef,
    t_enter: f32,
}

impl Default for Pending {
    fn default() -> Self {
        Self {
            child: ChildRef::EMPTY,
            t_enter: 0.0,
        }
    }
}

/// The closest primitive hit with `0 < t < t_max`.
#[inline(always)]
pub(crate) fn closest(
    nodes: &[Node],
    geometry: &Geometry,
    stack: &mut impl Stack<Pending>,
    query: &RayQuery,
    t_max: f32,
) -> Option<Found> {
    let mut closest = t_max;
    let mut found = None;
    let mut current = ChildRef::node(0);
    loop {
        match current.get() {
            Child::Node(index) => {
                let node = &nodes[index];
                let (mask, t_enter) = node.hit(&query.boxes, closest);
                if mask != 0 {
                    current = nearest_first(node, mask, t_enter, stack);
                    continue;
                }
            }
            Child::Triangles { packet, lanes } => {
                let packet4 = &geometry.packets[packet];
                if let Some((lane, hit)) = query.shear.nearest4(packet4, lanes, closest) {
                    closest = hit.t;
                    found = Some(Found::Triangle { packet, lane, hit });
                }
            }
            Child::Sphere(index) => {
                let sphere = &geometry.spheres[index];
                if let Some(t) = sphere.intersect(query.origin, query.dir, closest) {
                    closest = t;
                    found = Some(Found::Sphere { index, t });
                }
            }
        }
        current = loop {
            match stack.pop() {
                None => return found,
                Some(entry) if entry.t_enter <= closest => break entry.child,
                Some(_) => {}
            }
        };
    }
}

/// The child of `node` to visit next among those in `mask` (non-empty): the nearest; the others
/// are pushed, the farthest first.
#[inline(always)]
fn nearest_first(
    node: &Node,
    mask: u32,
    t_enter: [f32; WIDTH],
    stack: &mut impl Stack<Pending>,
) -> ChildRef {
    let entry = |lane: u32| Pending {
        child: node.children[lane as usize],
        t_enter: t_enter[lane as usize],
    };
    let a = entry(mask.trailing_zeros());
    let mut rest = mask & (mask - 1);
    if rest == 0 {
        return a.child;
    }
    let b = entry(rest.trailing_zeros());
    rest &= rest - 1;
    if rest == 0 {
        let (near, far) = if b.t_enter < a.t_enter {
            (b, a)
        } else {
            (a, b)
        };
        stack.push(far);
        return near.child;
    }
    // Three or more: sorted farthest first by insertion.
    let mut sorted = [Pending::default(); WIDTH];
    sorted[..2].copy_from_slice(&[a, b]);
    let mut len = 2;
    while rest != 0 {
        let next = entry(rest.trailing_zeros());
        rest &= rest - 1;
        let mut j = len;
        while j > 0 && sorted[j - 1].t_enter < next.t_enter {
            sorted[j] = sorted[j - 1];
            j -= 1;
        }
        sorted[j] = next;
        len += 1;
    }
    for &pending in &sorted[..len - 1] {
        stack.push(pending);
    }
    sorted[len - 1].child
}

/// Whether any primitive is hit with `0 < t < t_max`.
#[inline(always)]
pub(crate) fn any(
    nodes: &[Node],
    geometry: &Geometry,
    stack: &mut impl Stack<ChildRef>,
    query: &RayQuery,
    t_max: f32,
) -> bool {
    let mut current = ChildRef::node(0);
    loop {
        match current.get() {
            Child::Node(index) => {
                let node = &nodes[index];
                let (mut mask, _) = node.hit(&query.boxes, t_max);
                if mask != 0 {
                    current = node.children[mask.trailing_zeros() as usize];
                    mask &= mask - 1;
                    while mask != 0 {
                        stack.push(node.children[mask.trailing_zeros() as usize]);
                        mask &= mask - 1;
                    }
                    continue;
                }
            }
            Child::Triangles { packet, lanes } => {
                if query.shear.any4(&geometry.packets[packet], lanes, t_max) {
                    return true;
                }
            }
            Child::Sphere(index) => {
                let sphere = &geometry.spheres[index];
                if sphere.intersect(query.origin, query.dir, t_max).is_some() {
                    return true;
                }
            }
        }
        match stack.pop() {
            Some(child) => current = child,
            None => return false,
        }
    }
}
