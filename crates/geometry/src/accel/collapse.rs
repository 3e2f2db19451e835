//! Collapsing obvhs' binary BVH into the 8-wide hierarchy the traversal walks.
//!
//! Top-down and greedy: a node's children start as the two children of a binary node, and the
//! child with the largest surface area that is still an inner node is replaced by its two
//! children until there are [`WIDTH`] (the rule of Wald et al. 2008, "Getting rid of packets",
//! which Embree's wide BVH builders follow). A binary subtree becomes a leaf when it is a binary
//! leaf, or when it holds at most `max_leaf` primitives that may share a leaf.

use obvhs::aabb::Aabb as BvhAabb;
use obvhs::bvh2::Bvh2;

use super::node::{ChildRef, Node, WIDTH};

/// The 8-wide hierarchy: its nodes, the root at index 0.
pub(crate) struct Tree {
    pub nodes: Vec<Node>,
    /// The most traversal stack entries a query can need: over the paths from the root, the most
    /// non-empty siblings left behind (`children - 1` summed over the path's inner nodes).
    pub stack_need: usize,
}

/// Collapses `bvh2`, whose leaves hold one primitive each (PLOC's do), into an 8-wide tree.
///
/// Primitives for which `groupable` is true share leaves, up to `max_leaf` of them; the others
/// have a leaf each. `leaf` receives the primitives (input indices, in the binary subtree's
/// order) of every leaf and returns the reference the leaf's parent stores.
///
/// # Panics
/// If a binary leaf holds more than one primitive.
pub(crate) fn collapse(
    bvh2: &Bvh2,
    max_leaf: u32,
    groupable: impl Fn(u32) -> bool,
    mut leaf: impl FnMut(&[u32]) -> ChildRef,
) -> Tree {
    let mut tree = Tree {
        nodes: Vec::new(),
        stack_need: 0,
    };
    if bvh2.nodes.is_empty() {
        return tree;
    }
    // A primitive that may not share a leaf weighs more than a full leaf.
    let weight = |prim: u32| if groupable(prim) { 1 } else { max_leaf + 1 };
    let leaves = leaf_choices(bvh2, weight, max_leaf);
    let is_leaf = |index: usize| leaves[index];
    let (mut prims, mut scratch) = (Vec::new(), Vec::new());
    let mut leaf_of = |index: usize| {
        prims.clear();
        gather(bvh2, index, &mut prims, &mut scratch);
        leaf(&prims)
    };

    tree.nodes.push(Node::EMPTY);
    // (binary node, wide node it fills).
    let mut pending = Vec::new();
    if is_leaf(0) {
        let b = bvh2.nodes[0].aabb();
        tree.nodes[0].set(0, b.min.into(), b.max.into(), leaf_of(0));
    } else {
        pending.push((0, 0));
    }
    while let Some((binary, index)) = pending.pop() {
        let children = open(bvh2, binary, &is_leaf);
        let mut node = Node::EMPTY;
        for (lane, &child) in children.as_slice().iter().enumerate() {
            let content = if is_leaf(child) {
                leaf_of(child)
            } else {
                tree.nodes.push(Node::EMPTY);
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

/// The (two to [`WIDTH`]) binary nodes that become the children of the wide node for the
/// inner binary node `binary`.
fn open(bvh2: &Bvh2, binary: usize, is_leaf: &impl Fn(usize) -> bool) -> Opened {
    let first = bvh2.nodes[binary].first_index as usize;
    let mut children = [0; WIDTH];
    children[..2].copy_from_slice(&[first, first + 1]);
    let mut len = 2;
    while len < WIDTH {
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

/// Up to [`WIDTH`] binary node indices.
struct Opened {
    children: [usize; WIDTH],
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

/// Appends the primitives of the binary subtree at `root` to `prims` (left before right);
/// `pending` is scratch space.
fn gather(bvh2: &Bvh2, root: usize, prims: &mut Vec<u32>, pending: &mut Vec<usize>) {
    pending.push(root);
    while let Some(index) = pending.pop() {
        let node = &bvh2.nodes[index];
        let start = node.first_index as usize;
        if node.is_leaf() {
            assert_eq!(node.prim_count, 1, "a binary leaf of several primitives");
            prims.push(bvh2.primitive_indices[start]);
        } else {
            pending.push(start + 1);
            pending.push(start);
        }
    }
}

/// Cost of testing a triangle packet (or a sphere) relative to the traversal cost of a binary
/// node, for the surface area heuristic that decides which subtrees become leaves.
const LEAF_COST: f32 = 4.0;

/// Which binary nodes become leaves: binary leaves, and subtrees whose primitives weigh at most
/// `max_leaf` in all when the surface area heuristic favours one leaf over the subtree (so the
/// two flat walls of a room stay apart, their common box being the whole room).
fn leaf_choices(bvh2: &Bvh2, weight: impl Fn(u32) -> u32, max_leaf: u32) -> Vec<bool> {
    let mut leaves = vec![false; bvh2.nodes.len()];
    let mut weights = vec![0u32; bvh2.nodes.len()];
    let mut costs = vec![0f32; bvh2.nodes.len()];
    // (node, whether its children are done already).
    let mut pending = vec![(0, false)];
    while let Some((index, children_done)) = pending.pop() {
        let node = &bvh2.nodes[index];
        let first = node.first_index as usize;
        let area = node.aabb().half_area();
        if node.is_leaf() {
            let prims = &bvh2.primitive_indices[first..first + node.prim_count as usize];
            weights[index] = prims.iter().fold(0u32, |w, &p| w.saturating_add(weight(p)));
            costs[index] = area * LEAF_COST;
            leaves[index] = true;
        } else if children_done {
            weights[index] = weights[first].saturating_add(weights[first + 1]);
            let split = area + costs[first] + costs[first + 1];
            let leaf = area * LEAF_COST;
            leaves[index] = weights[index] <= max_leaf && leaf <= split;
            costs[index] = if leaves[index] { leaf } else { split };
        } else {
            pending.extend([(index, true), (first, false), (first + 1, false)]);
        }
    }
    leaves
}

/// [`Tree::stack_need`] of `nodes`, whose children all have larger indices than their parents.
fn stack_need(nodes: &[Node]) -> usize {
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
    use crate::accel::node::Child;

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

    /// `bvh2` collapsed, with the primitives of each leaf (the leaf references are
    /// `ChildRef::triangles` of indices into those).
    fn collapsed(
        bvh2: &Bvh2,
        max_leaf: u32,
        groupable: impl Fn(u32) -> bool,
    ) -> (Tree, Vec<Vec<u32>>) {
        let mut leaves = Vec::new();
        let tree = collapse(bvh2, max_leaf, groupable, |prims| {
            leaves.push(prims.to_vec());
            ChildRef::triangles(leaves.len() - 1, prims.len().min(4))
        });
        (tree, leaves)
    }

    /// Walks `tree` from the root and checks its shape against `boxes`; returns the deepest
    /// stack a traversal can need, counted along every path.
    fn check(
        tree: &Tree,
        leaves: &[Vec<u32>],
        boxes: &[BvhAabb],
        max_leaf: u32,
        groupable: impl Fn(u32) -> bool,
    ) -> usize {
        let mut seen_prims = vec![false; boxes.len()];
        let mut seen_leaves = vec![false; leaves.len()];
        let mut seen_nodes = vec![false; tree.nodes.len()];
        let mut deepest = 0;
        // (node, stack entries left behind on the way to it).
        let mut pending = vec![(0usize, 0usize)];
        while let Some((index, stacked)) = pending.pop() {
            assert!(!seen_nodes[index], "node {index} reached twice");
            seen_nodes[index] = true;
            let node = &tree.nodes[index];
            let used: Vec<usize> = (0..WIDTH)
                .filter(|&lane| node.children[lane] != ChildRef::EMPTY)
                .collect();
            assert!(!used.is_empty(), "node {index} is empty");
            if index != 0 {
                assert!(used.len() >= 2, "inner node {index} has one child");
            }
            let stacked = stacked + used.len() - 1;
            deepest = deepest.max(stacked);
            for lane in used {
                let contains = |b: &BvhAabb| {
                    (0..3).all(|axis| {
                        node.plane(2 * axis, lane) <= b.min[axis]
                            && node.plane(2 * axis + 1, lane) >= b.max[axis]
                    })
                };
                match node.children[lane].get() {
                    Child::Node(inner) => {
                        assert!(inner > index, "child {inner} before its parent {index}");
                        pending.push((inner, stacked));
                    }
                    Child::Triangles { packet: leaf, .. } => {
                        assert!(!seen_leaves[leaf], "leaf {leaf} reached twice");
                        seen_leaves[leaf] = true;
                        let prims = &leaves[leaf];
                        assert!(!prims.is_empty() && prims.len() <= max_leaf as usize);
                        if prims.iter().any(|&p| !groupable(p)) {
                            assert_eq!(prims.len(), 1, "an ungroupable primitive shares a leaf");
                        }
                        for &prim in prims {
                            let prim = prim as usize;
                            assert!(!seen_prims[prim], "primitive {prim} twice");
                            seen_prims[prim] = true;
                            assert!(contains(&boxes[prim]), "primitive {prim} outside its box");
                        }
                    }
                    Child::Sphere(_) => panic!("the test makes no sphere leaves"),
                }
            }
        }
        assert!(seen_prims.iter().all(|&s| s), "a primitive is missing");
        assert!(seen_leaves.iter().all(|&s| s), "an unreachable leaf");
        assert!(seen_nodes.iter().all(|&s| s), "an unreachable node");
        deepest
    }

    #[test]
    fn every_primitive_lands_in_exactly_one_leaf() {
        for (count, seed) in [(1, 1), (2, 2), (5, 3), (37, 4), (1000, 5), (20_000, 6)] {
            let boxes = boxes(count, seed);
            let bvh2 = binary(&boxes);
            for max_leaf in [1, 2, 4] {
                for every in [1, 3] {
                    // Every third primitive (or none) may not share a leaf.
                    let groupable = |p: u32| every == 1 || !p.is_multiple_of(every);
                    let (tree, leaves) = collapsed(&bvh2, max_leaf, groupable);
                    let deepest = check(&tree, &leaves, &boxes, max_leaf, groupable);
                    assert_eq!(
                        tree.stack_need, deepest,
                        "{count} boxes, leaves of {max_leaf}"
                    );
                }
            }
        }
    }

    #[test]
    fn nodes_are_full_unless_all_children_are_leaves() {
        let boxes = boxes(5000, 7);
        let (tree, _) = collapsed(&binary(&boxes), 4, |_| true);
        for (index, node) in tree.nodes.iter().enumerate() {
            let used: Vec<ChildRef> = node
                .children
                .into_iter()
                .filter(|&c| c != ChildRef::EMPTY)
                .collect();
            assert!(
                used.len() == WIDTH || used.iter().all(|c| c.inner().is_none()),
                "node {index} has {} children, not all leaves",
                used.len()
            );
        }
    }

    #[test]
    fn flat_walls_of_a_room_get_a_leaf_each() {
        // Two triangles of the floor (y = -1) and two of the back wall (z = -1), each pair with
        // the same flat box: one leaf per wall, not one for the whole room.
        let floor = BvhAabb::new(Vec3A::new(-1.0, -1.0, -1.0), Vec3A::new(1.0, -1.0, 1.0));
        let back = BvhAabb::new(Vec3A::new(-1.0, -1.0, -1.0), Vec3A::new(1.0, 1.0, -1.0));
        let boxes = [floor, back, floor, back];
        let (tree, leaves) = collapsed(&binary(&boxes), 4, |_| true);
        let mut walls: Vec<Vec<u32>> = leaves
            .into_iter()
            .map(|mut prims| {
                prims.sort_unstable();
                prims
            })
            .collect();
        walls.sort_unstable();
        assert_eq!(walls, [vec![0, 2], vec![1, 3]]);
        assert_eq!(tree.nodes.len(), 1);
    }

    #[test]
    fn nothing_in_nothing_out() {
        let (tree, leaves) = collapsed(&Bvh2::default(), 1, |_| true);
        assert!(tree.nodes.is_empty() && leaves.is_empty());
        assert_eq!(tree.stack_need, 0);
    }
}
