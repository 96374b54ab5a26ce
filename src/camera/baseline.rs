//! A rig's baseline folders: each baseline is named by its whole centimetre
//! (`baseline_054`), so two baselines of one rig must differ there. This is a
//! rule of the rig, checked by scene validation, the CLI and the dataset
//! config alike; the output layouts name their folders with it.

use std::fmt;

/// Directory name of a baseline: the baseline in centimetres rounded to the
/// nearest integer, zero-padded to 3 digits: 54.0 → "baseline_054",
/// 300.0 → "baseline_300". Precondition: `baseline_cm` finite and ≥ 0.
pub fn baseline_dir_name(baseline_cm: f64) -> String {
    debug_assert!(baseline_cm.is_finite() && baseline_cm >= 0.0);
    // Snap to a millionth of a centimetre first: writers pass `metres * 100`,
    // configurations pass centimetres, and 14.5 / 100 * 100 is 14.4999…,
    // which would otherwise name another folder than 14.5 itself.
    let snapped = (baseline_cm * 1e6).round() / 1e6;
    format!("baseline_{:03}", snapped.round() as u64)
}

/// Two baselines of one rig whose folders coincide (same whole centimetre).
#[derive(Clone, Debug, PartialEq)]
pub struct SharedBaselineDir {
    /// Index of the later of the two in the list (the value to report).
    pub index: usize,
    /// The earlier baseline, centimetres.
    pub first_cm: f64,
    /// The later baseline, centimetres.
    pub second_cm: f64,
    /// The folder both would be written to (`baseline_XXX`).
    pub dir: String,
}

impl fmt::Display for SharedBaselineDir {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (a, b, dir) = (self.first_cm, self.second_cm, &self.dir);
        if a == b {
            write!(f, "baseline {a} cm is listed twice (both would be {dir})")
        } else {
            write!(
                f,
                "baselines {a} cm and {b} cm would share the folder {dir} (folders name \
                 the baseline in whole centimetres; give each its own centimetre)"
            )
        }
    }
}

/// Checks that every baseline gets its own `baseline_XXX` folder; the error
/// names the first pair that would share one. Render, dataset and the scene
/// and CLI checks all call this one rule. Precondition: values finite, ≥ 0.
pub fn check_baseline_dirs(baselines_cm: &[f64]) -> Result<(), SharedBaselineDir> {
    let dirs: Vec<String> = baselines_cm.iter().map(|&b| baseline_dir_name(b)).collect();
    for (j, dir) in dirs.iter().enumerate() {
        if let Some(i) = dirs[..j].iter().position(|d| d == dir) {
            return Err(SharedBaselineDir {
                index: j,
                first_cm: baselines_cm[i],
                second_cm: baselines_cm[j],
                dir: dir.clone(),
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn baseline_dir_rounds_to_whole_centimetres() {
        assert_eq!(baseline_dir_name(53.6), "baseline_054");
        assert_eq!(baseline_dir_name(0.54 * 100.0), "baseline_054");
        assert_eq!(baseline_dir_name(5.0), "baseline_005");
        assert_eq!(baseline_dir_name(1234.0), "baseline_1234");
    }

    #[test]
    fn baseline_dir_is_the_same_from_centimetres_and_from_metres() {
        // Writers name folders from `baseline_m * 100`, split lists and the
        // folder check from the configured centimetres: both must agree.
        for cm in [3.5, 14.5, 28.5, 54.5, 100.5, 0.5, 299.5] {
            assert_eq!(baseline_dir_name(cm / 100.0 * 100.0), baseline_dir_name(cm));
        }
        assert_eq!(baseline_dir_name(14.5 / 100.0 * 100.0), "baseline_015");
    }

    #[test]
    fn baselines_sharing_a_folder_are_named() {
        assert_eq!(
            check_baseline_dirs(&[10.0, 54.0, 100.0, 200.0, 300.0]),
            Ok(())
        );
        assert_eq!(check_baseline_dirs(&[54.0, 54.6]), Ok(()));
        let e = check_baseline_dirs(&[10.0, 53.6, 20.0, 54.4]).unwrap_err();
        assert_eq!((e.index, e.first_cm, e.second_cm), (3, 53.6, 54.4));
        assert_eq!(e.dir, "baseline_054");
        let msg = e.to_string();
        assert!(
            msg.contains("53.6 cm and 54.4 cm") && msg.contains("baseline_054"),
            "{msg}"
        );
        let e = check_baseline_dirs(&[54.0, 10.0, 54.0]).unwrap_err();
        assert_eq!(e.index, 2);
        assert!(e.to_string().contains("54 cm is listed twice"), "{e}");
    }
}
