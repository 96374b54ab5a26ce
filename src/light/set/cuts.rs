//! The light tree's cuts per cell of space (`bvh/cut.rs`): a vertex's
//! local light is chosen from the cut of the cell holding it, for its
//! normal's nearest axis when the normal lies near one. A cell's cut
//! depends on the tree and the cell's key only, so each thread keeps its
//! own cache of them (no locks), and which thread made a cut, or whether
//! it was made again after being evicted, changes no bit of a render.

use std::cell::RefCell;
use std::sync::atomic::{AtomicU64, Ordering};

use glam::Vec3;

use crate::light::bvh::{Cut, LightBvh, Region};

/// Edge of a cell, metres: the lamps of a street lie metres apart, and
/// within a cell this size a lamp's weight changes little against its
/// neighbours'.
const CELL_M: f32 = 2.0;
/// Size level of the cells of vertices after a path's first (8 m).
const DEEP_LEVEL: u8 = 2;
/// Nodes per cut: deep enough that a walk from the cut goes down a few
/// levels, not the tree's dozen.
const CUT_SIZE: usize = 64;
/// Least |cos| between a normal and its nearest axis for the axis's cut;
/// other normals take the cut for any normal (walls, roads and roofs lie
/// along the axes).
const AXIS_COS: f32 = 0.97;
/// Cuts each thread keeps (a power of two; a cell's slot is its key's hash).
const SLOTS: usize = 1 << 13;

/// A cell and which receivers: its integer coordinates, normal bin
/// (0–5: ±x, ±y, ±z; 6: any normal) and size (`CELL_M` × 2^level).
type Key = ([i32; 3], u8, u8);

/// A number for each light set, so a thread's cache serves one at a time.
static NEXT_SET: AtomicU64 = AtomicU64::new(1);

/// A new light set's number for [`with_cut`].
pub(super) fn next_set() -> u64 {
    NEXT_SET.fetch_add(1, Ordering::Relaxed)
}

/// One thread's cuts, of light set `set`: per slot the key of the cut
/// it holds (None: none yet).
#[derive(Default)]
struct Cache {
    set: u64,
    slots: Vec<(Option<Key>, Cut)>,
}

thread_local! {
    static CACHE: RefCell<Cache> = RefCell::new(Cache::default());
}

/// Calls `f` with the cut of light set `set`'s tree `bvh` for the cell of
/// point `p` and receiver normal `n` (zero: none) at a vertex after
/// `bounce` scattering events.
pub(super) fn with_cut<R>(
    (set, bvh): (u64, &LightBvh),
    (p, n): (Vec3, Vec3),
    bounce: u32,
    f: impl FnOnce(&Cut) -> R,
) -> R {
    let key = key_of(p, n, level_at(bounce));
    CACHE.with(|cache| {
        let mut cache = cache.borrow_mut();
        if cache.set != set || cache.slots.is_empty() {
            cache.set = set;
            cache.slots.clear();
            cache.slots.resize_with(SLOTS, Default::default);
        }
        let (k, cut) = &mut cache.slots[slot_of(key)];
        if *k != Some(key) {
            bvh.cut_into(&region_of(key), CUT_SIZE, cut);
            *k = Some(key);
        }
        f(cut)
    })
}

/// The cells' size level at a vertex after `bounce` scattering events:
/// the first vertex's light is seen directly, a later one's through a
/// bounce (and the indirect filter), which a coarser cut serves as well
/// while later vertices, spread over the whole town, touch far fewer
/// cells.
fn level_at(bounce: u32) -> u8 {
    if bounce == 0 {
        0
    } else {
        DEEP_LEVEL
    }
}

/// The cell of size level `level` and normal bin of a receiver at `p`
/// with normal `n`.
fn key_of(p: Vec3, n: Vec3, level: u8) -> Key {
    let size = CELL_M * (1u32 << level) as f32;
    let cell = (p / size).floor().to_array().map(|c| c as i32);
    let axis = n.abs().max_position();
    let bin = if n[axis].abs() >= AXIS_COS {
        2 * axis as u8 + (n[axis] < 0.0) as u8
    } else {
        6
    };
    (cell, bin, level)
}

/// The receivers a key stands for: its cell's bounding ball, and for an
/// axis bin the axis with how far a normal of the bin may lie from it.
fn region_of((cell, bin, level): Key) -> Region {
    let size = CELL_M * (1u32 << level) as f32;
    let centre = (Vec3::from_array(cell.map(|c| c as f32)) + 0.5) * size;
    let facing = (bin < 6).then(|| {
        let mut axis = Vec3::ZERO;
        axis[bin as usize / 2] = if bin % 2 == 0 { 1.0 } else { -1.0 };
        // |n − axis|² = 2 − 2 n·axis for unit vectors; a little more for
        // the rounding of normals and of this bound.
        (axis, (2.0 - 2.0 * AXIS_COS).sqrt() * 1.01 + 1e-4)
    });
    Region {
        centre,
        radius: 0.5 * 3f32.sqrt() * size * 1.001,
        facing,
    }
}

/// The cache slot of `key`.
fn slot_of(([x, y, z], bin, level): Key) -> usize {
    let mut h = (x as u32 as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    h = (h ^ y as u32 as u64).wrapping_mul(0xc2b2_ae3d_27d4_eb4f);
    h = (h ^ z as u32 as u64).wrapping_mul(0x1656_67b1_9e37_79f9);
    h = (h ^ (bin as u64 | (level as u64) << 8)).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    (h >> 40) as usize & (SLOTS - 1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampler::rng::Rng;

    #[test]
    fn a_keys_region_holds_its_cell_and_the_normals_of_its_bin() {
        let mut rng = Rng::new(&[0x5eed_0043]);
        let mut u = move || rng.f32();
        let mut binned = [0u32; 7];
        for k in 0..200_000 {
            let p = Vec3::new(u() - 0.5, u() - 0.5, u() - 0.5) * 300.0;
            let wobble = Vec3::new(u() - 0.5, u() - 0.5, u() - 0.5) * [0.0, 0.3, 0.6][k % 3];
            let axis = [Vec3::X, -Vec3::Y, Vec3::Z, -Vec3::Z][k % 4];
            let n = match k % 5 {
                0 => Vec3::ZERO,
                _ => (axis + wobble).normalize(),
            };
            let key = key_of(p, n, (k % 3) as u8);
            binned[key.1 as usize] += 1;
            let r = region_of(key);
            assert!((p - r.centre).length() <= r.radius, "{p} outside {r:?}");
            if let Some((axis, spread)) = r.facing {
                assert!((n - axis).length() <= spread, "{n} outside {r:?}");
            } else {
                assert!(n == Vec3::ZERO || n.abs().max_element() < AXIS_COS);
            }
        }
        // Normals on and near the axes take the axes' bins; the rest, and
        // no normal, the bin of any normal.
        for (bin, count) in binned.iter().enumerate() {
            let used = [0, 3, 4, 5, 6].contains(&bin);
            assert_eq!(*count > 0, used, "bin {bin}: {count}");
        }
    }
}
