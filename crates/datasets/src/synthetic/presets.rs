//! The named generator configurations (`sctl synth --preset`, the
//! `preset` of a config's synthetic dataset) and their scene lists.

use super::{
    generate_driving_random_scene, generate_driving_scene, generate_hopef_scene,
    generate_objects3d_scene, BackgroundParams, DrivingParams, DrivingRandomParams,
    Objects3dParams, SyntheticParams, SyntheticScene,
};
use crate::hopef_synth::{self, HopefParams};
use crate::DatasetError;
use serde::Serialize;

/// Named generator configurations.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Preset {
    /// `hopef-like`: HOPE-F's structure, categories 1–4 objects × 100 test
    /// scenes (folders 0900–0999), default parameters: 400 scenes.
    HopefLike,
    /// `quick`: 4 small scenes (categories 1 and 2, folders 0900–0901, 30–50
    /// points per object), for tests and a first run in seconds.
    Quick,
    /// `kitti-like`: static background under ego-motion plus 1–2 movers
    /// (categories 1 and 2, folders 0900–0909): 20 scenes.
    KittiLike,
    /// `hopef`: HOPE-F's own process ([`crate::hopef_synth`]), categories
    /// 1–4 × folders 0000–0999 (train 0000–0799, validation 0800–0899, test
    /// 0900–0999): 4000 scenes.
    Hopef,
    /// `kitti-real`: driving scenes of real size ([`generate_driving_scene`]):
    /// 1242 × 375 px, f ≈ 730 px, a background under forward ego-motion with
    /// 60–75 % of the matches, 1–2 cars (categories 1 and 2) that turn 4–15°
    /// and move sideways, each separable from the background and from the
    /// other car, 10–15 % outliers, 0.7 px noise, N = 1000, 2000, 3000, 5000
    /// by index mod 4; folders 0000–0999 split as HOPE-F's (train 0000–0799,
    /// validation 0800–0899, test 0900–0999): 2000 scenes.
    KittiReal,
    /// `adelaide-like`: HOPE-F's process ([`crate::hopef_synth`]) with the
    /// descriptive statistics of AdelaideRMF's 19 F scenes (N 165–360,
    /// 27–73 % outliers, mean 43 %, 35–146 inliers per motion, 640 × 480
    /// px): a 640 × 480 image, 25–75 % mismatches asked for (47 % outliers on
    /// average, 22–68 %), a match rate of 0.6 (which leaves enough unmatched
    /// keypoints for that share), texture 200–800 features per unit² and at
    /// least 35 matches per object ([`Preset::adelaide_like_params`]).
    /// Categories 1–4 × folders 0000–0999 split as HOPE-F's: 4000 scenes.
    AdelaideLike,
    /// `driving-random`: `kitti-real`'s driving scenes with every difficulty
    /// drawn per scene ([`generate_driving_random_scene`]): N 200–20 000
    /// (log-uniform), 0–3 movers of 2–30 % of N each, each at a median
    /// Sampson distance of 0.5–20 px (log-uniform) from the background's F,
    /// 0–30 % outliers, σ 0.3–1.5 px. One category folder, 0 (the number of
    /// motions is drawn), folders 0000–0999 split as HOPE-F's: 1000 scenes.
    DrivingRandom,
    /// `objects-3d`: 1–5 general 3-D objects (points on ellipsoids, relief
    /// planes, boxes) turning 5–40° about arbitrary axes before a moving
    /// camera, a static background in half the scenes, N 100–3000
    /// (log-uniform), 0–40 % outliers, objects down to 15 matches, focal
    /// 0.6–2.5 × max(W, H), W 400–1600, H 300–1200, every pair of motions
    /// distinct ([`generate_objects3d_scene`]). One category folder, 0,
    /// folders 0000–0999 split as HOPE-F's: 1000 scenes.
    Objects3d,
}

/// The parameters of a preset's generator.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum PresetParams {
    /// The generator of this module ([`generate_hopef_scene`]).
    Synthetic(SyntheticParams),
    /// The HOPE-F-faithful generator ([`hopef_synth::generate_scene`]).
    Hopef(HopefParams),
    /// The driving-scene generator ([`generate_driving_scene`]).
    Driving(DrivingParams),
    /// The `driving-random` generator ([`generate_driving_random_scene`]).
    DrivingRandom(DrivingRandomParams),
    /// The `objects-3d` generator ([`generate_objects3d_scene`]).
    Objects3d(Objects3dParams),
}

impl PresetParams {
    /// Checks the parameters (see [`SyntheticParams::validate`] and
    /// [`HopefParams::validate`]).
    pub fn validate(&self) -> Result<(), DatasetError> {
        match self {
            PresetParams::Synthetic(p) => p.validate(),
            PresetParams::Hopef(p) => p.validate(),
            PresetParams::Driving(p) => p.validate(),
            PresetParams::DrivingRandom(p) => p.validate(),
            PresetParams::Objects3d(p) => p.validate(),
        }
    }

    /// Generates scene `<category>/<index>` of a dataset made with `seed`.
    pub fn generate_scene(
        &self,
        seed: u64,
        category: u32,
        index: u32,
    ) -> Result<SyntheticScene, DatasetError> {
        match self {
            PresetParams::Synthetic(p) => generate_hopef_scene(p, seed, category, index),
            PresetParams::Hopef(p) => hopef_synth::generate_scene(p, seed, category, index),
            PresetParams::Driving(p) => generate_driving_scene(p, seed, category, index),
            PresetParams::DrivingRandom(p) => {
                generate_driving_random_scene(p, seed, category, index)
            }
            PresetParams::Objects3d(p) => generate_objects3d_scene(p, seed, category, index),
        }
    }

    /// The parameters of this module's generator, if they are those.
    pub fn as_synthetic(&self) -> Option<&SyntheticParams> {
        match self {
            PresetParams::Synthetic(p) => Some(p),
            _ => None,
        }
    }
}

impl Preset {
    /// All presets.
    pub const ALL: [Preset; 8] = [
        Preset::HopefLike,
        Preset::Quick,
        Preset::KittiLike,
        Preset::Hopef,
        Preset::KittiReal,
        Preset::AdelaideLike,
        Preset::DrivingRandom,
        Preset::Objects3d,
    ];

    /// The preset's name (`hopef-like`, `quick`, `kitti-like`, `hopef`,
    /// `kitti-real`, `adelaide-like`, `driving-random`, `objects-3d`).
    pub fn name(self) -> &'static str {
        match self {
            Preset::HopefLike => "hopef-like",
            Preset::Quick => "quick",
            Preset::KittiLike => "kitti-like",
            Preset::Hopef => "hopef",
            Preset::KittiReal => "kitti-real",
            Preset::AdelaideLike => "adelaide-like",
            Preset::DrivingRandom => "driving-random",
            Preset::Objects3d => "objects-3d",
        }
    }

    /// The preset called `name`.
    ///
    /// ```
    /// use datasets::synthetic::Preset;
    /// assert_eq!(Preset::from_name("quick"), Some(Preset::Quick));
    /// assert_eq!(Preset::from_name("nope"), None);
    /// ```
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|p| p.name() == name)
    }

    /// The generator parameters.
    pub fn params(self) -> PresetParams {
        PresetParams::Synthetic(match self {
            Preset::HopefLike => SyntheticParams::default(),
            Preset::Quick => SyntheticParams {
                points_per_object: [30, 50],
                min_points_per_object: 20,
                ..SyntheticParams::default()
            },
            Preset::KittiLike => SyntheticParams {
                background: BackgroundParams {
                    enabled: true,
                    ..BackgroundParams::default()
                },
                ..SyntheticParams::default()
            },
            Preset::Hopef => return PresetParams::Hopef(HopefParams::default()),
            Preset::KittiReal => return PresetParams::Driving(DrivingParams::default()),
            Preset::AdelaideLike => return PresetParams::Hopef(Self::adelaide_like_params()),
            Preset::DrivingRandom => {
                return PresetParams::DrivingRandom(DrivingRandomParams::default())
            }
            Preset::Objects3d => return PresetParams::Objects3d(Objects3dParams::default()),
        })
    }

    /// The `adelaide-like` preset's parameters: the `hopef` preset's with
    /// five fields set from AdelaideRMF's descriptive statistics (its image
    /// size, outlier shares and inliers per motion; nothing measured of a
    /// method on it).
    ///
    /// ```
    /// use datasets::synthetic::Preset;
    /// let p = Preset::adelaide_like_params();
    /// assert_eq!(p.image_size, [640, 480]);
    /// assert_eq!(p.min_inliers_per_object, 35);
    /// ```
    pub fn adelaide_like_params() -> HopefParams {
        HopefParams {
            image_size: [640, 480],
            mismatch_share: [0.25, 0.75],
            match_rate: 0.6,
            texture_density: [200.0, 800.0],
            min_inliers_per_object: 35,
            ..HopefParams::default()
        }
    }

    /// Reads a table of this preset's generator parameters (e.g. its own,
    /// serialised, with a user's overrides merged in).
    ///
    /// ```
    /// use datasets::synthetic::{Preset, PresetParams};
    /// let table: toml::Value = toml::from_str("mismatch_share = [0.2, 0.3]").unwrap();
    /// let PresetParams::Hopef(p) = Preset::Hopef.params_from_toml(table).unwrap() else {
    ///     panic!("hopef parameters expected");
    /// };
    /// assert_eq!(p.mismatch_share, [0.2, 0.3]);
    /// ```
    pub fn params_from_toml(self, table: toml::Value) -> Result<PresetParams, toml::de::Error> {
        match self.params() {
            PresetParams::Synthetic(_) => table.try_into().map(PresetParams::Synthetic),
            PresetParams::Hopef(_) => table.try_into().map(PresetParams::Hopef),
            PresetParams::Driving(_) => table.try_into().map(PresetParams::Driving),
            PresetParams::DrivingRandom(_) => table.try_into().map(PresetParams::DrivingRandom),
            PresetParams::Objects3d(_) => table.try_into().map(PresetParams::Objects3d),
        }
    }

    /// The category folders (numbers of moving objects).
    pub fn categories(self) -> Vec<u32> {
        match self {
            Preset::HopefLike | Preset::Hopef | Preset::AdelaideLike => vec![1, 2, 3, 4],
            Preset::Quick | Preset::KittiLike | Preset::KittiReal => vec![1, 2],
            Preset::DrivingRandom | Preset::Objects3d => vec![0],
        }
    }

    /// The scene folder indices of each category.
    pub fn indices(self) -> std::ops::RangeInclusive<u32> {
        match self {
            Preset::HopefLike => 900..=999,
            Preset::Quick => 900..=901,
            Preset::KittiLike => 900..=909,
            Preset::Hopef
            | Preset::KittiReal
            | Preset::AdelaideLike
            | Preset::DrivingRandom
            | Preset::Objects3d => 0..=999,
        }
    }

    /// Number of scenes the preset generates.
    pub fn len(self) -> usize {
        self.categories().len() * self.indices().count()
    }

    /// Always false: every preset has scenes.
    pub fn is_empty(self) -> bool {
        self.len() == 0
    }

    /// Generates all scenes of the preset from `seed` with `params`
    /// (normally [`Preset::params`]), calling `progress(done, total)` after
    /// each scene.
    pub fn generate_with(
        self,
        params: &PresetParams,
        seed: u64,
        mut progress: impl FnMut(usize, usize),
    ) -> Result<Vec<SyntheticScene>, DatasetError> {
        let total = self.len();
        let mut out = Vec::with_capacity(total);
        for category in self.categories() {
            for index in self.indices() {
                out.push(params.generate_scene(seed, category, index)?);
                progress(out.len(), total);
            }
        }
        Ok(out)
    }

    /// Generates all scenes of the preset from `seed` with its own parameters.
    ///
    /// ```
    /// use datasets::synthetic::Preset;
    /// let scenes = Preset::Quick.generate(7)?;
    /// let names: Vec<&str> = scenes.iter().map(|s| s.scene.name.as_str()).collect();
    /// assert_eq!(names, ["1/0900", "1/0901", "2/0900", "2/0901"]);
    /// # Ok::<(), datasets::DatasetError>(())
    /// ```
    pub fn generate(self, seed: u64) -> Result<Vec<SyntheticScene>, DatasetError> {
        self.generate_with(&self.params(), seed, |_, _| {})
    }
}
