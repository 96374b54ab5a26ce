//! The bay prefabs of a style: one floor-high slice of wall `bay_m` wide
//! with its opening, and what fills it — a window (frame, recessed glass,
//! sill, lintel) before a shallow room (walls, ceiling, a lamp panel,
//! curtains or blinds, a piece of furniture), a shopfront, a front door
//! with steps, a lobby or a roller door — plus the lamp overlay of a lit room.
//!
//! Bay frame: x along the wall (bay centred on x = 0), the wall plane at
//! y = 0 with the outside towards −y, the inside up to y = `SKIN_M`, z from
//! the bay's floor (0) to the floor above (`floor_m`). Bays tile a façade
//! edge to edge; the building's core starts at y = `SKIN_M`.

use glam::DVec3;

use crate::scene::desc::ObjectDesc;
use crate::scene::mesh::LocalMesh;
use crate::town::parts::{class, cuboid, repeated, turned_quad, Label};

use super::style::{Ground, Style};

/// Depth of the façade skin (wall, reveal, room) in front of the core.
pub const SKIN_M: f64 = 1.2;
/// Clearance of the room's floor above, and ceiling below, the floor
/// lines (the room above starts 2 cm higher: no shared planes).
const ROOM_FLOOR_M: f64 = 0.01;
/// Clearance of curtains and furniture from the bay's sides.
const LINING_M: f64 = 0.05;
/// Width of a window frame's bars.
const FRAME_M: f64 = 0.06;
/// Thickness of a glass pane.
const GLASS_M: f64 = 0.012;
/// Window variants per style (curtains, blinds, furniture).
pub const VARIANTS: u32 = 3;
/// Depth of a shopfront's glass behind the wall plane.
pub const SHOP_RECESS_M: f64 = 0.15;

/// A box between two corners of the bay frame.
pub fn boxed(lo: [f64; 3], hi: [f64; 3], mat: &str, l: Label) -> ObjectDesc {
    let size = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
    let at = [
        (lo[0] + hi[0]) / 2.0,
        (lo[1] + hi[1]) / 2.0,
        (lo[2] + hi[2]) / 2.0,
    ];
    cuboid(size, at, 0.0, mat, l)
}

/// A vertical rectangle x0..x1 × z0..z1 in the plane y, facing −y (out).
fn quad_out(x: [f64; 2], z: [f64; 2], y: f64, mat: &str, l: Label) -> ObjectDesc {
    let at = [(x[0] + x[1]) / 2.0, y, (z[0] + z[1]) / 2.0];
    let mut q = turned_quad([x[1] - x[0], z[1] - z[0]], at, 0.0, mat, l);
    // A quarter turn about x takes the quad's +z normal to −y, its +y to +z.
    q.transform.rotate_deg = Some([90.0, 0.0, 0.0]);
    q
}

/// A horizontal rectangle x0..x1 × y0..y1 at height z, facing up or down.
fn quad_flat(x: [f64; 2], y: [f64; 2], z: f64, up: bool, mat: &str, l: Label) -> ObjectDesc {
    let at = [(x[0] + x[1]) / 2.0, (y[0] + y[1]) / 2.0, z];
    let mut q = turned_quad([x[1] - x[0], y[1] - y[0]], at, 0.0, mat, l);
    if !up {
        q.transform.rotate_deg = Some([180.0, 0.0, 0.0]);
    }
    q
}

/// The opening of a bay: x half-width, bottom and top z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Opening {
    /// Half the opening's width.
    pub half_w: f64,
    /// Bottom of the opening above the bay's floor.
    pub z0: f64,
    /// Top of the opening.
    pub z1: f64,
}

/// The window opening of `s`.
pub fn window_opening(s: &Style) -> Opening {
    Opening {
        half_w: s.window_m[0] / 2.0,
        z0: s.sill_m,
        z1: s.sill_m + s.window_m[1],
    }
}

/// The wall around `o`, `depth` thick, as one mesh: its front and back
/// faces with the hole and the four reveals. The bay's outer sides, top
/// and bottom are left out: bays tile a wall edge to edge (neighbours,
/// the façade's solid ends, the roof and the ground hide them).
fn wall_around(s: &Style, o: Opening, depth: f64, out: &mut Vec<ObjectDesc>) {
    let (hw, h) = (s.bay_m / 2.0, s.floor_m);
    let outer = [-hw, hw, 0.0, h];
    let inner = [-o.half_w, o.half_w, o.z0, o.z1];
    out.push(ring(outer, inner, [0.0, depth], s.walls[0]));
}

/// A rectangular ring in the x–z plane between y0 and y1: the `outer`
/// rectangle `[x0, x1, z0, z1]` less the `inner` one, faces out (−y) at
/// y0, in (+y) at y1, and the hole's reveals facing into the hole; no
/// outer sides. Empty strips (an opening down to the floor) are skipped.
fn ring(outer: [f64; 4], inner: [f64; 4], [y0, y1]: [f64; 2], mat: &str) -> ObjectDesc {
    let mut m = LocalMesh::default();
    let [x0, x1, z0, z1] = outer;
    let [ix0, ix1, iz0, iz1] = inner;
    let (ex, ey, ez) = (DVec3::X, DVec3::Y, DVec3::Z);
    let strips = [
        ([x0, z0], [ix0 - x0, z1 - z0]),
        ([ix1, z0], [x1 - ix1, z1 - z0]),
        ([ix0, z0], [ix1 - ix0, iz0 - z0]),
        ([ix0, iz1], [ix1 - ix0, z1 - iz1]),
    ];
    for ([x, z], [w, hh]) in strips {
        // Front: x × z = −y; back: z × x = +y.
        rect(&mut m, DVec3::new(x, y0, z), ex * w, ez * hh);
        rect(&mut m, DVec3::new(x, y1, z), ez * hh, ex * w);
    }
    let d = y1 - y0;
    let ih = iz1 - iz0;
    let iw = ix1 - ix0;
    rect(&mut m, DVec3::new(ix0, y0, iz0), ey * d, ez * ih); // faces +x
    rect(&mut m, DVec3::new(ix1, y0, iz0), ez * ih, ey * d); // faces −x
    if iz0 > z0 {
        rect(&mut m, DVec3::new(ix0, y0, iz0), ex * iw, ey * d); // faces +z
    }
    if iz1 < z1 {
        rect(&mut m, DVec3::new(ix0, y0, iz1), ey * d, ex * iw); // faces −z
    }
    ObjectDesc {
        name: None,
        material: Some(mat.to_string()),
        semantic: Some("building".to_string()),
        instance: None,
        transform: Default::default(),
        repeat: Vec::new(),
        shape: m.into_shape(),
    }
}

/// Appends the rectangle p, p + u, p + u + v, p + v (normal u × v) unless
/// it is empty.
fn rect(m: &mut LocalMesh, p: DVec3, u: DVec3, v: DVec3) {
    if u.length() <= 0.0 || v.length() <= 0.0 {
        return;
    }
    let base = m.positions.len() as u32;
    m.positions.extend([p, p + u, p + u + v, p + v]);
    m.triangles
        .extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
}

/// The room behind the front wall (`front` thick): back wall, floor and
/// ceiling as single faces across the bay (neighbouring bays' rooms join
/// into one floor; the façade's solid ends close it), and the lamp panel
/// (off) under the ceiling.
fn room(s: &Style, front: f64, out: &mut Vec<ObjectDesc>) {
    let (b, hw, h) = (class("building"), s.bay_m / 2.0, s.floor_m);
    let (x, y) = ([-hw, hw], [front, SKIN_M]);
    out.push(quad_out(x, [0.0, h], SKIN_M, "facade_room_wall", b));
    out.push(quad_flat(x, y, ROOM_FLOOR_M, true, "facade_room_floor", b));
    out.push(quad_flat(
        x,
        y,
        h - ROOM_FLOOR_M,
        false,
        "facade_room_ceiling",
        b,
    ));
    let (y0, y1) = lamp_span(front);
    out.push(quad_flat(
        [-0.3, 0.3],
        [y0, y1],
        lamp_z(s),
        false,
        "facade_lamp_off",
        b,
    ));
}

/// Height of the unlit lamp panel (1 cm under the ceiling).
fn lamp_z(s: &Style) -> f64 {
    s.floor_m - ROOM_FLOOR_M - 0.01
}

/// The lamp panel's y extent in a room whose front wall is `front` thick.
fn lamp_span(front: f64) -> (f64, f64) {
    (front + 0.2, SKIN_M - 0.2)
}

/// Front-wall thickness of a bay whose glass stands `recess` deep.
pub fn front_depth(recess: f64) -> f64 {
    recess + 0.1
}

/// Glass filling `o` with its front face `recess` behind the wall plane,
/// a frame around it (proud of the glass by 4 cm), `panes` panes and an
/// optional transom.
fn glazing(o: Opening, recess: f64, frame: &str, panes: u32, transom: bool) -> Vec<ObjectDesc> {
    let b = class("building");
    let (hw, f) = (o.half_w, FRAME_M);
    let (y0, y1) = (recess - 0.04, recess + 0.06);
    let mut out = vec![boxed(
        [-hw, recess, o.z0],
        [hw, recess + GLASS_M, o.z1],
        "facade_glass",
        b,
    )];
    let inner = [-hw + f, hw - f, o.z0 + f, o.z1 - f];
    out.push(ring([-hw, hw, o.z0, o.z1], inner, [y0, y1], frame));
    if panes > 1 {
        let step = 2.0 * hw / panes as f64;
        let x = -hw + step - f / 2.0;
        let bar = boxed([x, y0, o.z0 + f], [x + f, y1, o.z1 - f], frame, b);
        out.push(repeated(bar, &[(panes - 1, [step, 0.0, 0.0])]));
    }
    if transom {
        let z = o.z0 + 0.72 * (o.z1 - o.z0);
        out.push(boxed([-hw + f, y0, z], [hw - f, y1, z + f], frame, b));
    }
    out
}

/// A window bay of style `s`, variant `v` (0..VARIANTS): wall with the
/// opening, glazing, stone sill and lintel, the room behind, and its
/// curtains or blinds and furniture.
pub fn window_bay(s: &Style, v: u32) -> Vec<ObjectDesc> {
    let b = class("building");
    let o = window_opening(s);
    let front = front_depth(s.recess_m);
    let mut out = Vec::new();
    wall_around(s, o, front, &mut out);
    out.extend(glazing(o, s.recess_m, s.frame, s.panes, s.transom));
    let hw = o.half_w;
    // Sill, lintel and curtains stay inside the bay (bays tile a wall).
    let wide = |e: f64| (hw + e).min(s.bay_m / 2.0 - LINING_M);
    // The sill sticks out 6 cm and reaches back to the glass; the lintel
    // is 3 cm proud of the wall.
    let (sx, lx) = (wide(0.08), wide(0.15));
    out.push(boxed(
        [-sx, -0.06, o.z0 - 0.06],
        [sx, s.recess_m, o.z0],
        s.trim,
        b,
    ));
    if o.z1 + 0.2 < s.floor_m {
        out.push(boxed([-lx, -0.03, o.z1], [lx, 0.0, o.z1 + 0.2], s.trim, b));
    }
    room(s, front, &mut out);
    // Curtains hang 3–6 cm behind the front wall, from the opening's top
    // to its sill; blinds come down from the top.
    let cy = front + 0.05;
    let (z0, z1) = (o.z0, (o.z1 + 0.05).min(lamp_z(s) - 0.01));
    let cx = wide(0.1);
    match v % VARIANTS {
        0 => {
            let w = 0.3 * hw;
            out.push(quad_out(
                [-cx, -hw + w],
                [z0, z1],
                cy,
                "facade_curtain_cream",
                b,
            ));
            out.push(quad_out(
                [hw - w, cx],
                [z0, z1],
                cy,
                "facade_curtain_cream",
                b,
            ));
        }
        1 => {
            let zb = o.z1 - 0.4 * (o.z1 - o.z0);
            out.push(quad_out([-hw, hw], [zb, z1], cy, "facade_blind", b));
        }
        _ => {
            let w = 0.9 * hw;
            out.push(quad_out(
                [-cx, -hw + w],
                [z0, z1],
                cy,
                "facade_curtain_red",
                b,
            ));
        }
    }
    furniture(s, front, v, &mut out);
    out
}

/// One piece of furniture against the room's back wall: a shelf, a table
/// or a sofa.
fn furniture(s: &Style, front: f64, v: u32, out: &mut Vec<ObjectDesc>) {
    let b = class("building");
    let back = SKIN_M - 0.001;
    let hw = s.bay_m / 2.0 - LINING_M - 0.1;
    let depth = (back - front - 0.3).min(0.45);
    let z = ROOM_FLOOR_M + 0.001;
    let (lo, hi, m) = match v % VARIANTS {
        0 => (
            [-hw.min(0.5), back - depth * 0.7, z],
            [hw.min(0.5), back, 1.8],
            "facade_wood",
        ),
        1 => (
            [-hw.min(0.6), back - depth, z],
            [hw.min(0.3), back, 0.75],
            "facade_wood",
        ),
        _ => (
            [-hw.min(0.9), back - depth, z],
            [hw.min(0.9), back, 0.8],
            "facade_sofa",
        ),
    };
    out.push(boxed(lo, [hi[0], hi[1], hi[2].min(s.floor_m - 0.3)], m, b));
}

/// The emitter of a lit room: a panel 2 mm under the window bay's (off)
/// lamp panel, radiating downward.
pub fn room_light(s: &Style) -> Vec<ObjectDesc> {
    let (y0, y1) = lamp_span(front_depth(s.recess_m));
    let z = lamp_z(s) - 0.002;
    vec![quad_flat(
        [-0.29, 0.29],
        [y0 + 0.01, y1 - 0.01],
        z,
        false,
        "window_lit",
        class("building"),
    )]
}

/// Shopfront opening of a ground-floor bay (narrow piers, a stall riser
/// and a fascia for the sign).
pub fn shop_opening(s: &Style) -> Opening {
    Opening {
        half_w: s.bay_m / 2.0 - 0.15,
        z0: if s.ground == Ground::Lobby { 0.1 } else { 0.45 },
        z1: (s.floor_m - 0.6).min(2.9),
    }
}

/// A shopfront (or lobby) bay: large glazing before a lit-by-day shop
/// room with shelves and a counter.
pub fn shop_bay(s: &Style) -> Vec<ObjectDesc> {
    let b = class("building");
    let o = shop_opening(s);
    let front = front_depth(SHOP_RECESS_M);
    let mut out = Vec::new();
    wall_around(s, o, front, &mut out);
    out.extend(glazing(o, SHOP_RECESS_M, s.frame, 2, false));
    room(s, front, &mut out);
    let back = SKIN_M - 0.001;
    let hw = o.half_w - 0.2;
    let shelf = boxed([-hw, back - 0.3, 0.9], [hw, back, 0.93], "facade_wood", b);
    out.push(repeated(shelf, &[(3, [0.0, 0.0, 0.5])]));
    let z = ROOM_FLOOR_M + 0.001;
    out.push(boxed(
        [-0.6, back - 0.7, z],
        [0.6, back - 0.45, 0.95],
        "facade_wood",
        b,
    ));
    out
}

/// Steps before a door: `n` risers of 0.17 m, each 0.3 m deep, 1.6 m wide.
pub fn steps(n: u32) -> Vec<ObjectDesc> {
    let b = class("building");
    (0..n)
        .map(|k| {
            let y0 = -0.3 * (n - k) as f64;
            let z1 = 0.17 * (k + 1) as f64;
            boxed([-0.8, y0, 0.0], [0.8, 0.0, z1], "facade_step", b)
        })
        .collect()
}

/// A door bay: the door recessed 0.25 m behind a stone threshold raised by
/// `n_steps` steps, a fanlight above it, a handle, and (residential) a
/// canopy.
pub fn door_bay(s: &Style, n_steps: u32, canopy: bool) -> Vec<ObjectDesc> {
    let b = class("building");
    let sill = 0.17 * n_steps as f64;
    let o = Opening {
        half_w: 0.55,
        z0: 0.0,
        z1: sill + 2.2 + 0.45,
    };
    let front = front_depth(0.25);
    let mut out = Vec::new();
    wall_around(s, o, front, &mut out);
    // The threshold fills the opening up to the door's sill.
    if sill > 0.0 {
        out.push(boxed(
            [-0.55, 0.0, 0.0],
            [0.55, front, sill],
            "facade_step",
            b,
        ));
    }
    let leaf_top = sill + 2.2;
    out.push(boxed([-0.55, 0.25, sill], [0.55, 0.3, leaf_top], "door", b));
    out.push(boxed(
        [0.35, 0.22, sill + 1.0],
        [0.42, 0.25, sill + 1.06],
        "facade_metal_dark",
        b,
    ));
    let fan = Opening {
        half_w: 0.55,
        z0: leaf_top,
        z1: o.z1,
    };
    out.extend(glazing(fan, 0.25, s.frame, 1, false));
    room(s, front, &mut out);
    out.extend(steps(n_steps));
    if canopy && o.z1 + 0.3 < s.floor_m {
        out.push(boxed(
            [-0.9, -0.9, o.z1 + 0.15],
            [0.9, 0.0, o.z1 + 0.25],
            s.trim,
            b,
        ));
    }
    out
}

/// A warehouse's roller door bay: a 3.2 m × 3.6 m opening closed by a
/// slatted steel door 0.2 m behind the wall plane.
pub fn roller_bay(s: &Style) -> Vec<ObjectDesc> {
    let b = class("building");
    let o = Opening {
        half_w: 1.6,
        z0: 0.0,
        z1: 3.6_f64.min(s.floor_m - 0.4),
    };
    let mut out = Vec::new();
    wall_around(s, o, 0.4, &mut out);
    out.push(boxed(
        [-1.6, 0.25, 0.0],
        [1.6, 0.4, o.z1],
        "facade_metal_grey",
        b,
    ));
    // Slats: ribs 4 cm proud, every 0.2 m.
    let rib = boxed([-1.6, 0.21, 0.1], [1.6, 0.25, 0.14], "facade_metal_grey", b);
    let n = ((o.z1 - 0.2) / 0.2) as u32;
    out.push(repeated(rib, &[(n, [0.0, 0.0, 0.2])]));
    out.push(boxed(
        [-1.6, 0.0, o.z1 - 0.01],
        [1.6, 0.25, o.z1],
        "facade_metal_dark",
        b,
    ));
    room(s, 0.4, &mut out);
    out
}
