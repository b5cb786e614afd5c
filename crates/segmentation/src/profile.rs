//! Named parameter sets ([`Profile`]): the starting point that a user's
//! own keys then override.

use crate::{MinimalSolver, Params};

/// A named set of [`Params`].
///
/// * `default`: [`Params::default`], the most accurate configuration
///   measured (five-point hypotheses at the focal prior, no focal filter,
///   Table 1 values);
/// * `thesis`: [`Params::thesis`], the thesis text's semi-calibrated
///   Algorithm 1;
/// * `fast`: [`Params::fast`], M 1000 and one IRLS iteration: four to
///   five times cheaper than `default` (results/README.md, "A fast
///   profile").
///
/// ```
/// use segmentation::{Params, Profile};
/// assert_eq!(Profile::from_name("fast"), Some(Profile::Fast));
/// assert_eq!(Profile::Fast.params(), Params::fast());
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
    /// [`Params::fast`].
    Fast,
}

impl Profile {
    /// Every profile.
    pub const ALL: [Profile; 3] = [Profile::Default, Profile::Thesis, Profile::Fast];

    /// The profile's parameters.
    pub fn params(self) -> Params {
        match self {
            Profile::Default => Params::default(),
            Profile::Thesis => Params::thesis(),
            Profile::Fast => Params::fast(),
        }
    }

    /// The profile's name (`default`, `thesis`, `fast`).
    pub fn name(self) -> &'static str {
        match self {
            Profile::Default => "default",
            Profile::Thesis => "thesis",
            Profile::Fast => "fast",
        }
    }

    /// The profile called `name`.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|p| p.name() == name)
    }
}

impl Params {
    /// The `fast` profile: the default pipeline with M 1000 instead of 3000
    /// and one IRLS-Tukey iteration instead of five, chosen on the
    /// synthetic validation splits among M ∈ {500, 750, 1000, 3000}, 1–5
    /// IRLS iterations, uniform or localized sampling and adaptive M
    /// (results/README.md, "A fast profile").
    pub fn fast() -> Self {
        Self {
            minimal_solver: MinimalSolver::FivePoint,
            num_samples: 1000,
            irls_iters: 1,
            ..Self::default()
        }
    }
}
