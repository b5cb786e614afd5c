//! Arbitrary bytes into the MAT v5 reader and the AdelaideRMF scene builder:
//! no panic, and whatever parses re-encodes into a file that parses again.
#![no_main]

use datasets::adelaidermf::{parse_scene, LoadOptions};
use datasets::mat::parse_mat;
use libfuzzer_sys::fuzz_target;
use std::path::Path;

/// The test-support writer, shared with the crate's tests.
#[path = "../../crates/datasets/tests/common/mat_writer.rs"]
mod mat_writer;
use mat_writer::write_mat;

fuzz_target!(|data: &[u8]| {
    if let Ok(file) = parse_mat(data) {
        let again = parse_mat(&write_mat(&file)).expect("re-encoded file parses");
        let numeric = file
            .variables
            .iter()
            .filter(|v| v.class.is_numeric())
            .count();
        assert_eq!(again.variables.len(), numeric);
    }
    let _ = parse_scene(
        data,
        "fuzz",
        Path::new("fuzz.mat"),
        LoadOptions { images: true },
    );
});
