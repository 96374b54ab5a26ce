//! Semantic classes: CARLA's 29-class table (the ids CARLA 0.9.14 and later
//! write in its semantic segmentation camera, `carla.CityObjectLabel`), each
//! with CARLA's palette colour and its Cityscapes train id, declared once.
//! The `semantic` ground-truth image stores these ids; 0 = unlabeled.

/// One semantic class.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Class {
    /// The name scene files use (`semantic = "road"`), snake_case.
    pub name: &'static str,
    /// The id written in the semantic image (CARLA's id).
    pub id: u8,
    /// CARLA's palette colour (the colour of its converted semantic images).
    pub colour: [u8; 3],
    /// The Cityscapes train id (0–18) the class is evaluated as, or
    /// [`CITYSCAPES_IGNORE`] for classes Cityscapes does not train on.
    pub cityscapes_train_id: u8,
}

/// Cityscapes' train id of classes left out of training and evaluation.
pub const CITYSCAPES_IGNORE: u8 = 255;

const fn class(name: &'static str, id: u8, colour: [u8; 3], cityscapes_train_id: u8) -> Class {
    Class {
        name,
        id,
        colour,
        cityscapes_train_id,
    }
}

const IGNORE: u8 = CITYSCAPES_IGNORE;

/// Every class, in id order (the index is the id).
pub const CLASSES: [Class; 29] = [
    class("unlabeled", 0, [0, 0, 0], IGNORE),
    class("road", 1, [128, 64, 128], 0),
    class("sidewalk", 2, [244, 35, 232], 1),
    class("building", 3, [70, 70, 70], 2),
    class("wall", 4, [102, 102, 156], 3),
    class("fence", 5, [190, 153, 153], 4),
    class("pole", 6, [153, 153, 153], 5),
    class("traffic_light", 7, [250, 170, 30], 6),
    class("traffic_sign", 8, [220, 220, 0], 7),
    class("vegetation", 9, [107, 142, 35], 8),
    class("terrain", 10, [152, 251, 152], 9),
    class("sky", 11, [70, 130, 180], 10),
    class("pedestrian", 12, [220, 20, 60], 11),
    class("rider", 13, [255, 0, 0], 12),
    class("car", 14, [0, 0, 142], 13),
    class("truck", 15, [0, 0, 70], 14),
    class("bus", 16, [0, 60, 100], 15),
    class("train", 17, [0, 80, 100], 16),
    class("motorcycle", 18, [0, 0, 230], 17),
    class("bicycle", 19, [119, 11, 32], 18),
    class("static", 20, [110, 190, 160], IGNORE),
    class("dynamic", 21, [170, 120, 50], IGNORE),
    class("other", 22, [55, 90, 80], IGNORE),
    class("water", 23, [45, 60, 150], IGNORE),
    // Cityscapes counts lane markings as road.
    class("road_line", 24, [157, 234, 50], 0),
    class("ground", 25, [81, 0, 81], IGNORE),
    class("bridge", 26, [150, 100, 100], IGNORE),
    class("rail_track", 27, [230, 150, 140], IGNORE),
    class("guard_rail", 28, [180, 165, 180], IGNORE),
];

/// Id of pixels that see no surface.
pub const SKY: u8 = 11;
/// Id of the road surface.
pub const ROAD: u8 = 1;
/// Id of markings painted on the road.
pub const ROAD_LINE: u8 = 24;
/// Id of sidewalks and kerbs.
pub const SIDEWALK: u8 = 2;
/// Id of grass, soil and gravel.
pub const TERRAIN: u8 = 10;
/// Id of objects (and pixels) without a class.
pub const UNLABELED: u8 = 0;

/// The id of a class name, `None` if the name is not a class.
pub fn class_id(name: &str) -> Option<u8> {
    CLASSES.iter().find(|c| c.name == name).map(|c| c.id)
}

/// The class of an id, `None` above the last class.
pub fn class_of(id: u8) -> Option<&'static Class> {
    CLASSES.get(id as usize)
}

/// The name of a class id, `None` above the last class.
pub fn class_name(id: u8) -> Option<&'static str> {
    class_of(id).map(|c| c.name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_are_dense_and_round_trip() {
        for (i, c) in CLASSES.iter().enumerate() {
            assert_eq!(c.id as usize, i);
            assert_eq!(class_id(c.name), Some(c.id));
            assert_eq!(class_name(c.id), Some(c.name));
        }
        assert_eq!(class_id("vehicle"), None);
        assert_eq!(class_name(29), None);
    }

    #[test]
    fn named_ids_are_carlas() {
        // carla.CityObjectLabel (0.9.14+): Roads 1, SideWalks 2, Terrain 10,
        // Sky 11, RoadLine 24, GuardRail 28.
        for (id, name) in [
            (UNLABELED, "unlabeled"),
            (ROAD, "road"),
            (SIDEWALK, "sidewalk"),
            (TERRAIN, "terrain"),
            (SKY, "sky"),
            (ROAD_LINE, "road_line"),
        ] {
            assert_eq!(class_name(id), Some(name));
        }
        assert_eq!(class_id("guard_rail"), Some(28));
        assert_eq!(class_id("car"), Some(14));
    }

    #[test]
    fn cityscapes_train_ids_cover_its_nineteen_classes_once_besides_road_lines() {
        let mut seen = [0u32; 19];
        for c in &CLASSES {
            if c.cityscapes_train_id != CITYSCAPES_IGNORE {
                seen[c.cityscapes_train_id as usize] += 1;
            }
        }
        // Road (0) takes road and road_line; every other train id one class.
        assert_eq!(seen[0], 2);
        assert!(seen[1..].iter().all(|&n| n == 1), "{seen:?}");
    }
}
