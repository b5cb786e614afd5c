//! No panic on any input: the `.mat` and `.npz` parsers and the loaders
//! behind them, fed random bytes and mutated real files (bit flips,
//! overwritten runs, truncation, insertion). Each case must return `Ok` or
//! `Err`; a panic fails the test.

mod common;

use common::mat_writer::write_mat;
use datasets::adelaidermf::{parse_scene, LoadOptions};
use datasets::hopef::{parse_camera, parse_features, CAMERA_FILE, FEATURES_FILE};
use datasets::mat::parse_mat;
use datasets::npz::parse_npy;
use proptest::prelude::*;
use std::path::Path;
use std::sync::OnceLock;

/// Seeds: a real AdelaideRMF file compressed (as shipped) and re-encoded
/// uncompressed (so that mutations reach the element structure instead of
/// the zlib stream), cropped to its `data` and `label` variables to keep
/// cases fast; and the HOPE-F fixture archives.
struct Seeds {
    mat_compressed: Vec<u8>,
    mat_plain: Vec<u8>,
    features: Vec<u8>,
    camera: Vec<u8>,
    npy: Vec<u8>,
}

fn seeds() -> &'static Seeds {
    static SEEDS: OnceLock<Seeds> = OnceLock::new();
    SEEDS.get_or_init(|| {
        let mat_compressed =
            std::fs::read(common::adelaidermf_dir().join("boardgame.mat")).unwrap();
        let mut parsed = parse_mat(&mat_compressed).unwrap();
        // Small images keep each case cheap: 4 x 5 grayscale.
        for v in &mut parsed.variables {
            if v.name.starts_with("img") {
                v.dims = vec![4, 5];
                v.values = datasets::mat::MatValues::UInt8((0..20).collect());
            }
        }
        let mat_plain = write_mat(&parsed);
        let scene = common::hopef_fixture("good").join("2/0001");
        let features = std::fs::read(scene.join(FEATURES_FILE)).unwrap();
        let camera = std::fs::read(scene.join(CAMERA_FILE)).unwrap();
        let k =
            datasets::npz::NpyArray::from_f64(vec![3, 3], (0..9).map(f64::from).collect()).unwrap();
        let npy = datasets::npz::encode_npy(&k);
        Seeds {
            mat_compressed,
            mat_plain,
            features,
            camera,
            npy,
        }
    })
}

#[derive(Debug, Clone)]
enum Mutation {
    Flip { at: usize, bit: u8 },
    Overwrite { at: usize, bytes: Vec<u8> },
    Truncate { len: usize },
    Insert { at: usize, bytes: Vec<u8> },
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        4 => (any::<usize>(), 0u8..8).prop_map(|(at, bit)| Mutation::Flip { at, bit }),
        3 => (any::<usize>(), prop::collection::vec(any::<u8>(), 1..9)).prop_map(|(at, bytes)| Mutation::Overwrite { at, bytes }),
        1 => any::<usize>().prop_map(|len| Mutation::Truncate { len }),
        1 => (any::<usize>(), prop::collection::vec(any::<u8>(), 1..9)).prop_map(|(at, bytes)| Mutation::Insert { at, bytes }),
    ]
}

/// Applies mutations; positions are taken modulo the current length and
/// biased to the first 4 kB, where headers and tags live.
fn mutate(seed: &[u8], mutations: &[Mutation]) -> Vec<u8> {
    let mut out = seed.to_vec();
    for m in mutations {
        let len = out.len().max(1);
        let pos = |at: usize| {
            if at % 2 == 0 {
                (at / 2) % len.min(4096)
            } else {
                (at / 2) % len
            }
        };
        match m {
            Mutation::Flip { at, bit } => {
                if !out.is_empty() {
                    let p = pos(*at);
                    out[p] ^= 1 << bit;
                }
            }
            Mutation::Overwrite { at, bytes } => {
                let p = pos(*at);
                for (i, b) in bytes.iter().enumerate() {
                    if let Some(slot) = out.get_mut(p + i) {
                        *slot = *b;
                    }
                }
            }
            Mutation::Truncate { len: l } => out.truncate(l % len),
            Mutation::Insert { at, bytes } => {
                let p = pos(*at).min(out.len());
                out.splice(p..p, bytes.iter().copied());
            }
        }
    }
    out
}

fn load_mat(bytes: &[u8]) {
    let _ = parse_scene(bytes, "case", Path::new("case.mat"), LoadOptions::default());
}

fn load_npz(bytes: &[u8]) {
    let _ = parse_features(bytes, Path::new(FEATURES_FILE));
    let _ = parse_camera(bytes, Path::new(CAMERA_FILE));
}

#[test]
fn seeds_are_valid() {
    let s = seeds();
    assert!(parse_scene(
        &s.mat_compressed,
        "boardgame",
        Path::new("b.mat"),
        LoadOptions::default()
    )
    .is_ok());
    assert!(parse_scene(
        &s.mat_plain,
        "boardgame",
        Path::new("b.mat"),
        LoadOptions::default()
    )
    .is_ok());
    assert!(parse_features(&s.features, Path::new("f.npz")).is_ok());
    assert!(parse_camera(&s.camera, Path::new("c.npz")).is_ok());
    assert!(parse_npy(&s.npy).is_ok());
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..600)) {
        load_mat(&bytes);
        load_npz(&bytes);
        let _ = parse_npy(&bytes);
        // With valid magic numbers the parsers get past the first check.
        let mut mat = vec![b' '; 128];
        mat[126..].copy_from_slice(b"IM");
        mat.extend_from_slice(&bytes);
        load_mat(&mat);
        let mut npy = b"\x93NUMPY\x01\x00".to_vec();
        npy.extend_from_slice(&bytes);
        let _ = parse_npy(&npy);
    }

    #[test]
    fn mutated_uncompressed_mat_never_panics(ms in prop::collection::vec(mutation(), 1..6)) {
        load_mat(&mutate(&seeds().mat_plain, &ms));
    }

    #[test]
    fn mutated_npz_never_panics(ms in prop::collection::vec(mutation(), 1..6)) {
        load_npz(&mutate(&seeds().features, &ms));
        load_npz(&mutate(&seeds().camera, &ms));
    }

    #[test]
    fn mutated_npy_never_panics(ms in prop::collection::vec(mutation(), 1..4)) {
        let _ = parse_npy(&mutate(&seeds().npy, &ms));
    }
}

proptest! {
    // Each case inflates a 370 kB file: fewer cases.
    #![proptest_config(ProptestConfig { cases: 40, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn mutated_compressed_mat_never_panics(ms in prop::collection::vec(mutation(), 1..4)) {
        load_mat(&mutate(&seeds().mat_compressed, &ms));
    }
}
