//! The multi-start weight sets of the robust focal solver (docs/method.md step
//! 4): a preset name or an explicit list, read and written by serde as
//! `"adelaidermf"`, `"hopef"` or a list of `[w_f1, w_pp1, w_f2, w_pp2]`.

use focal::FocalWeights;

/// A named list of multi-start weight sets for the robust focal solver.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "kebab-case")
)]
pub enum WeightPreset {
    /// The reference code's four AdelaideRMF sets.
    Adelaidermf,
    /// The reference code's six HOPE-F sets.
    Hopef,
}

/// Multi-start weight sets `(w_f1, w_pp1, w_f2, w_pp2)` of the robust focal
/// solver (docs/method.md step 4): a preset name or an explicit list. Serialised
/// as `"adelaidermf"`, `"hopef"` or a list of `[w_f1, w_pp1, w_f2, w_pp2]`.
#[derive(Debug, Clone, PartialEq)]
pub enum WeightSets {
    /// One of the reference code's lists.
    Preset(WeightPreset),
    /// An explicit list of `[w_f1, w_pp1, w_f2, w_pp2]`.
    Explicit(Vec<[f64; 4]>),
}

impl WeightSets {
    /// The weight sets: [`focal::ADELAIDE_WEIGHT_SETS`],
    /// [`focal::HOPEF_WEIGHT_SETS`] or the explicit list.
    pub fn sets(&self) -> Vec<FocalWeights> {
        match self {
            WeightSets::Preset(WeightPreset::Adelaidermf) => focal::ADELAIDE_WEIGHT_SETS.to_vec(),
            WeightSets::Preset(WeightPreset::Hopef) => focal::HOPEF_WEIGHT_SETS.to_vec(),
            WeightSets::Explicit(sets) => sets
                .iter()
                .map(|&[f1, pp1, f2, pp2]| FocalWeights::new(f1, pp1, f2, pp2))
                .collect(),
        }
    }

    /// The weights as plain numbers, for hashing and comparing parameter sets.
    pub(crate) fn key(&self) -> Vec<[u64; 4]> {
        self.sets()
            .iter()
            .map(|w| [w.f1, w.pp1, w.f2, w.pp2].map(f64::to_bits))
            .collect()
    }
}

#[cfg(feature = "serde")]
mod weight_sets_serde {
    use super::{WeightPreset, WeightSets};
    use serde::de::{self, Deserializer, SeqAccess, Visitor};
    use serde::{Deserialize, Serialize, Serializer};
    use std::fmt;

    impl Serialize for WeightSets {
        fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
            match self {
                WeightSets::Preset(preset) => preset.serialize(serializer),
                WeightSets::Explicit(sets) => sets.serialize(serializer),
            }
        }
    }

    struct WeightSetsVisitor;

    impl<'de> Visitor<'de> for WeightSetsVisitor {
        type Value = WeightSets;
        fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
            f.write_str(
                "`adelaidermf`, `hopef` or a list of [w_f1, w_pp1, w_f2, w_pp2] weight sets",
            )
        }
        fn visit_str<E: de::Error>(self, v: &str) -> Result<WeightSets, E> {
            match v {
                "adelaidermf" => Ok(WeightSets::Preset(WeightPreset::Adelaidermf)),
                "hopef" => Ok(WeightSets::Preset(WeightPreset::Hopef)),
                other => Err(E::invalid_value(de::Unexpected::Str(other), &self)),
            }
        }
        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<WeightSets, A::Error> {
            let mut sets = Vec::new();
            while let Some(set) = seq.next_element::<[f64; 4]>()? {
                sets.push(set);
            }
            Ok(WeightSets::Explicit(sets))
        }
    }

    impl<'de> Deserialize<'de> for WeightSets {
        fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
            deserializer.deserialize_any(WeightSetsVisitor)
        }
    }
}
