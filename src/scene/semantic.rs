//! Semantic classes: the fixed table of class names and their 8-bit ids
//! written in the `semantic` ground-truth image (0 = other, 13 = sky).

/// Every class name with its id, in id order.
pub const CLASSES: &[(&str, u8)] = &[
    ("other", 0),
    ("road", 1),
    ("lane_marking", 2),
    ("sidewalk", 3),
    ("building", 4),
    ("vegetation", 5),
    ("terrain", 6),
    ("pole", 7),
    ("traffic_light", 8),
    ("traffic_sign", 9),
    ("vehicle", 10),
    ("pedestrian", 11),
    ("water", 12),
    ("sky", 13),
];

/// The id of a class name, `None` if the name is not a class.
pub fn class_id(name: &str) -> Option<u8> {
    CLASSES.iter().find(|(n, _)| *n == name).map(|&(_, id)| id)
}

/// The name of a class id, `None` above the last class.
pub fn class_name(id: u8) -> Option<&'static str> {
    CLASSES.get(id as usize).map(|&(n, _)| n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_are_dense_and_round_trip() {
        for (i, &(name, id)) in CLASSES.iter().enumerate() {
            assert_eq!(id as usize, i);
            assert_eq!(class_id(name), Some(id));
            assert_eq!(class_name(id), Some(name));
        }
        assert_eq!(class_id("car"), None);
    }
}
