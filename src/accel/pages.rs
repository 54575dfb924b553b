//! Vectors of plain data whose large buffers ask the OS for 2 MiB pages.
//!
//! A big mesh's tree is tens of megabytes read at random: with 4 KiB pages
//! nearly every node visit and block test of an incoherent ray also misses
//! the TLB (the 1M-triangle mesh's tree spans 12,000 pages; a recent x86
//! core's second-level TLB holds 1,500 to 2,048 entries, by the vendors'
//! manuals). Linux backs memory with 2 MiB pages
//! ("transparent huge pages") where the process asks for them with
//! `madvise(MADV_HUGEPAGE)`, its default setting, and Embree asks for its
//! trees (`os_malloc` in its `common/sys/alloc.cpp`), so ptsc does too for
//! its own. Measurements: docs/performance.md, "Huge pages for the tree".
//!
//! The buffer is an anonymous mapping (`memmap2`, safe to create) viewed as
//! a slice of `T` through `bytemuck` (which checks size and alignment), so
//! no `unsafe` is needed. Small buffers, buffers the OS will not map (they
//! move back to the heap) and other systems than Linux use plain `Vec`s.

use bytemuck::Pod;
use memmap2::MmapMut;
use std::fmt;
use std::marker::PhantomData;
use std::ops::{Deref, DerefMut};

/// Buffers from this many bytes up are mapped: below it, a single huge page
/// would hold all of it and more, and a small tree fits the TLB anyway.
const MAPPED_FROM: usize = 4 << 20;

/// A vector of `T` that moves to a mapping advised for huge pages once it
/// holds (or reserves) [`MAPPED_FROM`] bytes. Dereferences to `[T]`.
pub struct PagedVec<T: Pod>(Buffer<T>);

/// Where a [`PagedVec`]'s elements are (private: `len` must stay within the
/// mapping).
enum Buffer<T: Pod> {
    /// A small buffer on the heap, or a large one the OS would not map.
    Heap(Vec<T>),
    /// A large one: the mapping (bytes past `len` elements are zero) and
    /// the elements in use.
    Mapped {
        map: MmapMut,
        len: usize,
        element: PhantomData<T>,
    },
}

impl<T: Pod> PagedVec<T> {
    /// An empty vector.
    pub fn new() -> Self {
        PagedVec(Buffer::Heap(Vec::new()))
    }

    /// How many elements fit before the buffer moves.
    pub fn capacity(&self) -> usize {
        match &self.0 {
            Buffer::Heap(v) => v.capacity(),
            // (Zero-sized elements are never mapped.)
            Buffer::Mapped { map, .. } => map.len() / size_of::<T>(),
        }
    }

    /// Makes room for `additional` more elements, exactly.
    pub fn reserve_exact(&mut self, additional: usize) {
        let needed = self.len().saturating_add(additional);
        if needed > self.capacity() && !self.remap(needed) {
            self.heap_reserve(additional, true);
        }
    }

    /// Appends an element, growing as a `Vec` does.
    pub fn push(&mut self, value: T) {
        let len = self.len();
        if len == self.capacity() && !self.remap(len.saturating_mul(2).max(4)) {
            self.heap_reserve(1, false);
        }
        match &mut self.0 {
            Buffer::Heap(v) => v.push(value),
            Buffer::Mapped { map, len, .. } => {
                let at = *len * size_of::<T>();
                map[at..at + size_of::<T>()].copy_from_slice(bytemuck::bytes_of(&value));
                *len += 1;
            }
        }
    }

    /// Reserves on the heap, moving the elements out of a mapping the OS
    /// would not grow (a `Vec` then fails as it would have anyway).
    fn heap_reserve(&mut self, additional: usize, exact: bool) {
        let mut v = match std::mem::replace(&mut self.0, Buffer::Heap(Vec::new())) {
            Buffer::Heap(v) => v,
            Buffer::Mapped { map, len, .. } => {
                bytemuck::cast_slice::<u8, T>(&map[..len * size_of::<T>()]).to_vec()
            }
        };
        if exact {
            v.reserve_exact(additional);
        } else {
            v.reserve(additional);
        }
        self.0 = Buffer::Heap(v);
    }

    /// Moves the elements to a mapping of `capacity` elements advised for
    /// huge pages, when that is large enough to be worth it and the OS
    /// gives it; whether it did. Only on Linux: elsewhere the advice does
    /// not exist and a mapping would bring nothing.
    fn remap(&mut self, capacity: usize) -> bool {
        if !cfg!(target_os = "linux") || size_of::<T>() == 0 {
            return false;
        }
        let Some(bytes) = capacity.checked_mul(size_of::<T>()) else {
            return false;
        };
        if bytes < MAPPED_FROM {
            return false;
        }
        let Ok(mut map) = MmapMut::map_anon(bytes) else {
            return false;
        };
        // Only a request: the kernel may decline (THP off), and then the
        // mapping is ordinary memory.
        #[cfg(target_os = "linux")]
        let _ = map.advise(memmap2::Advice::HugePage);
        let len = self.len();
        let used = len * size_of::<T>();
        map[..used].copy_from_slice(bytemuck::cast_slice(&self[..]));
        self.0 = Buffer::Mapped {
            map,
            len,
            element: PhantomData,
        };
        true
    }

    /// Whether the elements live in a mapping.
    pub fn is_mapped(&self) -> bool {
        matches!(self.0, Buffer::Mapped { .. })
    }
}

impl<T: Pod> Default for PagedVec<T> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Pod> Deref for PagedVec<T> {
    type Target = [T];

    #[inline(always)]
    fn deref(&self) -> &[T] {
        match &self.0 {
            Buffer::Heap(v) => v,
            Buffer::Mapped { map, len, .. } => bytemuck::cast_slice(&map[..*len * size_of::<T>()]),
        }
    }
}

impl<T: Pod> DerefMut for PagedVec<T> {
    #[inline(always)]
    fn deref_mut(&mut self) -> &mut [T] {
        match &mut self.0 {
            Buffer::Heap(v) => v,
            Buffer::Mapped { map, len, .. } => {
                bytemuck::cast_slice_mut(&mut map[..*len * size_of::<T>()])
            }
        }
    }
}

impl<T: Pod> Clone for PagedVec<T> {
    fn clone(&self) -> Self {
        self.iter().copied().collect()
    }
}

impl<T: Pod + fmt::Debug> fmt::Debug for PagedVec<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

impl<T: Pod> FromIterator<T> for PagedVec<T> {
    fn from_iter<I: IntoIterator<Item = T>>(iter: I) -> Self {
        let iter = iter.into_iter();
        let mut out = PagedVec::new();
        out.reserve_exact(iter.size_hint().0);
        for value in iter {
            out.push(value);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_vectors_stay_on_the_heap_and_large_ones_are_mapped() {
        let mut small: PagedVec<[f32; 4]> = PagedVec::new();
        for k in 0..1000 {
            small.push([k as f32; 4]);
        }
        assert!(!small.is_mapped());
        let n = MAPPED_FROM / size_of::<[f32; 4]>() + 3;
        let mut large: PagedVec<[f32; 4]> = PagedVec::new();
        for k in 0..n {
            large.push([k as f32; 4]);
        }
        assert_eq!(large.is_mapped(), cfg!(target_os = "linux"));
        assert_eq!(large.len(), n);
        assert!((0..n).all(|k| large[k] == [k as f32; 4]));
        large[7][1] = -1.0;
        assert_eq!(large[7], [7.0, -1.0, 7.0, 7.0]);
        let copy = large.clone();
        assert_eq!(&copy[..], &large[..]);
    }

    #[test]
    fn reserving_maps_up_front_and_keeps_what_was_pushed() {
        let mut v: PagedVec<u32> = PagedVec::new();
        v.push(5);
        v.push(6);
        v.reserve_exact(MAPPED_FROM);
        assert_eq!(v.is_mapped(), cfg!(target_os = "linux"));
        assert!(v.capacity() >= MAPPED_FROM + 2);
        assert_eq!(&v[..], &[5, 6]);
        v.push(7);
        assert_eq!(&v[..], &[5, 6, 7]);
        let collected: PagedVec<u32> = (0..10).collect();
        assert_eq!(&collected[..], &(0..10).collect::<Vec<_>>()[..]);
    }

    #[test]
    fn an_impossible_reservation_stays_usable() {
        let mut v: PagedVec<u64> = PagedVec::new();
        // usize::MAX / 8 elements do not fit in the address space: the
        // mapping fails, and the vector is as it was.
        v.push(1);
        assert!(!v.remap(usize::MAX / 8));
        assert_eq!(&v[..], &[1]);
    }

    #[test]
    fn a_mapping_that_cannot_grow_moves_back_to_the_heap() {
        let n = MAPPED_FROM / size_of::<u64>();
        let mut v: PagedVec<u64> = (0..n as u64).collect();
        assert_eq!(v.is_mapped(), cfg!(target_os = "linux"));
        // What `push` and `reserve_exact` do when the OS refuses a larger
        // mapping.
        v.heap_reserve(1, false);
        assert!(!v.is_mapped());
        v.push(n as u64);
        assert_eq!(v.len(), n + 1);
        assert!(v.iter().enumerate().all(|(k, &x)| x == k as u64));
    }
}
