//! The checks every entry point makes before it touches the caller's memory, and the
//! guard that keeps a Rust panic from crossing into C.

use crate::HcmStatus;
use std::panic::{self, AssertUnwindSafe};

/// Runs `body` and returns its status; a panic inside it becomes
/// [`HcmStatus::Panic`] instead of unwinding into C (undefined behaviour) or, since
/// Rust 1.81, aborting the caller's process.
///
/// `AssertUnwindSafe`: after a panic nothing of the interrupted call is used again;
/// every entry point writes its outputs only after its work succeeded.
pub(crate) fn guard(body: impl FnOnce() -> Result<(), HcmStatus>) -> HcmStatus {
    match panic::catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(())) => HcmStatus::Ok,
        Ok(Err(status)) => status,
        Err(payload) => {
            // Dropping the payload runs arbitrary `Drop` code that could panic again,
            // outside any guard: leak it instead (a few bytes, on a bug).
            core::mem::forget(payload);
            HcmStatus::Panic
        }
    }
}

/// `pointer` checked: null is [`HcmStatus::NullPointer`], an address that is not a
/// multiple of `T`'s alignment is [`HcmStatus::Misaligned`].
pub(crate) fn checked<T>(pointer: *const T) -> Result<*const T, HcmStatus> {
    if pointer.is_null() {
        Err(HcmStatus::NullPointer)
    } else if !pointer.is_aligned() {
        Err(HcmStatus::Misaligned)
    } else {
        Ok(pointer)
    }
}

/// [`checked`] for an output pointer.
pub(crate) fn checked_mut<T>(pointer: *mut T) -> Result<*mut T, HcmStatus> {
    checked(pointer.cast_const()).map(|_| pointer)
}

/// The `T` behind an input pointer, after [`checked`].
///
/// # Safety
/// If `pointer` is non-null and aligned, it must point to an initialised `T` that
/// stays unchanged for `'a` (the call). Every input struct of this API is made of
/// integers and floats only, so any initialised bytes are a valid `T`.
pub(crate) unsafe fn input<'a, T>(pointer: *const T) -> Result<&'a T, HcmStatus> {
    let pointer = checked(pointer)?;
    // SAFETY: non-null and aligned (just checked); valid and unaliased by the
    // caller's contract above.
    Ok(unsafe { &*pointer })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_becomes_a_status() {
        let status = guard(|| panic!("a bug inside hcm"));
        assert_eq!(status, HcmStatus::Panic);
        assert_eq!(
            guard(|| Err(HcmStatus::BadParameter)),
            HcmStatus::BadParameter
        );
        assert_eq!(guard(|| Ok(())), HcmStatus::Ok);
    }

    #[test]
    fn null_and_misaligned_pointers_are_refused() {
        let values = [0.0_f32; 2];
        let aligned = values.as_ptr();
        assert_eq!(checked(aligned), Ok(aligned));
        assert_eq!(
            checked(core::ptr::null::<f32>()),
            Err(HcmStatus::NullPointer)
        );
        let odd = aligned.cast::<u8>().wrapping_add(1).cast::<f32>();
        assert_eq!(checked(odd), Err(HcmStatus::Misaligned));
    }
}
