//! Range checks of MTL values, line by line, before tobj reads them: tobj
//! accepts `nan`, `inf` and out-of-range numbers (and panics on a short
//! `Kd`), which would surface much later as NaN samples or silent clamps.
//!
//! Rules: `Kd`, `Ks` and `Tf` are r g b in [0, 1] (`Tf` may be one number);
//! `Ke` and the unused `Ka` are r g b, each finite and ≥ 0; `Ni` (index of
//! refraction, below 1 for a denser outside medium) is finite and > 0; `d`,
//! `Pr` and `Pm` are in [0, 1]; `Ns` is finite and ≥ 0.

/// One checked key: how many numbers it takes and their allowed range.
struct Rule {
    key: &'static str,
    /// Accepted counts of numbers.
    counts: &'static [usize],
    lo: f64,
    hi: f64,
    /// Whether `lo` itself is excluded.
    lo_open: bool,
}

const fn rule(key: &'static str, counts: &'static [usize], lo: f64, hi: f64) -> Rule {
    Rule {
        key,
        counts,
        lo,
        hi,
        lo_open: false,
    }
}

const RULES: [Rule; 10] = [
    rule("Kd", &[3], 0.0, 1.0),
    rule("Ks", &[3], 0.0, 1.0),
    rule("Ka", &[3], 0.0, f64::INFINITY),
    rule("Tf", &[1, 3], 0.0, 1.0),
    rule("Ke", &[3], 0.0, f64::INFINITY),
    Rule {
        lo_open: true,
        ..rule("Ni", &[1], 0.0, f64::INFINITY)
    },
    rule("d", &[1], 0.0, 1.0),
    rule("Pr", &[1], 0.0, 1.0),
    rule("Pm", &[1], 0.0, 1.0),
    rule("Ns", &[1], 0.0, f64::INFINITY),
];

impl Rule {
    /// What is allowed, for messages.
    fn allowed(&self) -> String {
        let range = match (self.hi.is_finite(), self.lo_open) {
            (true, _) => format!("in [{}, {}]", self.lo, self.hi),
            (false, true) => format!("> {} and finite", self.lo),
            (false, false) => format!("≥ {} and finite", self.lo),
        };
        match self.counts {
            [1] => format!("a number {range}"),
            [3] => format!("3 numbers (r g b), each {range}"),
            _ => format!("1 or 3 numbers, each {range}"),
        }
    }

    fn check(&self, words: &[&str]) -> Result<(), String> {
        let allowed = self.allowed();
        if !self.counts.contains(&words.len()) {
            return Err(format!(
                "\"{}\" has {} values; allowed: {allowed}",
                words.join(" "),
                words.len()
            ));
        }
        for w in words {
            let x: f64 = w
                .parse()
                .map_err(|_| format!("\"{w}\" is not a number; allowed: {allowed}"))?;
            let above_lo = if self.lo_open {
                x > self.lo
            } else {
                x >= self.lo
            };
            if !(x.is_finite() && above_lo && x <= self.hi) {
                return Err(format!("{w} is out of range; allowed: {allowed}"));
            }
        }
        Ok(())
    }
}

/// Checks MTL text; an error reads "line N: KEY: what is wrong; allowed: …".
pub fn check_mtl(text: &str) -> Result<(), String> {
    for (i, line) in text.lines().enumerate() {
        let words: Vec<&str> = line.split_whitespace().collect();
        let Some((key, values)) = words.split_first() else {
            continue;
        };
        if let Some(rule) = RULES.iter().find(|r| r.key == *key) {
            rule.check(values)
                .map_err(|m| format!("line {}: {key}: {m}", i + 1))?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn good_values_pass() {
        let mtl = "newmtl a\nKd 0.5 0.5 0.5\nKs 1 1 1\nKe 20 0 3\nNi 1.45\nd 1\nNs 900\nTf 0.9\nTf 1 0.5 0\n";
        check_mtl(mtl).unwrap();
    }

    #[test]
    fn bad_values_name_line_key_value_and_rule() {
        for (line, says) in [
            (
                "Kd nan 0.5 0.5",
                "line 2: Kd: nan is out of range; allowed: 3 numbers (r g b), each in [0, 1]",
            ),
            ("Kd 0.5", "line 2: Kd: \"0.5\" has 1 values"),
            ("Ks 1.5 0 0", "line 2: Ks: 1.5 is out of range"),
            (
                "Ke -1 0 0",
                "line 2: Ke: -1 is out of range; allowed: 3 numbers (r g b), each ≥ 0 and finite",
            ),
            ("Ke inf 0 0", "Ke: inf is out of range"),
            (
                "Ni nan",
                "line 2: Ni: nan is out of range; allowed: a number > 0 and finite",
            ),
            ("Ni 0", "Ni: 0 is out of range"),
            ("d 1.2", "line 2: d: 1.2 is out of range"),
            ("Ns -5", "line 2: Ns: -5 is out of range"),
            ("Ns x", "line 2: Ns: \"x\" is not a number"),
        ] {
            let e = check_mtl(&format!("newmtl a\n{line}\n")).unwrap_err();
            assert!(e.contains(says), "{line}: {e}");
        }
    }
}
