//! Transparent huge pages for the large arrays: the program's allocator is
//! the system's, and every block of [`HUGE_FROM`] bytes or more is taken
//! aligned to a huge page and padded to whole huge pages, and marked
//! `MADV_HUGEPAGE` on Linux before its first touch, so that the kernel
//! backs all of it with 2 MiB pages where
//! `/sys/kernel/mm/transparent_hugepage/enabled` is `madvise` (or
//! `always`). A 10⁶-sphere bed keeps about 330 MB in such arrays, a
//! 10⁵-sphere bed about 30 MB in arrays of 2–4 MB; with 4 KiB pages the
//! pair stage's partner reads and the gather's per-body streams walk far
//! more pages than the TLB holds (docs/performance.md, section 3). The
//! advice changes where memory comes from, never what is computed.
//! [`init`] keeps each such block in its own mapping, so that its memory
//! goes back to the system when it is freed.

use std::alloc::{GlobalAlloc, Layout, System};

/// A huge page, bytes.
const HUGE_PAGE: usize = 2 << 20;

/// Smallest block given huge pages, bytes: one huge page. Smaller blocks
/// keep the allocator's ordinary pages (padding them would waste up to
/// half a huge page each); a block from here on wastes less than a third
/// of its size in padding, and nothing at the sizes where it matters.
const HUGE_FROM: usize = HUGE_PAGE;

/// Gives every block of [`HUGE_FROM`] bytes or more its own mapping, for
/// the life of the program: glibc's malloc otherwise raises its mmap
/// threshold to the size of each mapped block it frees (up to 32 MiB), so
/// that later blocks of up to that size come from the heap, whose freed
/// holes stay resident (and keep their huge-page advice, so that any small
/// block placed there later is backed by a whole huge page). A fixed
/// threshold makes a large block's memory go back to the system when it is
/// freed. Call it first thing in `main`; outside glibc it does nothing.
pub fn init() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: sets one malloc parameter; no block is touched.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, HUGE_FROM as libc::c_int);
    }
}

/// The system allocator, with huge pages for large blocks.
pub struct HugePages;

/// Whether a block of `size` bytes is taken on huge pages.
#[inline]
fn huge(size: usize) -> bool {
    size >= HUGE_FROM
}

/// The layout a huge block of `layout` is taken with: aligned to a huge
/// page and padded to whole huge pages, so that every page of it can be a
/// huge one.
#[inline]
fn padded(layout: Layout) -> Layout {
    let size = layout.size().next_multiple_of(HUGE_PAGE);
    // SAFETY: a power-of-two alignment, and a size rounded up to a
    // multiple of it that does not overflow (sizes stay below isize::MAX
    // less a huge page for any block the system could hand out)
    unsafe { Layout::from_size_align_unchecked(size, layout.align().max(HUGE_PAGE)) }
}

/// Marks the `len` bytes from `p` (whole, aligned huge pages)
/// `MADV_HUGEPAGE`. Failure (a kernel without transparent huge pages)
/// leaves the ordinary pages, which is no error.
#[inline]
fn advise(p: *mut u8, len: usize) {
    #[cfg(target_os = "linux")]
    if !p.is_null() {
        // SAFETY: the range is a block this allocator just took; the advice
        // moves no data and frees nothing.
        unsafe {
            libc::madvise(p as *mut libc::c_void, len, libc::MADV_HUGEPAGE);
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = (p, len);
}

// SAFETY: small blocks are passed to the system allocator unchanged; a huge
// block is taken from it with the padded layout, given back with the same
// (`padded` of the caller's layout, which the size decides), and its bytes
// are the caller's as for any block.
unsafe impl GlobalAlloc for HugePages {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if !huge(layout.size()) {
            return System.alloc(layout);
        }
        let big = padded(layout);
        let p = System.alloc(big);
        advise(p, big.size());
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if !huge(layout.size()) {
            return System.alloc_zeroed(layout);
        }
        // advised before the zeroing touches it
        let p = self.alloc(layout);
        if !p.is_null() {
            std::ptr::write_bytes(p, 0, layout.size());
        }
        p
    }

    unsafe fn dealloc(&self, p: *mut u8, layout: Layout) {
        if huge(layout.size()) {
            System.dealloc(p, padded(layout))
        } else {
            System.dealloc(p, layout)
        }
    }

    unsafe fn realloc(&self, p: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if !huge(layout.size()) && !huge(new_size) {
            return System.realloc(p, layout, new_size);
        }
        // within the padding: the block stays where it is
        if huge(layout.size()) && huge(new_size) && new_size <= padded(layout).size() {
            let same = Layout::from_size_align_unchecked(new_size, layout.align());
            if padded(same).size() == padded(layout).size() {
                return p;
            }
        }
        let new = Layout::from_size_align_unchecked(new_size, layout.align());
        let q = self.alloc(new);
        if !q.is_null() {
            std::ptr::copy_nonoverlapping(p, q, layout.size().min(new_size));
            self.dealloc(p, layout);
        }
        q
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// After `init`, a block of 3 MiB taken after a 5 MiB block was freed
    /// still gets its own mapping (glibc's count of mapped bytes grows by
    /// it), where glibc's own rule would have raised the threshold to 5 MiB
    /// at that free and taken the 3 MiB from the heap. Checked in a child
    /// process running only this test, so that no other test's freed
    /// blocks lie in the heap for the 5 MiB to be cut from and no other
    /// test's blocks change the count.
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    #[test]
    fn large_blocks_keep_their_own_mappings() {
        const CHILD: &str = "CLUMP_HUGE_PAGES_TEST_CHILD";
        if std::env::var_os(CHILD).is_none() {
            let out = std::process::Command::new(std::env::current_exe().unwrap())
                .args([
                    "huge_pages::tests::large_blocks_keep_their_own_mappings",
                    "--exact",
                    "--test-threads=1",
                ])
                .env(CHILD, "1")
                .output()
                .unwrap();
            let text = String::from_utf8_lossy(&out.stdout);
            assert!(out.status.success(), "child test failed: {text}");
            assert!(text.contains("1 passed"), "child ran no test: {text}");
            return;
        }
        // bytes in blocks with their own mappings, glibc's count
        let mapped = || unsafe { libc::mallinfo2() }.hblkhd;
        init();
        unsafe {
            let five = Layout::from_size_align(5 << 20, 16).unwrap();
            let before = mapped();
            // black_box: the optimiser may not drop an allocation it sees
            // freed unused
            let p = std::hint::black_box(System.alloc(five));
            assert!(!p.is_null());
            assert!(mapped() >= before + (5 << 20));
            System.dealloc(p, five);
            let three = Layout::from_size_align(3 << 20, 16).unwrap();
            let before = mapped();
            let q = std::hint::black_box(System.alloc(three));
            assert!(!q.is_null());
            assert!(
                mapped() >= before + (3 << 20),
                "a 3 MiB block after a freed 5 MiB one came from the heap"
            );
            System.dealloc(q, three);
        }
    }

    /// A large block from the allocator is usable end to end, zeroed when
    /// asked, aligned to a huge page, and keeps its bytes when grown (past
    /// its padding and within it) and when shrunk to a small block.
    #[test]
    fn large_blocks_are_ordinary_memory() {
        let a = HugePages;
        let n = 3 * HUGE_PAGE + 12345;
        let layout = Layout::from_size_align(n, 64).unwrap();
        let kept = |q: *mut u8, len: usize| {
            let s = unsafe { std::slice::from_raw_parts(q, len) };
            s.iter().enumerate().all(|(i, &b)| b == (i % 251) as u8)
        };
        unsafe {
            let p = a.alloc_zeroed(layout);
            assert!(!p.is_null());
            assert_eq!(p as usize % HUGE_PAGE, 0);
            let s = std::slice::from_raw_parts_mut(p, n);
            assert!(s.iter().all(|&b| b == 0));
            s.iter_mut()
                .enumerate()
                .for_each(|(i, b)| *b = (i % 251) as u8);
            // within the padding to 4 huge pages: in place
            let m = 4 * HUGE_PAGE - 8;
            let q = a.realloc(p, layout, m);
            assert_eq!(q, p);
            assert!(kept(q, n));
            // past it: moved, the bytes with it
            let r = a.realloc(q, Layout::from_size_align(m, 64).unwrap(), 2 * n);
            assert_eq!(r as usize % HUGE_PAGE, 0);
            assert!(kept(r, n));
            // shrunk to a small block
            let small = 1000;
            let t = a.realloc(r, Layout::from_size_align(2 * n, 64).unwrap(), small);
            assert!(kept(t, small));
            a.dealloc(t, Layout::from_size_align(small, 64).unwrap());
        }
    }
}
