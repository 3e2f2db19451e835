//! Collapsing obvhs' binary BVH into the 4-wide hierarchy the traversal walks.
//!
//! Top-down and greedy: a node's children start as the two children of a binary node, and the
//! child with the largest surface area that is still an inner node is replaced by its two
//! children until there are four (the rule of Wald et al. 2008, "Getting rid of packets", which
//! Embree's BVH4 builders follow). A binary subtree with at most `max_leaf` primitives becomes a
//! leaf, its primitives stored contiguously in the subtree's order.

use obvhs::aabb::Aabb as BvhAabb;
use obvhs::bvh2::Bvh2;

use super::node::{ChildRef, Node4};

/// The 4-wide hierarchy: nodes (the root at index 0) and the order of the primitives its leaves
/// refer to.
pub(crate) struct Tree {
    pub nodes: Vec<Node4>,
    /// `order[i]` is the input index of the primitive at BVH position `i`.
    pub order: Vec<u32>,
    /// The most traversal stack entries a query can need: over the paths from the root, the most
    /// non-empty siblings left behind (`children - 1` summed over the path's inner nodes).
    pub stack_need: usize,
}

/// Collapses `bvh2` (any shape: leaves with any number of primitives, chains thousands of levels
/// deep) into a 4-wide tree whose leaves hold at most `max_leaf` primitives (or one binary leaf,
/// whatever its size).
pub(crate) fn collapse(bvh2: &Bvh2, max_leaf: u32) -> Tree {
    let mut tree = Tree {
        nodes: Vec::new(),
        order: Vec::with_capacity(bvh2.primitive_indices.len()),
        stack_need: 0,
    };
    if bvh2.nodes.is_empty() {
        return tree;
    }
    let counts = subtree_counts(bvh2);
    let is_leaf = |index: usize| bvh2.nodes[index].is_leaf() || counts[index] <= max_leaf;

    tree.nodes.push(Node4::EMPTY);
    // (binary node, 4-wide node it fills).
    let mut pending = Vec::new();
    if is_leaf(0) {
        let child = leaf(bvh2, 0, &mut tree.order);
        let b = bvh2.nodes[0].aabb();
        tree.nodes[0].set(0, b.min.into(), b.max.into(), child);
    } else {
        pending.push((0, 0));
    }
    while let Some((binary, index)) = pending.pop() {
        let children = open(bvh2, binary, &is_leaf);
        let mut node = Node4::EMPTY;
        for (lane, &child) in children.as_slice().iter().enumerate() {
            let content = if is_leaf(child) {
                leaf(bvh2, child, &mut tree.order)
            } else {
                tree.nodes.push(Node4::EMPTY);
                pending.push((child, tree.nodes.len() - 1));
                ChildRef::node(tree.nodes.len() - 1)
            };
            let b = bvh2.nodes[child].aabb();
            node.set(lane, b.min.into(), b.max.into(), content);
        }
        tree.nodes[index] = node;
    }
    tree.stack_need = stack_need(&tree.nodes);
    tree
}

/// The (two to four) binary nodes that become the children of the 4-wide node for the inner
/// binary node `binary`.
fn open(bvh2: &Bvh2, binary: usize, is_leaf: &impl Fn(usize) -> bool) -> Opened {
    let first = bvh2.nodes[binary].first_index as usize;
    let mut children = [first, first + 1, 0, 0];
    let mut len = 2;
    while len < 4 {
        let largest = (0..len)
            .filter(|&slot| !is_leaf(children[slot]))
            .max_by(|&a, &b| area(bvh2, children[a]).total_cmp(&area(bvh2, children[b])));
        let Some(slot) = largest else {
            break;
        };
        let first = bvh2.nodes[children[slot]].first_index as usize;
        children[slot] = first;
        children[len] = first + 1;
        len += 1;
    }
    Opened { children, len }
}

/// Up to four binary node indices.
struct Opened {
    children: [usize; 4],
    len: usize,
}

impl Opened {
    fn as_slice(&self) -> &[usize] {
        &self.children[..self.len]
    }
}

fn area(bvh2: &Bvh2, index: usize) -> f32 {
    let b: &BvhAabb = bvh2.nodes[index].aabb();
    b.half_area()
}

/// Appends the primitives of the binary subtree at `root` to `order` (left before right) and
/// returns the leaf that refers to them.
fn leaf(bvh2: &Bvh2, root: usize, order: &mut Vec<u32>) -> ChildRef {
    let first = order.len();
    let mut pending = vec![root];
    while let Some(index) = pending.pop() {
        let node = &bvh2.nodes[index];
        let start = node.first_index as usize;
        if node.is_leaf() {
            order.extend_from_slice(
                &bvh2.primitive_indices[start..start + node.prim_count as usize],
            );
        } else {
            pending.push(start + 1);
            pending.push(start);
        }
    }
    let count = u32::try_from(order.len() - first).expect("a leaf of fewer than 2^32 primitives");
    ChildRef::leaf(first, count)
}

/// The number of primitives under every binary node.
fn subtree_counts(bvh2: &Bvh2) -> Vec<u32> {
    let mut counts = vec![0; bvh2.nodes.len()];
    // (node, whether its children are counted already).
    let mut pending = vec![(0, false)];
    while let Some((index, children_done)) = pending.pop() {
        let node = &bvh2.nodes[index];
        let first = node.first_index as usize;
        if node.is_leaf() {
            counts[index] = node.prim_count;
        } else if children_done {
            counts[index] = counts[first] + counts[first + 1];
        } else {
            pending.extend([(index, true), (first, false), (first + 1, false)]);
        }
    }
    counts
}

/// [`Tree::stack_need`] of `nodes`, whose children all have larger indices than their parents.
fn stack_need(nodes: &[Node4]) -> usize {
    let mut need = vec![0usize; nodes.len()];
    for index in (0..nodes.len()).rev() {
        let children = &nodes[index].children;
        let used = children.iter().filter(|&&c| c != ChildRef::EMPTY).count();
        let below = children
            .iter()
            .filter_map(|c| c.inner())
            .map(|c| need[c])
            .max()
            .unwrap_or(0);
        need[index] = used.saturating_sub(1) + below;
    }
    need.first().copied().unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use glam::Vec3A;
    use obvhs::BvhBuildParams;
    use obvhs::ploc::PlocBuilder;

    use super::*;

    /// obvhs' PLOC binary BVH over `boxes` (one primitive per leaf).
    fn binary(boxes: &[BvhAabb]) -> Bvh2 {
        let params = BvhBuildParams::medium_build();
        PlocBuilder::with_capacity(boxes.len()).build(
            params.ploc_search_distance,
            boxes,
            (0..boxes.len() as u32).collect(),
            params.sort_precision,
            params.search_depth_threshold,
        )
    }

    /// Random boxes, a tenth of them repeated exactly.
    fn boxes(count: usize, seed: u32) -> Vec<BvhAabb> {
        let mut state = seed;
        let mut f = move || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            (state >> 8) as f32 / (1 << 24) as f32
        };
        let mut out: Vec<BvhAabb> = Vec::with_capacity(count);
        for i in 0..count {
            if i % 10 == 9 {
                out.push(out[i / 2]);
                continue;
            }
            let c = Vec3A::new(f(), f(), f()) * 10.0;
            let half = Vec3A::new(f(), f(), f()) * 0.5;
            out.push(BvhAabb::new(c - half, c + half));
        }
        out
    }

    /// Walks `tree` from the root and checks its shape against `boxes`; returns the deepest
    /// stack a traversal can need, counted along every path.
    fn check(tree: &Tree, boxes: &[BvhAabb], max_leaf: u32) -> usize {
        let mut seen_prims = vec![false; boxes.len()];
        let mut seen_nodes = vec![false; tree.nodes.len()];
        let mut deepest = 0;
        // (node, stack entries left behind on the way to it).
        let mut pending = vec![(0usize, 0usize)];
        while let Some((index, stacked)) = pending.pop() {
            assert!(!seen_nodes[index], "node {index} reached twice");
            seen_nodes[index] = true;
            let node = &tree.nodes[index];
            let used: Vec<usize> = (0..4)
                .filter(|&lane| node.children[lane] != ChildRef::EMPTY)
                .collect();
            assert!(!used.is_empty(), "node {index} is empty");
            if index != 0 {
                assert!(used.len() >= 2, "inner node {index} has one child");
            }
            let stacked = stacked + used.len() - 1;
            deepest = deepest.max(stacked);
            for lane in used {
                let child = node.children[lane];
                let contains = |b: &BvhAabb| {
                    (0..3).all(|axis| {
                        node.planes[2 * axis][lane] <= b.min[axis]
                            && node.planes[2 * axis + 1][lane] >= b.max[axis]
                    })
                };
                match child.inner() {
                    Some(inner) => {
                        assert!(inner > index, "child {inner} before its parent {index}");
                        pending.push((inner, stacked));
                    }
                    None => {
                        let range = child.primitives();
                        assert!(!range.is_empty() && range.len() <= max_leaf as usize);
                        for position in range {
                            let prim = tree.order[position] as usize;
                            assert!(!seen_prims[prim], "primitive {prim} twice");
                            seen_prims[prim] = true;
                            assert!(contains(&boxes[prim]), "primitive {prim} outside its box");
                        }
                    }
                }
            }
        }
        assert!(seen_prims.iter().all(|&s| s), "a primitive is missing");
        assert!(seen_nodes.iter().all(|&s| s), "an unreachable node");
        assert_eq!(tree.order.len(), boxes.len());
        deepest
    }

    #[test]
    fn every_primitive_lands_in_exactly_one_leaf() {
        for (count, seed) in [(1, 1), (2, 2), (5, 3), (37, 4), (1000, 5), (20_000, 6)] {
            let boxes = boxes(count, seed);
            let bvh2 = binary(&boxes);
            for max_leaf in [1, 2, 4] {
                let tree = collapse(&bvh2, max_leaf);
                let deepest = check(&tree, &boxes, max_leaf);
                assert_eq!(
                    tree.stack_need, deepest,
                    "{count} boxes, leaves of {max_leaf}"
                );
            }
        }
    }

    #[test]
    fn nodes_have_four_children_unless_all_are_leaves() {
        let boxes = boxes(5000, 7);
        let tree = collapse(&binary(&boxes), 1);
        for (index, node) in tree.nodes.iter().enumerate() {
            let used: Vec<ChildRef> = node
                .children
                .into_iter()
                .filter(|&c| c != ChildRef::EMPTY)
                .collect();
            assert!(
                used.len() == 4 || used.iter().all(|c| c.inner().is_none()),
                "node {index} has {} children, not all leaves",
                used.len()
            );
        }
    }

    #[test]
    fn nothing_in_nothing_out() {
        let tree = collapse(&Bvh2::default(), 1);
        assert!(tree.nodes.is_empty() && tree.order.is_empty());
        assert_eq!(tree.stack_need, 0);
    }
}
