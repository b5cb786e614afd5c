//! Named parameter sets ([`Profile`]): the starting point that a user's
//! own keys then override.

use crate::Params;

/// A named set of [`Params`].
///
/// * `default`: [`Params::default`], one configuration for 8 to 50 000
///   matches (five-point hypotheses at the focal prior, guided sampling,
///   at most 1000 matches clustered, motions chosen by their a-contrario
///   significance);
/// * `thesis`: [`Params::thesis`], the thesis text's semi-calibrated
///   Algorithm 1.
///
/// The `fast` and `large` profiles of earlier versions were folded into
/// the default (`RETIRED_PROFILES`); their names are refused with a
/// message that says so.
///
/// ```
/// use segmentation::{Params, Profile};
/// assert_eq!(Profile::from_name("thesis"), Some(Profile::Thesis));
/// assert_eq!(Profile::Default.params(), Params::default());
/// assert_eq!(Profile::from_name("fast"), None);
/// assert!(Profile::ALL.iter().all(|p| p.params().validate().is_ok()));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "kebab-case")
)]
pub enum Profile {
    /// [`Params::default`].
    #[default]
    Default,
    /// [`Params::thesis`].
    Thesis,
}

/// Profiles that existed before the one default, and what became of them.
pub const RETIRED_PROFILES: [(&str, &str); 2] = [
    (
        "fast",
        "folded into the default (results/README.md, \"One default\"), as cheap and more accurate; \
         its keys until then are pinned in configs/headline/headline_fast_*.toml",
    ),
    (
        "large",
        "folded into the default (results/README.md, \"One default\"), which clusters at most 1000 matches at any N; \
         its keys until then are pinned in configs/headline/headline_large_*.toml",
    ),
];

impl Profile {
    /// Every profile.
    pub const ALL: [Profile; 2] = [Profile::Default, Profile::Thesis];

    /// The profile's parameters.
    pub fn params(self) -> Params {
        match self {
            Profile::Default => Params::default(),
            Profile::Thesis => Params::thesis(),
        }
    }

    /// The profile's name (`default`, `thesis`).
    pub fn name(self) -> &'static str {
        match self {
            Profile::Default => "default",
            Profile::Thesis => "thesis",
        }
    }

    /// The profile called `name`.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|p| p.name() == name)
    }

    /// Why `name` is not a profile: what became of a retired one, else the
    /// profiles there are.
    ///
    /// ```
    /// let why = segmentation::Profile::unknown("fast");
    /// assert!(why.contains("folded into the default"), "{why}");
    /// assert!(segmentation::Profile::unknown("quick").contains("default, thesis"));
    /// ```
    pub fn unknown(name: &str) -> String {
        match RETIRED_PROFILES.iter().find(|(n, _)| *n == name) {
            Some((_, what)) => format!("profile `{name}` was {what}"),
            None => format!(
                "unknown profile `{name}`; expected one of: {}",
                Self::names()
            ),
        }
    }

    /// Every profile's name, comma-separated, for error messages.
    ///
    /// ```
    /// assert_eq!(segmentation::Profile::names(), "default, thesis");
    /// ```
    pub fn names() -> String {
        Self::ALL.map(Self::name).join(", ")
    }
}

impl Params {
    /// `self` changed by `edit`: a profile with a few keys of its own,
    /// e.g. `Params::thesis().with(|p| p.sampling.num_samples = 300)`.
    ///
    /// ```
    /// use segmentation::Params;
    /// let p = Params::thesis().with(|p| p.sampling.num_samples = 300);
    /// assert_eq!((p.sampling.num_samples, p.focal.method), (300, Params::thesis().focal.method));
    /// ```
    pub fn with(mut self, edit: impl FnOnce(&mut Self)) -> Self {
        edit(&mut self);
        self
    }
}
