//! Object placement in f64: `TransformDesc` → affine map, and repeat grids.
//!
//! parent_from_local = T · Rz · Ry · Rx · S (scale first, rotations about x,
//! then y, then z, translation last); composition is right to left (pbrt).

use glam::{DAffine3, DMat3, DVec3};

use super::desc::{RepeatDesc, TransformDesc};

/// The affine map parent_from_local of a transform description.
pub fn parent_from_local(t: &TransformDesc) -> DAffine3 {
    let [rx, ry, rz] = t.rotate_deg.unwrap_or([0.0; 3]).map(f64::to_radians);
    let rotation =
        DMat3::from_rotation_z(rz) * DMat3::from_rotation_y(ry) * DMat3::from_rotation_x(rx);
    let scale = DVec3::from(t.scale.map_or([1.0; 3], |s| s.axes()));
    DAffine3 {
        matrix3: rotation * DMat3::from_diagonal(scale),
        translation: DVec3::from(t.translate.unwrap_or([0.0; 3])),
    }
}

/// Every offset of a nested repeat grid (parent frame), first copy at zero.
/// An empty grid yields the single offset zero.
pub fn repeat_offsets(repeat: &[RepeatDesc]) -> Vec<DVec3> {
    let mut offsets = vec![DVec3::ZERO];
    for level in repeat {
        let step = DVec3::from(level.offset);
        offsets = offsets
            .iter()
            .flat_map(|&o| (0..level.count).map(move |i| o + step * i as f64))
            .collect();
    }
    offsets
}

/// Number of copies a repeat grid makes (saturating).
pub fn repeat_count(repeat: &[RepeatDesc]) -> u64 {
    repeat
        .iter()
        .fold(1u64, |n, level| n.saturating_mul(level.count as u64))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::desc::ScaleDesc;

    #[test]
    fn rotation_order_is_x_then_y_then_z() {
        let t = TransformDesc {
            translate: Some([1.0, 2.0, 3.0]),
            rotate_deg: Some([90.0, 90.0, 0.0]),
            scale: Some(ScaleDesc::Uniform(2.0)),
        };
        // +y → (Rx 90°) +z → (Ry 90°) +x, scaled by 2, then translated.
        let p = parent_from_local(&t).transform_point3(DVec3::Y);
        assert!((p - DVec3::new(3.0, 2.0, 3.0)).length() < 1e-12, "{p}");
    }

    #[test]
    fn repeat_grid_multiplies_counts() {
        let grid = [
            RepeatDesc {
                count: 3,
                offset: [1.0, 0.0, 0.0],
            },
            RepeatDesc {
                count: 2,
                offset: [0.0, 5.0, 0.0],
            },
        ];
        let offsets = repeat_offsets(&grid);
        assert_eq!(offsets.len(), 6);
        assert_eq!(repeat_count(&grid), 6);
        assert!(offsets.contains(&DVec3::new(2.0, 5.0, 0.0)));
    }
}
