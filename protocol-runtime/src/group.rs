//! [`Group`]: a repeated group of up to `N` elements stored inline, without a heap. A payload
//! struct may end with one whose count follows from the payload's length (the servos of a
//! Dynamixel sync write).

use core::fmt;
use core::ops::Deref;

/// Up to `N` elements of `T`, stored inline.
#[derive(Clone, Copy)]
pub struct Group<T: Copy + Default, const N: usize> {
    len: usize,
    items: [T; N],
}

impl<T: Copy + Default, const N: usize> Group<T, N> {
    /// No elements.
    pub fn new() -> Self {
        Group {
            len: 0,
            items: [T::default(); N],
        }
    }

    /// A copy of `items`, or `None` if there are more than `N`.
    pub fn from_slice(items: &[T]) -> Option<Self> {
        let mut out = Self::new();
        out.items.get_mut(..items.len())?.copy_from_slice(items);
        out.len = items.len();
        Some(out)
    }

    /// Appends an element; gives it back when the group is full.
    ///
    /// # Errors
    ///
    /// The element, when the group already holds `N`.
    pub fn push(&mut self, item: T) -> Result<(), T> {
        match self.items.get_mut(self.len) {
            Some(slot) => {
                *slot = item;
                self.len = self.len.saturating_add(1);
                Ok(())
            }
            None => Err(item),
        }
    }

    /// The elements.
    pub fn as_slice(&self) -> &[T] {
        self.items.get(..self.len).unwrap_or(&[])
    }

    /// The capacity `N`.
    pub const fn capacity(&self) -> usize {
        N
    }
}

impl<T: Copy + Default, const N: usize> Default for Group<T, N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Copy + Default, const N: usize> Deref for Group<T, N> {
    type Target = [T];
    fn deref(&self) -> &[T] {
        self.as_slice()
    }
}

impl<T: Copy + Default + PartialEq, const N: usize> PartialEq for Group<T, N> {
    fn eq(&self, other: &Self) -> bool {
        self.as_slice() == other.as_slice()
    }
}

impl<T: Copy + Default + Eq, const N: usize> Eq for Group<T, N> {}

impl<T: Copy + Default + core::hash::Hash, const N: usize> core::hash::Hash for Group<T, N> {
    fn hash<H: core::hash::Hasher>(&self, state: &mut H) {
        self.as_slice().hash(state);
    }
}

impl<T: Copy + Default + fmt::Debug, const N: usize> fmt::Debug for Group<T, N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.as_slice()).finish()
    }
}

#[cfg(test)]
// Tests may index and unwrap: a panic there is a failed test, not a runtime fault.
#[allow(
    clippy::indexing_slicing,
    clippy::arithmetic_side_effects,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic
)]
mod tests {
    use super::*;

    #[test]
    fn holds_up_to_its_capacity() {
        let mut g = Group::<u16, 2>::new();
        assert_eq!(g.push(1), Ok(()));
        assert_eq!(g.push(2), Ok(()));
        assert_eq!(g.push(3), Err(3));
        assert_eq!(g.as_slice(), &[1, 2]);
        assert_eq!(Group::<u16, 2>::from_slice(&[1, 2]), Some(g));
        assert!(Group::<u16, 1>::from_slice(&[1, 2]).is_none());
    }
}
