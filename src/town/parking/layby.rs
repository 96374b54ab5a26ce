//! Lay-by geometry: along each run of adjacent bays the sidewalk and its
//! kerb are cut back (the road's kerb slab goes, the walk slab keeps only
//! its part behind the bay), a kerb of the bay's own stands between bay
//! and walk, and the bay's surface lies at road level (class `road`) with
//! white lines between the bays (class `road_line`).

use crate::scene::desc::{ObjectDesc, ShapeDesc};

use super::super::layout::Rect;
use super::super::parts::{class, ground_quad, slab};
use super::{Bay, KERB_M};

/// Height of a kerb top (as the road kerbs), metres.
const KERB_TOP_M: f64 = 0.15;
/// Bay lines: width and paint height, metres (as the road markings).
const LINE_W_M: f64 = 0.1;
const PAINT_Z: (f64, f64) = (0.0, 0.008);

/// Adjacent bays on one side of one road merged: one stretch of kerb.
pub fn runs(bays: &[Bay]) -> Vec<Bay> {
    let mut out: Vec<Bay> = Vec::new();
    for b in bays {
        match out.last_mut() {
            Some(r)
                if r.axis == b.axis
                    && r.road == b.road
                    && r.side == b.side
                    && (r.along.1 - b.along.0).abs() < 1e-9 =>
            {
                r.along.1 = b.along.1;
            }
            _ => out.push(*b),
        }
    }
    out
}

/// Cuts the lay-bys of `bays` into the road objects `objects` (curb and
/// sidewalk slabs), then adds each run's kerb, surface and bay lines.
pub fn cut_laybys(objects: &mut Vec<ObjectDesc>, bays: &[Bay]) {
    for r in runs(bays) {
        let mut kept = Vec::with_capacity(objects.len() + 4);
        for o in objects.drain(..) {
            match pieces(&o, &r) {
                Some(p) => kept.extend(p),
                None => kept.push(o),
            }
        }
        *objects = kept;
        objects.extend(layby_objects(&r));
    }
}

/// The run's own kerb, its surface and the lines between its bays.
fn layby_objects(r: &Bay) -> Vec<ObjectDesc> {
    let (hw, d) = (r.hw, r.depth);
    let mut out = Vec::new();
    let kerb = r.strip(r.along, (hw + d, hw + d + KERB_M));
    out.push(slab(
        kerb.min,
        kerb.max,
        0.0,
        KERB_TOP_M,
        "curb",
        class("sidewalk"),
    ));
    let floor = r.strip(r.along, (hw, hw + d));
    out.push(ground_quad(
        floor.min,
        floor.max,
        0.0,
        "asphalt",
        class("road"),
    ));
    let n = ((r.along.1 - r.along.0) / super::BAY_LEN_M).round() as usize;
    for k in 0..=n {
        let a = r.along.0 + k as f64 * super::BAY_LEN_M;
        // The end lines lie inside the run.
        let a = a.clamp(r.along.0 + LINE_W_M / 2.0, r.along.1 - LINE_W_M / 2.0);
        let line = r.strip((a - LINE_W_M / 2.0, a + LINE_W_M / 2.0), (hw + 0.2, hw + d));
        out.push(slab(
            line.min,
            line.max,
            PAINT_Z.0,
            PAINT_Z.1,
            "paint_white_road",
            class("road_line"),
        ));
    }
    out
}

/// An unturned box of the sidewalk class reaching into the run's bay zone
/// (the kerb and walk slabs beside it), split round the run: its parts
/// before and after the run, and beside it only what lies behind the
/// bay's kerb. `None` for every other object.
fn pieces(o: &ObjectDesc, r: &Bay) -> Option<Vec<ObjectDesc>> {
    let ShapeDesc::Box { size } = o.shape else {
        return None;
    };
    if o.semantic.as_deref() != Some("sidewalk") || o.transform.rotate_deg.is_some() {
        return None;
    }
    let t = o.transform.translate?;
    let f = Rect::centered([t[0], t[1]], [size[0], size[1]]);
    let zone = r.strip(r.along, (r.hw, r.hw + r.depth + KERB_M));
    if !zone.overlaps(&f) {
        return None;
    }
    // The box in (along, offset) terms.
    let (along, across) = match r.axis {
        super::Axis::X => ((f.min[0], f.max[0]), (f.min[1], f.max[1])),
        super::Axis::Y => ((f.min[1], f.max[1]), (f.min[0], f.max[0])),
    };
    let off = |w: f64| r.side * (w - r.c);
    let (u0, u1) = (
        off(across.0).min(off(across.1)),
        off(across.0).max(off(across.1)),
    );
    let behind = r.hw + r.depth + KERB_M;
    let mut out = Vec::new();
    let mut piece = |a: (f64, f64), u: (f64, f64)| {
        if a.1 - a.0 > 1e-6 && u.1 - u.0 > 1e-6 {
            let p = r.strip(a, u);
            let mut q = o.clone();
            let c = p.center();
            q.transform.translate = Some([c[0], c[1], t[2]]);
            let s = p.size();
            q.shape = ShapeDesc::Box {
                size: [s[0], s[1], size[2]],
            };
            out.push(q);
        }
    };
    piece((along.0, along.1.min(r.along.0)), (u0, u1));
    piece((along.0.max(r.along.1), along.1), (u0, u1));
    piece(
        (along.0.max(r.along.0), along.1.min(r.along.1)),
        (u0.max(behind), u1),
    );
    Some(out)
}
