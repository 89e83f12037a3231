//! Test helpers shared by the workspace's crates (dev-dependency only).
//!
//! [`Counting`] is a global allocator that counts allocations, for the tests that prove a hot
//! path does not allocate. Install it in a test binary and compare [`allocations`] (the calling
//! thread's count) before and after:
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
use std::cell::Cell;

thread_local! {
    // Per thread: the test harness's own threads allocate now and then while a test runs, and
    // must not be blamed on the code under test. Const-initialised, so reading it never allocates.
    static ALLOCS: Cell<usize> = const { Cell::new(0) };
}

fn count() {
    // `try_with`: during thread teardown the slot may be gone; such allocations are not counted.
    let _ = ALLOCS.try_with(|c| c.set(c.get() + 1));
}

/// The system allocator, counting every `alloc` and `realloc` of the calling thread.
pub struct Counting;

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

/// Allocations (and reallocations) counted so far by [`Counting`] on the calling thread.
pub fn allocations() -> usize {
    ALLOCS.with(|c| c.get())
}
