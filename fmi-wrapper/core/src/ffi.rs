//! Helpers the FMI 2 and FMI 3 C layers share: arrays from the caller's pointers, and the
//! message of a caught panic.

#![allow(unsafe_code)] // turning the caller's (pointer, length) pairs into slices

use crate::instance::FmiError;

/// The caller's array of `n` elements at `p` (NULL only when `n` is 0).
///
/// # Safety
/// `p` must point at `n` initialised elements that stay valid for the returned lifetime.
pub unsafe fn slice<'a, T>(p: *const T, n: usize) -> Result<&'a [T], FmiError> {
    if n == 0 {
        return Ok(&[]);
    }
    if p.is_null() {
        return Err(FmiError::error("NULL array with a non-zero length"));
    }
    // SAFETY: the caller guarantees `n` elements at `p`.
    Ok(unsafe { std::slice::from_raw_parts(p, n) })
}

/// The caller's writable array of `n` elements at `p` (NULL only when `n` is 0).
///
/// # Safety
/// `p` must point at `n` writable elements, not aliased, valid for the returned lifetime.
pub unsafe fn slice_mut<'a, T>(p: *mut T, n: usize) -> Result<&'a mut [T], FmiError> {
    if n == 0 {
        return Ok(&mut []);
    }
    if p.is_null() {
        return Err(FmiError::error("NULL array with a non-zero length"));
    }
    // SAFETY: the caller guarantees `n` writable elements at `p`.
    Ok(unsafe { std::slice::from_raw_parts_mut(p, n) })
}

/// The text of a panic payload (for the "internal error" log line).
pub fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<String>()
        .cloned()
        .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
        .unwrap_or_default()
}
