//! The words printed on street furniture: street names from seeded word
//! lists (a fixed pool, so the prefabs are the same in every town; a town
//! picks its roads' names from the pool by seed), place names of direction
//! signs, billboard slogans and the speed limits signs may show.

use crate::town::rng::Rng;

/// Speed limits a sign may show, km/h (the set a town draws from).
pub const SPEED_LIMITS: [u32; 7] = [20, 30, 40, 50, 70, 90, 110];
/// Street names in the pool (one name-plate prefab each).
pub const STREET_NAME_COUNT: usize = 12;
/// Place names of direction signs (one prefab each).
pub const PLACES: [&str; 4] = ["CENTRE", "HARBOUR", "STATION", "AIRPORT"];
/// Billboard slogans (one prefab each).
pub const SLOGANS: [&str; 3] = ["DRIVE SAFE", "FRESH BREAD", "CITY BANK"];

const FIRST: [&str; 16] = [
    "OAK", "MILL", "KING", "ELM", "BROOK", "HIGH", "ASH", "CHURCH", "PARK", "STATION", "NORTH",
    "MARKET", "BRIDGE", "WILLOW", "QUEEN", "CEDAR",
];
const KIND: [&str; 6] = ["ST", "RD", "AVE", "LN", "WAY", "DR"];
/// Seed of the name pool (a constant: names are content, not randomness
/// of a frame).
const NAME_SEED: u64 = 0x5354_5245_4554;

/// The pool of street names, distinct, drawn from the word lists.
pub fn street_names() -> Vec<String> {
    let mut r = Rng::new(&[NAME_SEED]);
    let mut out: Vec<String> = Vec::new();
    while out.len() < STREET_NAME_COUNT {
        let name = format!(
            "{} {}",
            FIRST[r.index(FIRST.len())],
            KIND[r.index(KIND.len())]
        );
        if !out.contains(&name) {
            out.push(name);
        }
    }
    out
}

/// The speed limit of a sign in a town driving at `speed_kmh`: the
/// largest limit not above the town's speed, or one step lower with
/// probability 1/4 (school and residential zones), from `r`.
pub fn speed_limit(speed_kmh: f64, r: &mut Rng) -> u32 {
    let k = SPEED_LIMITS
        .iter()
        .rposition(|&s| s as f64 <= speed_kmh + 1e-9)
        .unwrap_or(0);
    let k = if k > 0 && r.chance(0.25) { k - 1 } else { k };
    SPEED_LIMITS[k]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_distinct_printable_and_fixed() {
        let names = street_names();
        assert_eq!(names.len(), STREET_NAME_COUNT);
        assert_eq!(names, street_names());
        for (i, n) in names.iter().enumerate() {
            assert!(!names[i + 1..].contains(n), "{n} twice");
            assert!(n.chars().all(|c| c.is_ascii_uppercase() || c == ' '), "{n}");
        }
    }

    #[test]
    fn speed_limits_follow_the_town_speed_from_the_set() {
        let mut r = Rng::new(&[1]);
        let draws: Vec<u32> = (0..200).map(|_| speed_limit(40.0, &mut r)).collect();
        assert!(draws.iter().all(|s| [30, 40].contains(s)), "{draws:?}");
        let low = draws.iter().filter(|&&s| s == 30).count();
        assert!((25..=75).contains(&low), "{low} of 200 one step lower");
        assert!((0..50).all(|_| speed_limit(100.0, &mut r) >= 70));
        assert_eq!(speed_limit(5.0, &mut r), 20);
    }
}
