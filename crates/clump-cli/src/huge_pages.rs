//! Transparent huge pages for the large arrays: the program's allocator is
//! the system's, and every block of [`HUGE_FROM`] bytes or more it hands
//! out (or grows) is marked `MADV_HUGEPAGE` on Linux, before the first
//! touch of a fresh mapping, so that the kernel backs it with 2 MiB pages
//! where `/sys/kernel/mm/transparent_hugepage/enabled` is `madvise` (or
//! `always`). A 10⁶-sphere bed keeps about 330 MB in such arrays; with
//! 4 KiB pages the pair stage's partner reads and the gather's per-body
//! streams walk far more pages than the TLB holds (docs/performance.md,
//! section 3). The advice changes where memory comes from, never what is
//! computed.

use std::alloc::{GlobalAlloc, Layout, System};

/// A huge page, bytes.
const HUGE_PAGE: usize = 2 << 20;

/// Smallest block given the advice, bytes: four huge pages, so that the
/// rounding inwards to whole huge pages leaves most of the block covered,
/// and small blocks keep the allocator's ordinary pages.
const HUGE_FROM: usize = 4 * HUGE_PAGE;

/// The system allocator, with huge-page advice for large blocks.
pub struct HugePages;

/// Marks the whole huge pages inside `len` bytes from `p` `MADV_HUGEPAGE`.
/// Failure (a kernel without transparent huge pages) leaves the ordinary
/// pages, which is no error.
#[inline]
fn advise(p: *mut u8, len: usize) {
    if p.is_null() || len < HUGE_FROM {
        return;
    }
    let start = (p as usize).next_multiple_of(HUGE_PAGE);
    let end = (p as usize + len) & !(HUGE_PAGE - 1);
    #[cfg(target_os = "linux")]
    if end > start {
        // SAFETY: the range lies inside a block this allocator just handed
        // out; the advice moves no data and frees nothing.
        unsafe {
            libc::madvise(start as *mut libc::c_void, end - start, libc::MADV_HUGEPAGE);
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = (start, end);
}

// SAFETY: every call is passed to the system allocator unchanged; the
// advice only tells the kernel how to back the pages of the block.
unsafe impl GlobalAlloc for HugePages {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = System.alloc(layout);
        advise(p, layout.size());
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let p = System.alloc_zeroed(layout);
        advise(p, layout.size());
        p
    }

    unsafe fn dealloc(&self, p: *mut u8, layout: Layout) {
        System.dealloc(p, layout)
    }

    unsafe fn realloc(&self, p: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let q = System.realloc(p, layout, new_size);
        advise(q, new_size);
        q
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A large block from the allocator is usable end to end, zeroed when
    /// asked, and keeps its bytes when grown.
    #[test]
    fn large_blocks_are_ordinary_memory() {
        let a = HugePages;
        let n = 3 * HUGE_FROM + 12345;
        let layout = Layout::from_size_align(n, 64).unwrap();
        unsafe {
            let p = a.alloc_zeroed(layout);
            assert!(!p.is_null());
            let s = std::slice::from_raw_parts_mut(p, n);
            assert!(s.iter().all(|&b| b == 0));
            s.iter_mut()
                .enumerate()
                .for_each(|(i, b)| *b = (i % 251) as u8);
            let q = a.realloc(p, layout, 2 * n);
            let s = std::slice::from_raw_parts(q, n);
            assert!(s.iter().enumerate().all(|(i, &b)| b == (i % 251) as u8));
            a.dealloc(q, Layout::from_size_align(2 * n, 64).unwrap());
        }
    }
}
