//! Cache hints (issue 36 point 4): asking the processor for memory a loop will read a few
//! iterations later, where the hardware cannot guess the address (a scatter through an index
//! array, the heap allocations of a model's elements) or its stride (the band LU's column
//! segments). A hint only: it never faults and changes no result.

/// Cache line [bytes].
const LINE: usize = 64;

/// Asks for the cache line holding the byte at `p`.
#[inline(always)]
pub(crate) fn line<T>(p: *const T) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: a prefetch never faults and reads nothing the program sees, whatever `p`.
    #[allow(unused_unsafe)]
    unsafe {
        std::arch::x86_64::_mm_prefetch::<{ std::arch::x86_64::_MM_HINT_T0 }>(p.cast::<i8>());
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = p;
}

/// Asks for the lines of the `len` bytes from `p`.
#[inline(always)]
pub(crate) fn lines<T>(p: *const T, len: usize) {
    let p = p.cast::<u8>();
    let mut offset = 0;
    while offset < len {
        line(p.wrapping_add(offset));
        offset += LINE;
    }
}

/// Asks for the line of `slice[i]`, when there is one.
#[inline(always)]
pub(crate) fn at<T>(slice: &[T], i: usize) {
    if i < slice.len() {
        line(slice.as_ptr().wrapping_add(i));
    }
}
