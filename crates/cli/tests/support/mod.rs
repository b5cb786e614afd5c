//! Helpers shared by the integration tests (`mod support;` in each); every
//! test file uses a subset of them.
#![allow(dead_code, unused_imports)]

mod fixtures;
mod png;
mod schema;

pub use fixtures::{load_fixture, number, shared_fixture, PoseLibFocals};
pub use png::{decode_chart, decode_png};
pub use schema::PER_SCENE_COLUMNS;

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

/// Asserts that `sctl` failed with nothing on stdout and one line on
/// stderr, `error: ` and a message containing every one of `needles`;
/// returns the message.
pub fn one_line_error(output: &std::process::Output, needles: &[&str]) -> String {
    assert!(!output.status.success(), "sctl succeeded");
    assert!(
        output.stdout.is_empty(),
        "stdout: {}",
        String::from_utf8_lossy(&output.stdout)
    );
    let stderr = String::from_utf8(output.stderr.clone()).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    let message = stderr
        .strip_prefix("error: ")
        .unwrap_or_else(|| panic!("{stderr} does not start with `error: `"))
        .trim_end()
        .to_string();
    for needle in needles {
        assert!(message.contains(needle), "{message} lacks {needle:?}");
    }
    message
}

/// Whether two fundamental matrices are equal up to scale and sign: the
/// largest entry difference of their unit-norm forms, sign aligned, is at
/// most `tolerance`.
pub fn same_up_to_scale(
    a: &nalgebra::Matrix3<f64>,
    b: &nalgebra::Matrix3<f64>,
    tolerance: f64,
) -> bool {
    let (a, b) = (a / a.norm(), b / b.norm());
    let sign = if a.dot(&b) < 0.0 { -1.0 } else { 1.0 };
    (a - b * sign).amax() <= tolerance
}
