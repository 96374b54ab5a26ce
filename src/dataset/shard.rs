//! Sharding: `--shard i/N` (1-based) takes every job whose position in the
//! plan is ≡ i−1 (mod N), so shards are disjoint, cover the plan and mix
//! towns and weathers evenly. The index may instead come from a batch
//! engine: Slurm arrays (`SLURM_ARRAY_TASK_ID`, `SLURM_ARRAY_TASK_COUNT`,
//! with `SLURM_ARRAY_TASK_MIN` as the first id) or Kubernetes Indexed Jobs
//! (`JOB_COMPLETION_INDEX`, 0-based, with the count from `PARALLAX_SHARD_COUNT`).

use std::fmt;

/// One shard of a job list: `index` in 1..=count.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// 1-based shard index.
    pub index: u32,
    /// Number of shards, ≥ 1.
    pub count: u32,
}

impl Shard {
    /// The whole job list.
    pub const ALL: Shard = Shard { index: 1, count: 1 };

    /// Parses `i/N` with 1 ≤ i ≤ N.
    pub fn parse(s: &str) -> Result<Shard, String> {
        let bad = || format!("--shard '{s}': expected i/N with 1 ≤ i ≤ N (1-based), e.g. 2/8");
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let index: u32 = i.trim().parse().map_err(|_| bad())?;
        let count: u32 = n.trim().parse().map_err(|_| bad())?;
        if count == 0 || index == 0 || index > count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }

    /// The shard a batch engine hands over through `env`, if any: Slurm array
    /// variables first, then a Kubernetes Indexed Job's index.
    pub fn from_env(env: &dyn Fn(&str) -> Option<String>) -> Result<Option<Shard>, String> {
        let num = |name: &str| -> Result<Option<u32>, String> {
            match env(name) {
                None => Ok(None),
                Some(v) => v
                    .trim()
                    .parse()
                    .map(Some)
                    .map_err(|_| format!("{name}='{v}' is not a whole number")),
            }
        };
        if let Some(id) = num("SLURM_ARRAY_TASK_ID")? {
            let count = num("SLURM_ARRAY_TASK_COUNT")?
                .ok_or("SLURM_ARRAY_TASK_ID is set but SLURM_ARRAY_TASK_COUNT is not")?;
            let min = num("SLURM_ARRAY_TASK_MIN")?.unwrap_or(1);
            let index = id
                .checked_sub(min)
                .map(|k| k.saturating_add(1))
                .ok_or("SLURM_ARRAY_TASK_ID is below SLURM_ARRAY_TASK_MIN")?;
            return Shard::from_variables(
                index,
                count,
                &format!("SLURM_ARRAY_TASK_ID={id} (SLURM_ARRAY_TASK_MIN={min}, SLURM_ARRAY_TASK_COUNT={count})"),
            )
            .map(Some);
        }
        if let Some(k) = num("JOB_COMPLETION_INDEX")? {
            let count = num("PARALLAX_SHARD_COUNT")?.ok_or(
                "JOB_COMPLETION_INDEX is set: give the shard count as PARALLAX_SHARD_COUNT \
                 (the Job's spec.completions) or pass --shard",
            )?;
            return Shard::from_variables(
                k.saturating_add(1),
                count,
                &format!("JOB_COMPLETION_INDEX={k} (PARALLAX_SHARD_COUNT={count})"),
            )
            .map(Some);
        }
        Ok(None)
    }

    /// Shard `index` of `count` (1-based) taken from the batch engine's
    /// variables, shown as `vars` when out of range: the user set those, not
    /// `--shard`.
    fn from_variables(index: u32, count: u32, vars: &str) -> Result<Shard, String> {
        if count == 0 || index == 0 || index > count {
            return Err(format!(
                "{vars}: the task's shard would be {index} of {count}; \
                 a shard index must lie in 1..={count} of a count of at least 1"
            ));
        }
        Ok(Shard { index, count })
    }

    /// True when the job at plan position `position` belongs to this shard.
    pub fn owns(&self, position: usize) -> bool {
        position as u64 % self.count as u64 == (self.index - 1) as u64
    }

    /// The shard's manifest file name: `shard-i-of-N.jsonl`.
    pub fn manifest_name(&self) -> String {
        format!("shard-{}-of-{}.jsonl", self.index, self.count)
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn env_of<'a>(pairs: &'a [(&'a str, &'a str)]) -> impl Fn(&str) -> Option<String> + 'a {
        move |k| {
            pairs
                .iter()
                .find(|(n, _)| *n == k)
                .map(|(_, v)| v.to_string())
        }
    }

    #[test]
    fn parse_accepts_1_based_and_rejects_out_of_range() {
        assert_eq!(Shard::parse("2/3"), Ok(Shard { index: 2, count: 3 }));
        for bad in ["0/3", "4/3", "1/0", "3", "a/b", "-1/2"] {
            assert!(Shard::parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn shards_partition_the_plan() {
        let n = 3;
        for pos in 0..100 {
            let owners = (1..=n)
                .filter(|&i| Shard { index: i, count: n }.owns(pos))
                .count();
            assert_eq!(owners, 1);
        }
    }

    #[test]
    fn slurm_and_kubernetes_indices_map_to_1_based_shards() {
        let slurm = env_of(&[
            ("SLURM_ARRAY_TASK_ID", "0"),
            ("SLURM_ARRAY_TASK_COUNT", "4"),
            ("SLURM_ARRAY_TASK_MIN", "0"),
        ]);
        assert_eq!(
            Shard::from_env(&slurm),
            Ok(Some(Shard { index: 1, count: 4 }))
        );
        let slurm1 = env_of(&[
            ("SLURM_ARRAY_TASK_ID", "4"),
            ("SLURM_ARRAY_TASK_COUNT", "4"),
        ]);
        assert_eq!(
            Shard::from_env(&slurm1),
            Ok(Some(Shard { index: 4, count: 4 }))
        );
        let k8s = env_of(&[("JOB_COMPLETION_INDEX", "2"), ("PARALLAX_SHARD_COUNT", "3")]);
        assert_eq!(
            Shard::from_env(&k8s),
            Ok(Some(Shard { index: 3, count: 3 }))
        );
        assert!(Shard::from_env(&env_of(&[("JOB_COMPLETION_INDEX", "2")])).is_err());
    }

    #[test]
    fn out_of_range_task_names_the_variables_not_the_flag() {
        let slurm = env_of(&[
            ("SLURM_ARRAY_TASK_ID", "3"),
            ("SLURM_ARRAY_TASK_COUNT", "2"),
        ]);
        let e = Shard::from_env(&slurm).unwrap_err();
        assert!(
            e.contains("SLURM_ARRAY_TASK_ID=3") && e.contains("3 of 2"),
            "{e}"
        );
        assert!(!e.contains("--shard"), "{e}");
        let k8s = env_of(&[
            ("JOB_COMPLETION_INDEX", "4294967295"),
            ("PARALLAX_SHARD_COUNT", "3"),
        ]);
        let e = Shard::from_env(&k8s).unwrap_err();
        assert!(e.contains("JOB_COMPLETION_INDEX=4294967295"), "{e}");
        assert_eq!(Shard::from_env(&env_of(&[])), Ok(None));
    }
}
