//! The ranges of [`Params`] that the types cannot express.

use super::stages::{Sampling, SizeRule};
use super::Params;
use thiserror::Error;

/// A parameter out of its range: the key ([`super::KEYS`]) and why.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("invalid parameter `{key}`: {message}")]
pub struct ParamError {
    /// The key.
    pub key: &'static str,
    /// What is wrong.
    pub message: String,
}

impl ParamError {
    fn new(key: &'static str, message: impl Into<String>) -> Self {
        Self {
            key,
            message: message.into(),
        }
    }
}

/// `Ok` for a finite `v > 0`, else the error of `key`.
fn positive(key: &'static str, v: f64) -> Result<(), ParamError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(ParamError::new(
            key,
            format!("must be a finite number > 0, got {v}"),
        ))
    }
}

impl Params {
    /// Checks the ranges the types cannot: the first offending key and why.
    pub fn validate(&self) -> Result<(), ParamError> {
        self.validate_sampling()?;
        let (refinement, focal) = (&self.refinement, &self.focal);
        positive("thr_px", refinement.thr_px)?;
        positive("tau_diff", focal.tau_diff)?;
        positive("tau_range", focal.tau_range)?;
        if refinement.refine && refinement.irls_iters == 0 {
            return Err(ParamError::new(
                "irls_iters",
                "must be at least 1 when refine = true",
            ));
        }
        let offset = self.reference_code.irls_sigma_offset_px;
        if !(offset.is_finite() && offset >= 0.0) {
            return Err(ParamError::new(
                "irls_sigma_offset_px",
                format!("must be a finite number >= 0, got {offset}"),
            ));
        }
        if focal.max_iters == 0 {
            return Err(ParamError::new("max_iters", "must be at least 1"));
        }
        if let SizeRule::RelativeMin(f) = self.clustering.size_rule {
            if !(0.0..=1.0).contains(&f) {
                return Err(ParamError::new(
                    "size_rule",
                    format!("relative-min must be a fraction in [0, 1], got {f}"),
                ));
            }
        }
        self.validate_weight_sets()
    }

    fn validate_sampling(&self) -> Result<(), ParamError> {
        let s = &self.sampling;
        if s.num_samples == 0 {
            return Err(ParamError::new("num_samples", "must be at least 1"));
        }
        if s.sampling == Sampling::Guided && s.guided_batch == 0 {
            return Err(ParamError::new("guided_batch", "must be at least 1"));
        }
        if s.mss_size < 8 {
            return Err(ParamError::new(
                "mss_size",
                format!(
                    "must be at least 8 (the 8-point algorithm; the five-point draws its \
                     own sample size and still refines on 8 or more), got {}",
                    s.mss_size
                ),
            ));
        }
        if s.cluster_subset != 0 && s.cluster_subset < s.mss_size {
            return Err(ParamError::new(
                "cluster_subset",
                format!(
                    "must be 0 (all matches) or at least mss_size = {}, got {}",
                    s.mss_size, s.cluster_subset
                ),
            ));
        }
        Ok(())
    }

    fn validate_weight_sets(&self) -> Result<(), ParamError> {
        let sets = self.focal.weight_sets.sets();
        if sets.is_empty() {
            return Err(ParamError::new(
                "weight_sets",
                "must hold at least one weight set",
            ));
        }
        for (i, set) in sets.iter().enumerate() {
            let w = [set.f1, set.pp1, set.f2, set.pp2];
            if w.iter().any(|w| !(w.is_finite() && *w > 0.0)) {
                return Err(ParamError::new(
                    "weight_sets",
                    format!("set {i} {w:?}: every weight must be a finite number > 0"),
                ));
            }
        }
        Ok(())
    }
}
