//! Locating the shared datasets and fixtures. A missing directory fails the
//! test with where to get it; nothing is skipped silently.
#![allow(dead_code)]

pub mod mat_writer;

use datasets::{data_root_env, resolve_data_root, workspace_datasets_dir, DataRootSources};
use std::path::PathBuf;

/// `../shared` beside the workspace.
pub fn shared_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared")
}

/// The AdelaideRMF `F` directory: under the resolved data root
/// (`SCTL_DATA_ROOT` or `datasets/`), else `../shared/datasets/adelaidermf/F`.
pub fn adelaidermf_dir() -> PathBuf {
    let sources = DataRootSources {
        env: data_root_env(),
        ..DataRootSources::default()
    };
    let root = resolve_data_root(&sources, &workspace_datasets_dir());
    let candidates = [
        root.adelaidermf_dir(),
        shared_dir().join("datasets/adelaidermf/F"),
    ];
    candidates
        .iter()
        .find(|p| p.join("biscuit.mat").is_file())
        .cloned()
        .unwrap_or_else(|| {
            panic!(
                "AdelaideRMF not found at {:?}: {}",
                candidates,
                datasets::DATASET_HINT
            )
        })
}

/// `../shared/fixtures/hopef-layout/<sub>`.
pub fn hopef_fixture(sub: &str) -> PathBuf {
    let dir = shared_dir().join("fixtures/hopef-layout").join(sub);
    assert!(
        dir.is_dir(),
        "HOPE-F layout fixtures not found at {}: they ship in ../shared beside the workspace \
         (see datasets/README.md)",
        dir.display()
    );
    dir
}
