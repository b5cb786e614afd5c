//! The order of a run's rows: every (combination, scene) unit by number,
//! whatever order the rows were written in.

use crate::output::CsvTable;
use crate::sweep::SweepPlan;
use anyhow::{bail, Context, Result};
use std::collections::{HashMap, HashSet};
use std::path::Path;

/// Unit order: `(combination, scene)` of each row's key, for sorting.
pub(super) struct UnitIndex<'a> {
    plan: &'a SweepPlan,
    scenes: HashMap<&'a str, usize>,
}

impl<'a> UnitIndex<'a> {
    pub(super) fn new(plan: &'a SweepPlan, scenes: &'a [String]) -> Self {
        Self {
            plan,
            scenes: scenes
                .iter()
                .enumerate()
                .map(|(i, s)| (s.as_str(), i))
                .collect(),
        }
    }

    /// The plan the units are numbered by.
    pub(super) fn plan(&self) -> &'a SweepPlan {
        self.plan
    }

    pub(super) fn of(&self, row: &[String], file: &Path, line: usize) -> Result<(usize, usize)> {
        let k = self.plan.columns.len();
        if row.len() <= k {
            bail!("{}: row {line}: too few columns", file.display());
        }
        let combo = self.plan.find(&row[..k]).with_context(|| {
            format!(
                "{}: row {line}: parameters ({}) are not a combination of this run",
                file.display(),
                row[..k].join(", ")
            )
        })?;
        let scene = *self.scenes.get(row[k].as_str()).with_context(|| {
            format!(
                "{}: row {line}: scene `{}` is not part of this run",
                file.display(),
                row[k]
            )
        })?;
        Ok((combo, scene))
    }
}

/// Rewrites a run's CSV rows in unit order (one row per unit, the first one
/// seen) and drops timing rows of units without a result.
pub(super) fn sort_rows(
    table: &mut CsvTable,
    index: &UnitIndex,
    file: &Path,
    keep: Option<&HashSet<(usize, usize)>>,
) -> Result<HashSet<(usize, usize)>> {
    let mut keyed: Vec<((usize, usize), Vec<String>)> = Vec::with_capacity(table.rows.len());
    let mut seen = HashSet::new();
    for (r, row) in table.rows.drain(..).enumerate() {
        let key = index.of(&row, file, r + 2)?;
        if keep.is_some_and(|k| !k.contains(&key)) || !seen.insert(key) {
            continue;
        }
        keyed.push((key, row));
    }
    keyed.sort_by_key(|(key, _)| *key);
    table.rows = keyed.into_iter().map(|(_, row)| row).collect();
    Ok(seen)
}
