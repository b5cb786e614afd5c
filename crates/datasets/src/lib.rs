//! Scenes for two-view motion segmentation: the [`Scene`] type every stage of
//! the pipeline consumes (docs/method.md, "Input"), loaders for the datasets the
//! thesis evaluates (docs/method.md, "Datasets") and a synthetic generator.
//!
//! * [`adelaidermf`]: the 19 AdelaideRMF fundamental-matrix scenes (`.mat`).
//! * [`hopef`]: HOPE-F scene folders (`.npz`), with split and category
//!   selection.
//! * [`user`]: a user's CSV or `matches.txt` file with a sidecar TOML.
//! * [`synthetic`]: seeded HOPE-F-like scenes, the named presets and a
//!   writer of the HOPE-F layout.
//! * [`hopef_synth`]: scenes made by HOPE-F's own process (the `hopef`
//!   preset), with its labelling and acceptance rules.
//! * [`mat`], [`npz`]: the MATLAB v5 and NumPy readers behind the loaders,
//!   safe on arbitrary bytes.
//! * [`resolve_data_root`]: where datasets live (flag, `SCTL_DATA_ROOT`,
//!   config, `datasets/`).
//!
//! Every loader returns a validated scene ([`Scene::validate`]) or a
//! [`DatasetError`] naming the file, scene and field.
//!
//! ```
//! use datasets::synthetic::{generate_scene, SyntheticParams};
//! let scene = generate_scene(&SyntheticParams::default(), 1, 2, "two-objects")?;
//! assert_eq!(scene.num_motions(), 2);
//! assert!(scene.len() >= 8);
//! # Ok::<(), datasets::DatasetError>(())
//! ```

#![warn(missing_docs)]

pub mod adelaidermf;
pub mod data_root;
mod echo;
pub mod error;
pub mod hopef;
pub mod hopef_synth;
pub mod mat;
pub mod npz;
pub mod scene;
pub mod synthetic;
pub use echo::{echo, ECHO_MAX_CHARS};
pub mod user;

pub use data_root::{
    data_root_env, resolve_data_root, workspace_datasets_dir, DataRoot, DataRootSource,
    DataRootSources, DATA_ROOT_ENV,
};
pub use error::{DatasetError, DATASET_HINT};
pub use scene::{centre_principal_point, LoadOptions, Scene, MIN_POINTS, UNKNOWN_LABEL};
