//! Arbitrary bytes into the `.npy` / `.npz` readers and the HOPE-F archive
//! parsers: no panic, and whatever `.npy` parses re-encodes to the same
//! shape and values.
#![no_main]

use datasets::hopef::{parse_camera, parse_features, CAMERA_FILE, FEATURES_FILE};
use datasets::npz::{encode_npy, parse_npy, NpyData};
use libfuzzer_sys::fuzz_target;
use std::path::Path;

/// Value equality that treats NaNs with the same bits as equal.
fn same(a: &NpyData, b: &NpyData) -> bool {
    match (a, b) {
        (NpyData::Float(x), NpyData::Float(y)) => x
            .iter()
            .map(|v| v.to_bits())
            .eq(y.iter().map(|v| v.to_bits())),
        (NpyData::Int(x), NpyData::Int(y)) => x == y,
        _ => false,
    }
}

fuzz_target!(|data: &[u8]| {
    let _ = parse_features(data, Path::new(FEATURES_FILE));
    let _ = parse_camera(data, Path::new(CAMERA_FILE));
    if let Ok(array) = parse_npy(data) {
        let again = parse_npy(&encode_npy(&array)).expect("re-encoded array parses");
        assert_eq!(again.shape, array.shape);
        assert!(same(&again.data, &array.data));
    }
});
