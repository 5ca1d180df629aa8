//! Hints about cache lines: read one ahead ([`prefetch`]), take one for
//! writing ahead ([`WritePrefetch`]), hand lines back to memory
//! ([`ReleaseLines`]). None changes what the program reads or writes; they
//! change where the lines are when it does. Each is what the tiled
//! rasterizer's setup and bands needed on a 2-core virtual machine whose
//! host runs the two cores either beside each other (one last-level cache)
//! or apart (BENCHMARKS.md, "Where the two threads' cores are").

/// Asks the processor to start loading the cache line holding `value`, so
/// that a later read does not wait for memory (a hint: it has no effect on
/// the program's results, and none at all off x86-64).
#[inline(always)]
pub(crate) fn prefetch<T>(value: &T) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        // SAFETY: a prefetch never faults and changes no memory; SSE is part
        // of every x86-64 processor; the address comes from a reference.
        unsafe { _mm_prefetch::<_MM_HINT_T0>((value as *const T).cast()) };
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = value;
}

/// How to ask for a cache line that is about to be written
/// ([`WritePrefetch::line`]): with `PREFETCHW` where the processor has it
/// (every AMD64 processor, Intel's since Broadwell), else as [`prefetch`].
///
/// Why: a line that another core has read is shared with that core's
/// cache, and a store to it must first take it away from there. A read
/// prefetch brings the line shared, so the store still waits for that;
/// `PREFETCHW` takes the line for writing ahead of the store. Setup's bins
/// are such lines: each frame's bands, on every thread, read what the
/// chunks' setup wrote into them, and the next frame's setup writes them
/// again. Where the host runs the two cores of a virtual machine apart (a
/// cache line's round trip between them of 430–650 ns instead of 40–60),
/// setup took 1.7 times as long on the bunny at 1920×1080 (flat); taking
/// the lines for writing won back a third of that (BENCHMARKS.md, "Where
/// the two threads' cores are").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct WritePrefetch {
    exclusive: bool,
}

impl WritePrefetch {
    /// This processor's way, found once.
    pub(crate) fn detect() -> WritePrefetch {
        static EXCLUSIVE: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
        let exclusive = *EXCLUSIVE.get_or_init(has_prefetchw);
        WritePrefetch { exclusive }
    }

    /// Asks the processor to fetch the line holding `value` for writing (a
    /// hint: it has no effect on the program's results, and none at all off
    /// x86-64).
    #[inline(always)]
    pub(crate) fn line<T>(self, value: &T) {
        #[cfg(target_arch = "x86_64")]
        if self.exclusive {
            // SAFETY: `detect` found PREFETCHW (CPUID 8000_0001h, ECX bit
            // 8); a prefetch never faults, writes no memory and leaves the
            // flags; the address comes from a reference.
            unsafe {
                std::arch::asm!(
                    "prefetchw byte ptr [{0}]",
                    in(reg) (value as *const T),
                    options(nostack, preserves_flags, readonly),
                );
            }
            return;
        }
        prefetch(value);
    }
}

/// Whether the processor has `PREFETCHW` (CPUID leaf 8000_0001h, ECX bit 8;
/// the standard library's feature detection does not name it).
fn has_prefetchw() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::__cpuid;
        // SAFETY: CPUID exists on every x86-64 processor; leaf 8000_0001h
        // is read only where leaf 8000_0000h says it exists. (`__cpuid` is
        // a safe function in the newest Rust; the block keeps the oldest
        // this builds with, 1.89, building.)
        #[allow(unused_unsafe)]
        unsafe {
            let highest = __cpuid(0x8000_0000).eax;
            highest >= 0x8000_0001 && __cpuid(0x8000_0001).ecx & (1 << 8) != 0
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    false
}

/// How a thread hands back to memory the cache lines of data that another
/// thread wrote and will write again ([`ReleaseLines::slice`]): with
/// `CLFLUSHOPT` where the processor has it, else not at all.
///
/// Why: each frame's bands read the bins that setup wrote on either thread,
/// and the next frame's setup writes the same lines again. A line read by
/// the other core is shared with that core's cache, and where the host
/// runs the two cores apart (a cache line's round trip of 300–650 ns), the
/// write waits to take it back from there, even prefetched for writing:
/// the dragon's 1920×1080 Phong spent 0.5 ms of its two-thread setup's 1.6
/// on it. Flushed once the band has read it, the line is in memory alone,
/// and the write takes it from there, without asking the other core:
/// setup 1.31 ms, the frame 4.66 → 4.39 ms. With the cores beside each
/// other the flush costs time instead, so the tiled rasterizer flushes
/// only where it measures the cores apart (`raster/tiled/placement.rs`;
/// BENCHMARKS.md, "Bins handed back where the cores are apart").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct ReleaseLines {
    /// The flushed line's size in bytes (`CLFLUSH`'s, from CPUID), or 0:
    /// no `CLFLUSHOPT`, nothing flushed.
    line: usize,
}

impl ReleaseLines {
    /// This processor's way, found once.
    pub(crate) fn detect() -> ReleaseLines {
        static LINE: std::sync::OnceLock<usize> = std::sync::OnceLock::new();
        ReleaseLines {
            line: *LINE.get_or_init(clflushopt_line),
        }
    }

    /// Hands the cache lines holding `items` back to memory (a hint: the
    /// values read and written stay the same; no effect off x86-64 or
    /// without `CLFLUSHOPT`).
    #[inline]
    pub(crate) fn slice<T>(self, items: &[T]) {
        #[cfg(target_arch = "x86_64")]
        if self.line != 0 && !items.is_empty() {
            let start = items.as_ptr() as usize;
            let end = start + std::mem::size_of_val(items);
            let mut line = start - start % self.line;
            while line < end {
                // SAFETY: `detect` found CLFLUSHOPT (CPUID leaf 7, EBX bit
                // 23). It writes a modified line back and drops it from
                // the caches, so the memory keeps its values; it neither
                // faults on nor changes the flags. Every line flushed holds
                // at least one byte of `items`, so its address is mapped.
                unsafe {
                    std::arch::asm!(
                        "clflushopt byte ptr [{0}]",
                        in(reg) line,
                        options(nostack, preserves_flags, readonly),
                    );
                }
                line += self.line;
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        let _ = items;
    }
}

/// The size in bytes of the line `CLFLUSHOPT` flushes (CPUID leaf 1, EBX
/// bits 8–15, in 8-byte units), or 0 when the processor lacks `CLFLUSHOPT`
/// (CPUID leaf 7 subleaf 0, EBX bit 23; the standard library's feature
/// detection does not name it).
fn clflushopt_line() -> usize {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{__cpuid, __cpuid_count};
        // SAFETY: CPUID exists on every x86-64 processor; leaf 7 is read
        // only where leaf 0 says it exists. (As in `has_prefetchw`.)
        #[allow(unused_unsafe)]
        unsafe {
            if __cpuid(0).eax < 7 || __cpuid_count(7, 0).ebx & (1 << 23) == 0 {
                return 0;
            }
            ((__cpuid(1).ebx >> 8) & 0xff) as usize * 8
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    0
}
