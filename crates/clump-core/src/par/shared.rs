//! A raw pointer that parallel loops use to write disjoint elements, and
//! unchecked reads for the hot loops.

/// Pointer to the start of a slice, shared across threads. Safety: callers
/// must write each element from at most one thread at a time, and keep the
/// slice alive and unmoved while in use.
#[derive(Clone, Copy)]
pub(crate) struct SharedMut<T>(*mut T, usize);

unsafe impl<T: Send> Send for SharedMut<T> {}
unsafe impl<T: Send> Sync for SharedMut<T> {}

impl<T> SharedMut<T> {
    pub(crate) fn new(s: &mut [T]) -> Self {
        SharedMut(s.as_mut_ptr(), s.len())
    }

    /// # Safety
    /// `i` is written by this thread only, for the duration of the borrow.
    #[inline(always)]
    #[allow(clippy::mut_from_ref)]
    pub(crate) unsafe fn get(&self, i: usize) -> &mut T {
        debug_assert!(i < self.1);
        &mut *self.0.add(i)
    }

    /// Reads element `i` (a copy; no reference to the slice is formed).
    ///
    /// # Safety
    /// `i` is in range and no other thread writes it during the call.
    #[inline(always)]
    pub(crate) unsafe fn read(&self, i: usize) -> T
    where
        T: Copy,
    {
        debug_assert!(i < self.1);
        *self.0.add(i)
    }

    /// Pointer to element `i`, for access to one field of it through raw
    /// pointers (no reference to the whole element is formed).
    ///
    /// # Safety
    /// `i` is in range.
    #[inline(always)]
    pub(crate) unsafe fn ptr(&self, i: usize) -> *mut T {
        debug_assert!(i < self.1);
        self.0.add(i)
    }

    /// The start of the slice, for reads through raw pointers.
    pub(crate) fn as_ptr(&self) -> *const T {
        self.0
    }

    /// Number of elements.
    pub(crate) fn len(&self) -> usize {
        self.1
    }
}

/// `v[i]` without a bounds check in release builds (checked in debug builds).
///
/// # Safety
/// `i < v.len()`.
#[inline(always)]
pub(crate) unsafe fn at<T: Copy>(v: &[T], i: usize) -> T {
    debug_assert!(i < v.len());
    *v.get_unchecked(i)
}
