//! Traversal state for obvhs' `traverse!` macro with a stack of our choosing.
//!
//! obvhs' own state has a fixed 32-entry stack that silently overwrites its top entry when a tree
//! is deeper than that. The macro only needs a value with the same fields, so the hierarchy picks
//! a fixed stack for ordinary trees and a heap stack sized to the tree for pathological ones.

use glam::{BVec3A, UVec2, uvec2};
use obvhs::cwbvh::CwBvh;
use obvhs::faststack::FastStack;

/// Capacity of the fixed traversal stack. A stack of capacity `n` keeps `n - 1` entries intact
/// (obvhs' `StackStack` overwrites its last slot when full), and traversal pushes at most one
/// entry per tree level below the root.
pub(crate) const FIXED_STACK: usize = 32;

/// Capacity of the stack for shallow trees (small scenes), where zeroing the 32-entry stack for
/// every ray is a measurable part of a ray's cost.
pub(crate) const SMALL_STACK: usize = 8;

/// Which traversal stack a tree needs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum StackKind {
    /// [`SMALL_STACK`] entries on the call stack.
    Small,
    /// [`FIXED_STACK`] entries on the call stack.
    Fixed,
    /// On the heap, sized to the tree (thousands of exactly coincident primitives).
    Heap,
}

impl StackKind {
    /// The smallest stack that holds the traversal of a tree `depth` levels deep.
    pub fn for_depth(depth: usize) -> Self {
        if depth + 1 < SMALL_STACK {
            StackKind::Small
        } else if depth + 1 < FIXED_STACK {
            StackKind::Fixed
        } else {
            StackKind::Heap
        }
    }
}

/// Traversal state, field for field what `obvhs::traverse!` reads and writes.
pub(crate) struct Walk<S> {
    pub stack: S,
    pub current_group: UVec2,
    pub primitive_group: UVec2,
    pub oct_inv4: u32,
    pub primitive_id: u32,
    pub hitmask: u32,
}

impl<S: FastStack<UVec2>> Walk<S> {
    /// Starts at the root of a non-empty tree, visiting children in the order that suits a ray
    /// whose direction has the negative components `neg`.
    pub fn new(stack: S, neg: BVec3A) -> Self {
        let axis_bits = |axis: usize, bits: u32| if neg.test(axis) { 0 } else { bits };
        Self {
            stack,
            current_group: uvec2(0, 0x8000_0000),
            primitive_group: UVec2::ZERO,
            oct_inv4: axis_bits(0, 0x0404_0404)
                | axis_bits(1, 0x0202_0202)
                | axis_bits(2, 0x0101_0101),
            primitive_id: 0,
            hitmask: 0,
        }
    }
}

/// Number of node levels of `bvh` (1 for a root whose children are all leaves, 0 when empty).
pub(crate) fn depth(bvh: &CwBvh) -> usize {
    if bvh.nodes.is_empty() {
        return 0;
    }
    let mut deepest = 0;
    let mut pending = vec![(0usize, 1usize)];
    while let Some((index, level)) = pending.pop() {
        deepest = deepest.max(level);
        let node = &bvh.nodes[index];
        pending.extend(
            (0..8)
                .filter(|&c| !node.is_leaf(c))
                .map(|c| (node.child_node_index(c) as usize, level + 1)),
        );
    }
    deepest
}
