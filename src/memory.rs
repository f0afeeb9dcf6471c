//! The process's memory policy for programs that run many walks: the CLI, the benchmarks, or a
//! program that embeds klaw in a loop (a sweep of its own, a game generating walks on demand).
//!
//! A walk allocates and frees its steps' records, ≈ 1 MB for ten steps. glibc's `free` hands the
//! top of its heap back to the kernel once more than 128 KiB is free there (`M_TRIM_THRESHOLD`),
//! so with its defaults every walk of a bench, a sweep or a long streamed walk faults the same
//! pages in again (what that cost, and what [`keep_freed_memory`] saves: docs/engine.md, "Files
//! and sweeps").

/// Keep up to 64 MiB of freed memory at the top of glibc's heaps instead of returning it to the
/// kernel at every `free` (glibc on Linux; elsewhere nothing). Only what was already in use
/// stays mapped, so peak memory barely moves, and large buffers (≥ 128 KiB) are still mapped and
/// unmapped on their own. Call it once, early; `klaw` (the binary) does (`tests/memory.rs`
/// counts its page faults).
pub fn keep_freed_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: mallopt takes no pointers and only sets an allocator parameter; glibc documents it
    // as thread-safe (MT-Safe).
    unsafe {
        libc::mallopt(libc::M_TRIM_THRESHOLD, 64 << 20);
    }
}
