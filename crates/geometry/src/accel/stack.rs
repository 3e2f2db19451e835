//! Traversal stacks: a fixed array on the call stack for ordinary trees, a vector on the heap for
//! pathologically deep ones.

/// Capacity of the stack for shallow trees (small scenes), where clearing a larger stack for
/// every ray is a measurable part of a ray's cost.
pub(crate) const SMALL_STACK: usize = 32;

/// Capacity of the fixed stack for ordinary trees.
pub(crate) const FIXED_STACK: usize = 64;

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
    /// The smallest stack that holds `need` entries.
    pub fn for_need(need: usize) -> Self {
        if need <= SMALL_STACK {
            StackKind::Small
        } else if need <= FIXED_STACK {
            StackKind::Fixed
        } else {
            StackKind::Heap
        }
    }
}

/// A last-in first-out stack of traversal entries.
pub(crate) trait Stack<T> {
    fn push(&mut self, item: T);
    fn pop(&mut self) -> Option<T>;
}

/// A stack of at most `N` entries on the call stack. Pushing more is a bug (the hierarchy picks
/// a stack that holds its [`super::collapse::Tree::stack_need`]) and panics.
pub(crate) struct ArrayStack<T, const N: usize> {
    items: [T; N],
    len: usize,
}

impl<T: Copy + Default, const N: usize> ArrayStack<T, N> {
    #[inline(always)]
    pub fn new() -> Self {
        Self {
            items: [T::default(); N],
            len: 0,
        }
    }
}

impl<T: Copy, const N: usize> Stack<T> for ArrayStack<T, N> {
    #[inline(always)]
    fn push(&mut self, item: T) {
        self.items[self.len] = item;
        self.len += 1;
    }

    #[inline(always)]
    fn pop(&mut self) -> Option<T> {
        self.len = self.len.checked_sub(1)?;
        Some(self.items[self.len])
    }
}

impl<T> Stack<T> for Vec<T> {
    #[inline(always)]
    fn push(&mut self, item: T) {
        Vec::push(self, item);
    }

    #[inline(always)]
    fn pop(&mut self) -> Option<T> {
        Vec::pop(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stack_kinds_hold_what_they_are_chosen_for() {
        assert_eq!(StackKind::for_need(0), StackKind::Small);
        assert_eq!(StackKind::for_need(SMALL_STACK), StackKind::Small);
        assert_eq!(StackKind::for_need(SMALL_STACK + 1), StackKind::Fixed);
        assert_eq!(StackKind::for_need(FIXED_STACK), StackKind::Fixed);
        assert_eq!(StackKind::for_need(FIXED_STACK + 1), StackKind::Heap);
    }

    #[test]
    fn array_stack_is_last_in_first_out_up_to_its_capacity() {
        let mut stack = ArrayStack::<u32, 3>::new();
        for i in 1..=3 {
            stack.push(i);
        }
        assert_eq!([stack.pop(), stack.pop()], [Some(3), Some(2)]);
        stack.push(4);
        assert_eq!(
            [stack.pop(), stack.pop(), stack.pop()],
            [Some(4), Some(1), None]
        );
    }

    #[test]
    #[should_panic(expected = "index out of bounds")]
    fn pushing_past_the_capacity_does_not_go_unnoticed() {
        let mut full = ArrayStack::<u32, 1>::new();
        full.push(1);
        full.push(2);
    }
}
