//! Helpers shared by the integration tests (`mod support;` in each); every
//! test file uses a subset of them.
#![allow(dead_code)]

use assert_cmd::Command;
use datasets::synthetic::Preset;
use datasets::Scene;
use std::path::PathBuf;

/// The `sctl` binary of this build.
pub fn sctl() -> Command {
    Command::cargo_bin("sctl").unwrap()
}

/// `configs/quickstart.toml`.
pub fn quickstart() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../configs/quickstart.toml")
}

/// Scene `index` of `category` of the synthetic `quick` preset (generator seed 1).
pub fn quick_scene(category: u32, index: u32) -> Scene {
    Preset::Quick
        .params()
        .generate_scene(1, category, index)
        .unwrap()
        .scene
}
