//! clustering crate (under construction).
