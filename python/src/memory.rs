//! Memory a call needs, checked before anything is allocated: a call that sizes its arrays from
//! its arguments (a run's samples, a navigation's records, a Monte Carlo's seeds) computes the
//! bytes first and raises `MemoryError` naming them (and what to change) where they do not fit
//! what the process can still allocate, instead of letting the allocator abort the interpreter
//! (Rust's `memory allocation of N bytes failed`, SIGABRT). What can still be allocated is the
//! least of (Linux): the address-space and data-size limits (`ulimit -v`, `ulimit -d`) less what
//! the process maps already, the cgroup's memory limit less its use, and the available memory
//! and swap. Elsewhere nothing is checked up front. The arrays themselves are reserved with
//! `try_reserve`, so a reservation that fails all the same raises `MemoryError` too.

use pyo3::exceptions::PyMemoryError;
use pyo3::prelude::*;

/// Bytes as a number and in GB (or MB), for messages: `8285760000 bytes (8.29 GB)`.
pub fn bytes(n: u128) -> String {
    let x = n as f64;
    if x >= 1e12 {
        format!("{n} bytes ({:.2} TB)", x / 1e12)
    } else if x >= 1e9 {
        format!("{n} bytes ({:.2} GB)", x / 1e9)
    } else {
        format!("{n} bytes ({:.1} MB)", x / 1e6)
    }
}

/// A soft limit from /proc/self/limits (`Max address space`, …), in bytes; `None`: unlimited
/// or unknown.
fn limit(limits: &str, what: &str) -> Option<u128> {
    let rest = limits.lines().find_map(|l| l.strip_prefix(what))?;
    rest.split_whitespace().next()?.parse().ok()
}

/// A `Name:   123 kB` line of /proc/self/status or /proc/meminfo, in bytes.
fn kb(text: &str, key: &str) -> Option<u128> {
    let rest = text.lines().find_map(|l| l.strip_prefix(key))?;
    let kb: u128 = rest.split_whitespace().next()?.parse().ok()?;
    Some(kb * 1024)
}

/// The cgroup (v2) memory limit less the cgroup's use, if there is a limit.
fn cgroup_room() -> Option<(u128, &'static str)> {
    let cg = std::fs::read_to_string("/proc/self/cgroup").ok()?;
    let path = cg.lines().find_map(|l| l.strip_prefix("0::"))?;
    let dir = format!("/sys/fs/cgroup{}", path.trim_end_matches('/'));
    let max: u128 = std::fs::read_to_string(format!("{dir}/memory.max"))
        .ok()?
        .trim()
        .parse()
        .ok()?;
    let current: u128 = std::fs::read_to_string(format!("{dir}/memory.current"))
        .ok()?
        .trim()
        .parse()
        .ok()?;
    Some((max.saturating_sub(current), "its cgroup's memory limit"))
}

/// What the process can still allocate and the bound that sets it (`None`: not known here).
pub fn room() -> Option<(u128, &'static str)> {
    let mut bounds: Vec<(u128, &'static str)> = Vec::new();
    let limits = std::fs::read_to_string("/proc/self/limits").unwrap_or_default();
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    if let (Some(l), Some(used)) = (limit(&limits, "Max address space"), kb(&status, "VmSize:")) {
        bounds.push((
            l.saturating_sub(used),
            "its address-space limit (ulimit -v, RLIMIT_AS)",
        ));
    }
    if let (Some(l), Some(used)) = (limit(&limits, "Max data size"), kb(&status, "VmData:")) {
        bounds.push((
            l.saturating_sub(used),
            "its data-size limit (ulimit -d, RLIMIT_DATA)",
        ));
    }
    bounds.extend(cgroup_room());
    let meminfo = std::fs::read_to_string("/proc/meminfo").unwrap_or_default();
    if let Some(avail) = kb(&meminfo, "MemAvailable:") {
        let swap = kb(&meminfo, "SwapFree:").unwrap_or(0);
        bounds.push((avail + swap, "the machine's available memory and swap"));
    }
    bounds.into_iter().min_by_key(|b| b.0)
}

/// A `MemoryError` for `what` (e.g. `rins.run: 60480000 samples × 137 bytes`) needing `need`
/// bytes, with `hint` (what to change) and, if known, what is left.
pub fn error(what: &str, need: u128, left: Option<(u128, &str)>, hint: &str) -> PyErr {
    let left = match left {
        Some((b, why)) => format!(
            ", more than this process can still allocate ({} under {why})",
            bytes(b)
        ),
        None => ": the allocation failed".into(),
    };
    PyMemoryError::new_err(format!("{what} = {} of arrays{left}; {hint}", bytes(need)))
}

/// Requests below this many bytes are not checked up front (reading the limits takes longer
/// than a short `Simulation.step`); their reservation is still checked.
const UNCHECKED: u128 = 64 << 20;

/// Checks that `need` bytes fit before anything is allocated: `MemoryError` otherwise (see
/// [`error`]).
pub fn check(what: &str, need: u128, hint: &str) -> PyResult<()> {
    if need < UNCHECKED {
        return Ok(());
    }
    match room() {
        Some((left, why)) if need > left => Err(error(what, need, Some((left, why)), hint)),
        _ => Ok(()),
    }
}

/// An empty vector with room for `n` values, or `MemoryError` (through [`error`], for the
/// whole of `need`) if the reservation fails. A large reservation is advised for transparent
/// huge pages ([`advise_huge_pages`]).
pub fn vec<T>(n: u128, what: &str, need: u128, hint: &str) -> PyResult<Vec<T>> {
    let mut v = Vec::<T>::new();
    usize::try_from(n)
        .ok()
        .and_then(|n| v.try_reserve_exact(n).ok())
        .ok_or_else(|| error(what, need, None, hint))?;
    advise_huge_pages(v.as_mut_ptr().cast(), v.capacity() * size_of::<T>());
    Ok(v)
}

/// The transparent-huge-page size of x86-64 and aarch64 (4 KiB base pages).
const HUGE_PAGE: usize = 2 << 20;

/// Asks the kernel to back the whole 2 MiB pages inside `len` bytes at `ptr` with huge pages
/// (`madvise(MADV_HUGEPAGE)`), as numpy does for its own large arrays. Why: the arrays of a
/// run are written once, front to back, and where transparent huge pages are `madvise`-only
/// (the common default) each 4 KiB page costs a fault on first touch: with the truth columns
/// (425 bytes a sample) that was most of the difference between `truth=True` and
/// `truth=False` (docs/python.md, Performance). Advice only: a kernel that declines leaves
/// the memory as it was, so the result is ignored.
#[allow(unsafe_code)] // one madvise call on memory this function's caller just reserved
fn advise_huge_pages(ptr: *mut u8, len: usize) {
    #[cfg(target_os = "linux")]
    {
        let start = (ptr as usize).next_multiple_of(HUGE_PAGE);
        let end = (ptr as usize + len) / HUGE_PAGE * HUGE_PAGE;
        if end > start {
            // SAFETY: [start, end) lies inside the allocation just reserved, which this
            // process owns and nothing reads yet; MADV_HUGEPAGE changes neither its contents
            // nor its mapping, only how later faults are served.
            unsafe {
                libc::madvise(start as *mut libc::c_void, end - start, libc::MADV_HUGEPAGE);
            }
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = (ptr, len, HUGE_PAGE);
}
