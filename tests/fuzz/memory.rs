//! Memory accounting for the fuzzer: a counting global allocator (peak bytes per input, and a
//! refusal of any single allocation over [`MAX_SINGLE_ALLOC_BYTES`]) and an address-space limit
//! for the whole process, so a parser that asks for gigabytes fails the test instead of swapping
//! the CI machine.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering::Relaxed};

/// Largest single allocation any parser may request under the fuzzer's budgets (64 MiB for a
/// raster, 256 MiB for a scenario): a larger one means a size taken from the input bypassed the
/// budget check.
pub const MAX_SINGLE_ALLOC_BYTES: usize = 1 << 30;

/// Address space allowed to the whole test process: far above what it needs (a few hundred MiB),
/// far below the machine's memory, so a runaway allocation aborts instead of swapping.
pub const ADDRESS_SPACE_LIMIT_BYTES: u64 = 8 << 30;

static CURRENT_BYTES: AtomicUsize = AtomicUsize::new(0);
static PEAK_BYTES: AtomicUsize = AtomicUsize::new(0);
static HUGE_REQUEST_BYTES: AtomicUsize = AtomicUsize::new(0);
static HUGE_SEEN: AtomicBool = AtomicBool::new(false);

/// The system allocator, counting live bytes and their peak.
pub struct Counting;

fn grow(n: usize) {
    let now = CURRENT_BYTES.fetch_add(n, Relaxed).saturating_add(n);
    PEAK_BYTES.fetch_max(now, Relaxed);
}

fn shrink(n: usize) {
    CURRENT_BYTES.fetch_sub(n, Relaxed);
}

/// Records a refused request and saves the input that made it (the process may abort next).
fn refuse(size: usize) {
    HUGE_REQUEST_BYTES.fetch_max(size, Relaxed);
    HUGE_SEEN.store(true, Relaxed);
    super::dump_current_input_raw(size);
}

// SAFETY: every method forwards to `System` with the caller's arguments unchanged; the counters
// are plain atomics and the refusal path allocates nothing.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if layout.size() > MAX_SINGLE_ALLOC_BYTES {
            refuse(layout.size());
            return std::ptr::null_mut();
        }
        // SAFETY: forwarded as received.
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            grow(layout.size());
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if layout.size() > MAX_SINGLE_ALLOC_BYTES {
            refuse(layout.size());
            return std::ptr::null_mut();
        }
        // SAFETY: forwarded as received.
        let p = unsafe { System.alloc_zeroed(layout) };
        if !p.is_null() {
            grow(layout.size());
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: forwarded as received.
        unsafe { System.dealloc(ptr, layout) };
        shrink(layout.size());
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if new_size > MAX_SINGLE_ALLOC_BYTES {
            refuse(new_size);
            return std::ptr::null_mut();
        }
        // SAFETY: forwarded as received.
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if !p.is_null() {
            if new_size >= layout.size() {
                grow(new_size - layout.size());
            } else {
                shrink(layout.size() - new_size);
            }
        }
        p
    }
}

/// Starts measuring one input: resets the peak to the live bytes and returns them.
pub fn start_input() -> usize {
    HUGE_SEEN.store(false, Relaxed);
    let now = CURRENT_BYTES.load(Relaxed);
    PEAK_BYTES.store(now, Relaxed);
    now
}

/// Peak bytes above `baseline` since [`start_input`], and the largest refused request if there
/// was one.
pub fn finish_input(baseline: usize) -> (usize, Option<usize>) {
    let peak = PEAK_BYTES.load(Relaxed).saturating_sub(baseline);
    let huge = HUGE_SEEN
        .swap(false, Relaxed)
        .then(|| HUGE_REQUEST_BYTES.swap(0, Relaxed));
    (peak, huge)
}

/// Lowers the soft address-space limit of this process to [`ADDRESS_SPACE_LIMIT_BYTES`].
pub fn limit_address_space() {
    let mut limit = libc::rlimit {
        rlim_cur: 0,
        rlim_max: 0,
    };
    // SAFETY: plain system calls on a local struct.
    unsafe {
        if libc::getrlimit(libc::RLIMIT_AS, &mut limit) == 0 {
            limit.rlim_cur = limit
                .rlim_max
                .min(ADDRESS_SPACE_LIMIT_BYTES as libc::rlim_t);
            let ok = libc::setrlimit(libc::RLIMIT_AS, &limit);
            assert_eq!(ok, 0, "setrlimit(RLIMIT_AS) failed");
        }
    }
}
