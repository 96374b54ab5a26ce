//! Numbers in messages about descriptions, printed compactly (`1e308`, not
//! 309 digits): the description checks and scene validation share it.

/// A number for a message: plain when moderate, exponent form when huge or tiny.
pub fn num(x: f64) -> String {
    if x.is_finite() && x != 0.0 && !(1e-4..1e7).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

#[cfg(test)]
mod tests {
    use super::num;

    #[test]
    fn numbers_print_compactly() {
        assert_eq!(num(f64::MAX), "1.7976931348623157e308");
        assert_eq!(num(1e308), "1e308");
        assert_eq!(num(-2.5e-9), "-2.5e-9");
        assert_eq!(num(1.5), "1.5");
        assert_eq!(num(-90.0), "-90");
        assert_eq!(num(0.0), "0");
    }
}
