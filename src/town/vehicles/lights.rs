//! Head-lights at night: two spot lights per car (one per two-wheeler) at
//! its head-lamps, aimed along the vehicle and 3.5° down so the beam lights
//! the road ahead, placed from each vehicle instance's pose in the scene.
//! Added only for the dark weathers (`needs_headlights`): by day they
//! would only cost light samples.

use glam::DVec3;

use crate::scene::desc::{LightDesc, ObjectDesc, SceneDesc, ShapeDesc};
use crate::scene::transform::parent_from_local;

use super::{BodyKind, BODIES};

/// On-axis intensity of a car head-light, W·sr⁻¹ (about 17,000 cd: a low
/// beam; one scene unit of intensity is ~100 cd).
pub const CAR_BEAM: [f64; 3] = [170.0, 165.0, 150.0];
/// Full-intensity half-angle and cut-off of the beam, degrees.
pub const BEAM_INNER_DEG: f64 = 12.0;
/// Cut-off half-angle of the beam, degrees.
pub const BEAM_OUTER_DEG: f64 = 32.0;
/// Beam axis in the body frame: forward, 3.5° down.
const AIM: [f64; 3] = [1.0, 0.0, -0.061];

/// Whether a weather preset is dark enough for head-lights (night, dusk).
pub fn needs_headlights(preset: crate::weather::Weather) -> bool {
    matches!(
        preset,
        crate::weather::Weather::Night | crate::weather::Weather::Sunset
    )
}

/// The lamp points (body frame) and on-axis intensity of a body.
fn lamps_of(kind: BodyKind) -> (Vec<[f64; 3]>, [f64; 3]) {
    match kind {
        BodyKind::Motorcycle => (vec![super::two_wheel::MOTO_LAMP], CAR_BEAM.map(|c| c * 0.8)),
        BodyKind::Bicycle => (
            vec![super::two_wheel::BIKE_LAMP],
            CAR_BEAM.map(|c| c * 0.03),
        ),
        k => {
            let s = super::spec::spec_of(k).expect("a four-wheeled body");
            (super::lamps::headlamp_points(&s).to_vec(), CAR_BEAM)
        }
    }
}

/// The head-light spots of every moving vehicle instance among `objects`.
pub fn headlights(objects: &[ObjectDesc]) -> Vec<LightDesc> {
    let lamps: Vec<(BodyKind, Vec<[f64; 3]>, [f64; 3])> = BODIES
        .iter()
        .map(|&k| {
            let (p, i) = lamps_of(k);
            (k, p, i)
        })
        .collect();
    let mut out = Vec::new();
    for o in objects {
        let ShapeDesc::Instance { prefab, .. } = &o.shape else {
            continue;
        };
        let Some((_, points, intensity)) = lamps.iter().find(|(k, ..)| k.prefab() == prefab) else {
            continue;
        };
        // Parked cars (static ids, below the moving vehicles') stay dark.
        if o.instance
            .is_some_and(|i| u32::from(i) < crate::town::VEHICLE_ID_BASE)
        {
            continue;
        }
        let m = parent_from_local(&o.transform);
        let direction = (m.matrix3 * DVec3::from(AIM)).to_array();
        for &p in points {
            // Just ahead of the lens, so the lamp's own geometry never
            // shadows its beam.
            let q = m.transform_point3(DVec3::from(p) + DVec3::new(0.08, 0.0, 0.0));
            out.push(LightDesc::Spot {
                position: q.to_array(),
                direction,
                intensity: *intensity,
                inner_deg: BEAM_INNER_DEG,
                outer_deg: BEAM_OUTER_DEG,
            });
        }
    }
    out
}

/// Adds the head-lights of `desc`'s vehicles to its lights.
pub fn add_headlights(desc: &mut SceneDesc) {
    let spots = headlights(&desc.objects);
    desc.lights.extend(spots);
}
