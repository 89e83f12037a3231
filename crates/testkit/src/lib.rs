//! Test helpers shared by the workspace's crates (dev-dependency only).
//!
//! [`Counting`] is a global allocator that counts allocations, for the tests that prove a hot
//! path does not allocate. Install it in a test binary of its own (so nothing else allocates
//! meanwhile) and compare [`allocations`] before and after:
//!
//! ```ignore
//! #[global_allocator]
//! static GLOBAL: osrl_testkit::Counting = osrl_testkit::Counting;
//!
//! let before = osrl_testkit::allocations();
//! hot_path();
//! assert_eq!(osrl_testkit::allocations() - before, 0);
//! ```

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

static ALLOCS: AtomicUsize = AtomicUsize::new(0);

/// The system allocator, counting every `alloc` and `realloc`.
pub struct Counting;

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

/// Allocations (and reallocations) counted so far by [`Counting`] in this process.
pub fn allocations() -> usize {
    ALLOCS.load(Ordering::SeqCst)
}
