//! The binary's memory policy (`klaw::memory::keep_freed_memory`): a bench of many walks
//! faults its pages in once, not once per walk. Alone in its test binary, so that the children
//! whose page faults `getrusage(RUSAGE_CHILDREN)` adds up are this test's only.
#![cfg(all(target_os = "linux", target_env = "gnu"))]

use std::process::Command;

/// Minor page faults of the waited-for children so far.
fn children_minor_faults() -> i64 {
    let mut usage = std::mem::MaybeUninit::<libc::rusage>::zeroed();
    // SAFETY: getrusage writes one rusage into the pointer it is given.
    let rc = unsafe { libc::getrusage(libc::RUSAGE_CHILDREN, usage.as_mut_ptr()) };
    assert_eq!(rc, 0, "getrusage failed");
    // SAFETY: initialized by the successful call above.
    unsafe { usage.assume_init() }.ru_minflt
}

fn bench_faults(repeat: &str) -> i64 {
    let before = children_minor_faults();
    let out = Command::new(env!("CARGO_BIN_EXE_klaw"))
        .args(["bench", "--repeat", repeat])
        .output()
        .expect("klaw runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    children_minor_faults() - before
}

/// 100 walks more cost fewer than 1 000 page faults more (with glibc's default trim threshold
/// each default walk faulted ≈ 120 pages in again: ≈ 12 000 for 100; with the policy ≈ 0).
#[test]
fn walks_reuse_their_memory() {
    let one = bench_faults("1");
    let many = bench_faults("101");
    assert!(
        many - one < 1_000,
        "1 walk: {one} page faults, 101 walks: {many}"
    );
}
