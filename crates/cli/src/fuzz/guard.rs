//! The fuzz run's guards: a global allocator that bounds what one case may allocate, and a
//! watchdog that ends the process when one case runs too long (a hang).

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::io::Write;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// One allocation larger than this during a case ends the process (it would exhaust memory).
pub const HARD_BYTES: usize = 1 << 30;

thread_local! {
    static ACTIVE: Cell<bool> = const { Cell::new(false) };
    static LIVE: Cell<usize> = const { Cell::new(0) };
    static PEAK: Cell<usize> = const { Cell::new(0) };
}

/// The case running now (for the messages of the allocator and the watchdog).
pub static CASE: AtomicUsize = AtomicUsize::new(usize::MAX);
static STARTED_MS: AtomicU64 = AtomicU64::new(0);
static RUNNING: AtomicBool = AtomicBool::new(false);

/// The system allocator, measuring the live bytes of a case on the fuzzing thread.
pub struct Bounded;

fn grow(size: usize) {
    let _ = ACTIVE.try_with(|a| {
        if !a.get() {
            return;
        }
        if size > HARD_BYTES {
            die(b"fuzz: one allocation of more than 1 GiB in case ");
        }
        let live = LIVE.with(|l| {
            l.set(l.get() + size);
            l.get()
        });
        PEAK.with(|p| p.set(p.get().max(live)));
    });
}

fn shrink(size: usize) {
    let _ = ACTIVE.try_with(|a| {
        if a.get() {
            LIVE.with(|l| l.set(l.get().saturating_sub(size)));
        }
    });
}

/// Writes `msg`, the case number and a hint to stderr without allocating, then aborts.
fn die(msg: &[u8]) -> ! {
    let mut digits = [0u8; 20];
    let (mut n, mut i) = (CASE.load(Ordering::Relaxed), digits.len());
    loop {
        i -= 1;
        digits[i] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    let mut e = std::io::stderr();
    let _ = e.write_all(msg);
    let _ = e.write_all(&digits[i..]);
    let _ = e.write_all(b" (rerun it alone with FUZZ_CASE=that number)\n");
    std::process::abort();
}

unsafe impl GlobalAlloc for Bounded {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        grow(layout.size());
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        grow(layout.size());
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        shrink(layout.size());
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        grow(new_size);
        shrink(layout.size());
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

/// Starts measuring case `k` on this thread.
pub fn begin(k: usize) {
    CASE.store(k, Ordering::Relaxed);
    LIVE.with(|l| l.set(0));
    PEAK.with(|p| p.set(0));
    STARTED_MS.store(now_ms(), Ordering::Relaxed);
    RUNNING.store(true, Ordering::Release);
    ACTIVE.with(|a| a.set(true));
}

/// Ends the case; the most bytes it had allocated at once (beyond what it freed).
pub fn end() -> usize {
    ACTIVE.with(|a| a.set(false));
    RUNNING.store(false, Ordering::Release);
    PEAK.with(|p| p.get())
}

fn now_ms() -> u64 {
    static T0: std::sync::OnceLock<Instant> = std::sync::OnceLock::new();
    T0.get_or_init(Instant::now).elapsed().as_millis() as u64
}

/// A thread that aborts the process when one case runs longer than `budget` (a hang).
pub fn watchdog(budget: Duration) {
    now_ms();
    std::thread::spawn(move || loop {
        std::thread::sleep(Duration::from_millis(200));
        let started = STARTED_MS.load(Ordering::Relaxed);
        if RUNNING.load(Ordering::Acquire)
            && now_ms().saturating_sub(started) > budget.as_millis() as u64
        {
            die(b"fuzz: a case ran longer than its time budget (a hang): case ");
        }
    });
}
