//! Stopping a segmentation from another thread: a [`Cancel`] flag that
//! [`crate::segment_cancellable`] reads between the stages of Algorithm 1
//! (docs/method.md steps 1–9), between minimal samples and refinements
//! (step 1–3) and between preference rows (step 7).

use crate::SegmentationError;
use std::sync::atomic::{AtomicBool, Ordering};

/// A cancellation flag shared by the caller and a running segmentation.
/// Setting it ([`Cancel::cancel`]) makes the segmentation return
/// [`SegmentationError::Interrupted`] at its next check; reading it is one
/// relaxed atomic load, cheap enough to be done once per hypothesis.
///
/// ```
/// use segmentation::{Cancel, SegmentationError};
/// let cancel = Cancel::new();
/// assert!(cancel.check().is_ok());
/// cancel.cancel();
/// assert!(matches!(cancel.check(), Err(SegmentationError::Interrupted)));
/// ```
#[derive(Debug, Default)]
pub struct Cancel(AtomicBool);

impl Cancel {
    /// A flag not set.
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets the flag: the segmentation stops at its next check.
    pub fn cancel(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    /// True once [`Cancel::cancel`] was called.
    pub fn is_cancelled(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }

    /// `Err(Interrupted)` once the flag is set.
    pub fn check(&self) -> Result<(), SegmentationError> {
        if self.is_cancelled() {
            Err(SegmentationError::Interrupted)
        } else {
            Ok(())
        }
    }
}
