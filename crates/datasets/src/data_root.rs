//! The data root: the directory that dataset paths are relative to.
//!
//! Resolution order: the `--data-root` flag, else the `SCTL_DATA_ROOT`
//! environment variable, else the config's `data_root`, else `datasets/` in
//! the workspace. Under it: `adelaidermf/F/*.mat`, `hopef/<k>/<NNNN>/…`,
//! `synthetic/…`.

use std::ffi::OsString;
use std::path::{Path, PathBuf};

/// Name of the environment variable that sets the data root.
pub const DATA_ROOT_ENV: &str = "SCTL_DATA_ROOT";

/// Where the resolved data root came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DataRootSource {
    /// The `--data-root` command-line flag.
    Flag,
    /// The `SCTL_DATA_ROOT` environment variable.
    Env,
    /// The `data_root` entry of a configuration file.
    Config,
    /// The default, `datasets/` in the workspace.
    Workspace,
}

/// The candidate data roots, highest priority first. Empty values count as
/// unset. A relative `config` path is taken as given (relative to the
/// current directory); a caller that wants it relative to the config file
/// joins it first.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct DataRootSources {
    /// Value of the `--data-root` flag.
    pub flag: Option<PathBuf>,
    /// Value of the `SCTL_DATA_ROOT` environment variable (see
    /// [`data_root_env`]).
    pub env: Option<OsString>,
    /// The config file's `data_root`.
    pub config: Option<PathBuf>,
}

/// A resolved data root and where it came from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DataRoot {
    /// The directory.
    pub path: PathBuf,
    /// Which source gave it.
    pub source: DataRootSource,
}

/// Reads `SCTL_DATA_ROOT` from the process environment: the only place this
/// crate looks at the environment. `None` when unset or empty.
pub fn data_root_env() -> Option<OsString> {
    std::env::var_os(DATA_ROOT_ENV).filter(|v| !v.is_empty())
}

/// `datasets/` at the top of the workspace this crate was built in.
pub fn workspace_datasets_dir() -> PathBuf {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    manifest
        .parent()
        .and_then(Path::parent)
        .unwrap_or(manifest)
        .join("datasets")
}

/// Resolves the data root from its sources: flag, else env, else config,
/// else `workspace_default`. A pure function of its arguments.
///
/// ```
/// use datasets::{resolve_data_root, DataRootSource, DataRootSources};
/// use std::path::{Path, PathBuf};
/// let default = Path::new("/ws/datasets");
/// let sources = DataRootSources {
///     flag: None,
///     env: Some("/from/env".into()),
///     config: Some(PathBuf::from("/from/config")),
/// };
/// let root = resolve_data_root(&sources, default);
/// assert_eq!(root.path, Path::new("/from/env"));
/// assert_eq!(root.source, DataRootSource::Env);
/// let root = resolve_data_root(&DataRootSources::default(), default);
/// assert_eq!((root.path.as_path(), root.source), (default, DataRootSource::Workspace));
/// ```
pub fn resolve_data_root(sources: &DataRootSources, workspace_default: &Path) -> DataRoot {
    let non_empty = |p: &Option<PathBuf>| p.as_ref().filter(|p| !p.as_os_str().is_empty()).cloned();
    if let Some(path) = non_empty(&sources.flag) {
        return DataRoot {
            path,
            source: DataRootSource::Flag,
        };
    }
    if let Some(env) = sources.env.as_ref().filter(|v| !v.is_empty()) {
        return DataRoot {
            path: PathBuf::from(env),
            source: DataRootSource::Env,
        };
    }
    if let Some(path) = non_empty(&sources.config) {
        return DataRoot {
            path,
            source: DataRootSource::Config,
        };
    }
    DataRoot {
        path: workspace_default.to_path_buf(),
        source: DataRootSource::Workspace,
    }
}

impl DataRoot {
    /// AdelaideRMF's fundamental-matrix scenes: `<root>/adelaidermf/F`.
    pub fn adelaidermf_dir(&self) -> PathBuf {
        self.path.join("adelaidermf").join("F")
    }

    /// HOPE-F: `<root>/hopef`.
    pub fn hopef_dir(&self) -> PathBuf {
        self.path.join("hopef")
    }

    /// Generated datasets: `<root>/synthetic`.
    pub fn synthetic_dir(&self) -> PathBuf {
        self.path.join("synthetic")
    }

    /// A config-relative dataset path: joined to the root unless absolute.
    pub fn join(&self, relative: impl AsRef<Path>) -> PathBuf {
        self.path.join(relative)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn priority_order() {
        let default = Path::new("/ws/datasets");
        let all = DataRootSources {
            flag: Some("/flag".into()),
            env: Some("/env".into()),
            config: Some("/config".into()),
        };
        assert_eq!(
            resolve_data_root(&all, default).source,
            DataRootSource::Flag
        );
        let no_flag = DataRootSources {
            flag: None,
            ..all.clone()
        };
        assert_eq!(resolve_data_root(&no_flag, default).path, Path::new("/env"));
        let config_only = DataRootSources {
            flag: None,
            env: None,
            ..all.clone()
        };
        assert_eq!(
            resolve_data_root(&config_only, default),
            DataRoot {
                path: "/config".into(),
                source: DataRootSource::Config
            }
        );
        // Empty values are ignored.
        let empty = DataRootSources {
            flag: Some(PathBuf::new()),
            env: Some(OsString::new()),
            config: None,
        };
        assert_eq!(
            resolve_data_root(&empty, default).source,
            DataRootSource::Workspace
        );
    }

    #[test]
    fn sub_directories() {
        let root = DataRoot {
            path: "/d".into(),
            source: DataRootSource::Flag,
        };
        assert_eq!(root.adelaidermf_dir(), Path::new("/d/adelaidermf/F"));
        assert_eq!(root.hopef_dir(), Path::new("/d/hopef"));
        assert_eq!(root.synthetic_dir(), Path::new("/d/synthetic"));
        assert_eq!(root.join("x/y"), Path::new("/d/x/y"));
        assert_eq!(root.join("/abs"), Path::new("/abs"));
    }

    #[test]
    fn workspace_default_is_the_repository_datasets_dir() {
        let dir = workspace_datasets_dir();
        assert!(dir.ends_with("datasets"));
        assert!(dir.parent().unwrap().join("Cargo.toml").is_file());
    }
}
