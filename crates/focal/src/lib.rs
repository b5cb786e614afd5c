//! focal crate (under construction).
