//! The instance handles that are alive in this process: registered at instantiate, removed at
//! free. Every C entry point looks its handle up here before touching memory, so that a caller's
//! misuse (freeing an instance twice, calling doStep after fmi2FreeInstance, passing a pointer
//! that never was an instance) is refused with an error status instead of freeing or reading
//! memory that is not an instance: a double free aborts the whole host process ("double free or
//! corruption"), with every other FMU and the master's unsaved results in it.
//!
//! A handle is keyed by its address and the Rust type behind it, so that an instance of one
//! model is not taken for another's (one process may load several models' libraries, and the
//! tests link several models into one binary). The check cannot tell a stale handle from a new
//! instance the allocator has placed at the same address; it catches every misuse before that.

use std::any::TypeId;
use std::collections::BTreeMap;
use std::ffi::c_void;
use std::sync::{Mutex, MutexGuard};

/// Address → type of every live handle.
static LIVE: Mutex<BTreeMap<usize, TypeId>> = Mutex::new(BTreeMap::new());

/// The table, whatever a panicking holder left (it only holds plain data, always consistent
/// between two statements): a poisoned lock must not turn every later call into a panic.
fn table() -> MutexGuard<'static, BTreeMap<usize, TypeId>> {
    LIVE.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Records `handle`, just created, as a live `T`.
pub fn register<T: 'static>(handle: *mut c_void) {
    table().insert(handle as usize, TypeId::of::<T>());
}

/// Whether `handle` is a live `T` (false for NULL, a freed handle or any other pointer).
pub fn is_live<T: 'static>(handle: *mut c_void) -> bool {
    table().get(&(handle as usize)) == Some(&TypeId::of::<T>())
}

/// Removes `handle` if it is a live `T`; true if it was, and the caller may then free it (once:
/// a second call returns false).
pub fn unregister<T: 'static>(handle: *mut c_void) -> bool {
    let mut t = table();
    let key = handle as usize;
    if t.get(&key) == Some(&TypeId::of::<T>()) {
        t.remove(&key);
        true
    } else {
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    struct A;
    struct B;

    #[test]
    fn a_handle_is_live_from_register_to_unregister_and_only_once() {
        let mut x = 0u8;
        let h = &mut x as *mut u8 as *mut c_void;
        assert!(!is_live::<A>(h));
        register::<A>(h);
        assert!(is_live::<A>(h));
        assert!(!is_live::<B>(h), "another type at the same address");
        assert!(!unregister::<B>(h));
        assert!(unregister::<A>(h));
        assert!(!is_live::<A>(h));
        assert!(!unregister::<A>(h), "a second free");
        assert!(!is_live::<A>(std::ptr::null_mut()));
    }
}
