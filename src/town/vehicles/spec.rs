//! The parameters of a four-wheeled body and the side-profile, plan and
//! section functions the loft (`loft`) sweeps: length, width, roof height,
//! wheelbase, wheel size, bonnet, windscreen, roof line and boot.
//!
//! Body frame: x forward, y left, z up, origin on the ground at the centre
//! of the footprint; the nose is at x = length / 2.

pub use super::bed::Bed;

/// What a body looks like, metres (x stations are body-frame x).
#[derive(Clone, Copy, Debug)]
pub struct Spec {
    /// Body length, bumper to bumper.
    pub length: f64,
    /// Body width without mirrors.
    pub width: f64,
    /// Roof top.
    pub height: f64,
    /// Wheel (tyre) radius.
    pub wheel_r: f64,
    /// Tyre width.
    pub tyre_w: f64,
    /// Axle x (front, rear).
    pub axles: [f64; 2],
    /// Underside of the body.
    pub floor_z: f64,
    /// Top of the nose at the front tip.
    pub nose_z: f64,
    /// Bonnet top at the windscreen base.
    pub hood_z: f64,
    /// Waist (side-window sill) at the rear of the glass.
    pub belt_z: f64,
    /// Top of the boot or tailgate at the tail.
    pub deck_z: f64,
    /// Windscreen base x.
    pub ws_x: f64,
    /// Front of the flat roof.
    pub roof_front_x: f64,
    /// Rear of the flat roof.
    pub roof_rear_x: f64,
    /// Base of the rear window (end of the glass house).
    pub rear_x: f64,
    /// Plan-view roundness of the ends (superellipse exponent; high = blunt).
    pub plan_p: f64,
    /// Section roundness (superellipse exponent; high = boxy).
    pub section_n: f64,
    /// Number of door seams per side (2 or 3 for cars, 1 for vans).
    pub doors: u8,
    /// A cargo box behind the cab from this x to the tail (box truck).
    pub cargo_front_x: Option<f64>,
    /// An open load bed behind the cab (pickup).
    pub bed: Option<Bed>,
}

/// `sign(v)·|v|^e`, the superellipse coordinate.
pub fn spow(v: f64, e: f64) -> f64 {
    v.signum() * v.abs().powf(e)
}

/// Smooth 0 → 1 ramp of `t` over [0, 1] (clamped).
fn ease(t: f64) -> f64 {
    let t = t.clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

impl Spec {
    /// Half the body length.
    pub fn hl(&self) -> f64 {
        self.length / 2.0
    }

    /// Plan half-width at x: a superellipse, blunt at both ends.
    pub fn half_width(&self, x: f64) -> f64 {
        let xi = (x / self.hl()).abs().min(1.0);
        self.width / 2.0
            * (1.0 - xi.powf(self.plan_p))
                .max(0.0)
                .powf(1.0 / self.plan_p)
    }

    /// Underside at x: the floor, lifted towards both bumpers and cut by a
    /// wheel arch (radius wheel + 6 cm) over each axle.
    pub fn bottom_z(&self, x: f64) -> f64 {
        let end = (x.abs() - (self.hl() - 0.45)).max(0.0) / 0.45;
        let mut z = self.floor_z + 0.12 * end * end;
        let ra = self.wheel_r + 0.06;
        for a in self.axles {
            let d = (x - a).abs();
            if d < ra {
                z = z.max(self.wheel_r + (ra * ra - d * d).sqrt() * 0.96);
            }
        }
        z.min(self.top_z(x) - 0.05)
    }

    /// Top of the painted lower body (shoulder line) at x: nose rising to
    /// the bonnet, a waist rising from the windscreen to the rear glass,
    /// the boot deck, and a rounded drop at the very tail.
    pub fn top_z(&self, x: f64) -> f64 {
        let hl = self.hl();
        let z = if x >= self.ws_x {
            let s = (hl - x) / (hl - self.ws_x);
            self.nose_z + (self.hood_z - self.nose_z) * (1.0 - (1.0 - s).powi(2))
        } else if x >= self.rear_x {
            let s = (self.ws_x - x) / (self.ws_x - self.rear_x);
            self.hood_z + (self.belt_z - self.hood_z) * s
        } else {
            let s = (self.rear_x - x) / (self.rear_x + hl);
            self.belt_z + (self.deck_z - self.belt_z) * ease(s)
        };
        // The tail and nose round off over their last 12 cm.
        let tip = ((x.abs() - (hl - 0.12)).max(0.0) / 0.12).min(1.0);
        z - 0.08 * tip * tip
    }

    /// Lower-body section centre and half-height at x.
    fn section(&self, x: f64) -> (f64, f64) {
        let (b, t) = (self.bottom_z(x), self.top_z(x));
        ((b + t) / 2.0, (t - b) / 2.0)
    }

    /// Point of the lower body at station x and angle θ about the x axis
    /// (θ = 0 on the left side, π/2 on top): a superellipse section,
    /// 6 % narrower at the top (tumblehome).
    pub fn lower(&self, x: f64, th: f64) -> [f64; 3] {
        let (zc, hz) = self.section(x);
        let e = 2.0 / self.section_n;
        let v = spow(th.sin(), e);
        let y = self.half_width(x) * spow(th.cos(), e) * (1.0 - 0.06 * v.max(0.0));
        [x, y, zc + hz * v]
    }

    /// Half-width of the lower body at x and height z (0 outside it).
    pub fn lower_half_width_at(&self, x: f64, z: f64) -> f64 {
        let (zc, hz) = self.section(x);
        if hz <= 0.0 {
            return 0.0;
        }
        let ts = (z - zc) / hz;
        if ts.abs() >= 1.0 {
            return 0.0;
        }
        let n = self.section_n;
        let c = (1.0 - ts.abs().powf(n)).powf(1.0 / n);
        self.half_width(x) * c * (1.0 - 0.06 * ts.max(0.0))
    }

    /// Base of the glass house at x: just under the shoulder line.
    pub fn glass_base_z(&self, x: f64) -> f64 {
        self.top_z(x) - 0.03
    }

    /// Roof line at x over the glass house: windscreen curving into the
    /// roof, a slight crown, the rear window curving down.
    pub fn roof_z(&self, x: f64) -> f64 {
        let base = self.glass_base_z(x);
        if x > self.ws_x || x < self.rear_x {
            return base;
        }
        let f = |s: f64| {
            let s = s.clamp(0.0, 1.0);
            s * (2.0 - s)
        };
        let s = if x > self.roof_front_x {
            f((self.ws_x - x) / (self.ws_x - self.roof_front_x))
        } else if x < self.roof_rear_x {
            f((x - self.rear_x) / (self.roof_rear_x - self.rear_x))
        } else {
            1.0
        };
        let mid = (self.roof_front_x + self.roof_rear_x) / 2.0;
        let half = ((self.roof_front_x - self.roof_rear_x) / 2.0).max(0.1);
        let crown = 0.025 * (((x - mid) / half).powi(2)).min(1.0);
        base + (self.height - crown - base).max(0.0) * s
    }

    /// Point of the glass house at station x and θ ∈ [0, π] (0 at the
    /// left sill, π/2 on the roof): its base follows the lower body at the
    /// sill, narrowing 18 % to the roof; `inset` shrinks it inwards.
    pub fn glass(&self, x: f64, th: f64, inset: f64) -> [f64; 3] {
        let zb = self.glass_base_z(x);
        let zr = (self.roof_z(x) - inset).max(zb);
        let hw = (self.lower_half_width_at(x, zb + 0.01) * 0.99 - inset).max(0.0);
        let e = 2.0 / 5.0;
        let v = th.sin().abs().powf(e);
        let y = hw * spow(th.cos(), e) * (1.0 - 0.18 * v);
        [x, y, zb + (zr - zb) * v]
    }

    /// Where the body's front (sign 1) or rear (−1) surface is at height z
    /// and side offset y, scanning inward from the tip (x, metres).
    pub fn end_x(&self, sign: f64, y: f64, z: f64) -> f64 {
        let mut x = self.hl();
        while x > 0.0 {
            let xs = sign * x;
            let (b, t) = (self.bottom_z(xs), self.top_z(xs));
            if z > b && z < t && self.lower_half_width_at(xs, z) >= y.abs() {
                return xs;
            }
            x -= 0.002;
        }
        0.0
    }
}

/// The spec of every four-wheeled body type by name.
pub fn spec_of(kind: super::BodyKind) -> Option<Spec> {
    use super::BodyKind as K;
    let car = Spec {
        length: 4.7,
        width: 1.8,
        height: 1.45,
        wheel_r: 0.32,
        tyre_w: 0.22,
        axles: [1.42, -1.40],
        floor_z: 0.17,
        nose_z: 0.68,
        hood_z: 0.9,
        belt_z: 0.98,
        deck_z: 1.0,
        ws_x: 0.85,
        roof_front_x: 0.12,
        roof_rear_x: -0.95,
        rear_x: -1.55,
        plan_p: 8.0,
        section_n: 6.0,
        doors: 3,
        cargo_front_x: None,
        bed: None,
    };
    Some(match kind {
        K::Sedan => car,
        K::Hatchback => Spec {
            length: 4.05,
            width: 1.76,
            height: 1.48,
            wheel_r: 0.3,
            axles: [1.28, -1.25],
            ws_x: 0.72,
            roof_front_x: 0.0,
            roof_rear_x: -1.5,
            rear_x: -1.9,
            deck_z: 0.98,
            ..car
        },
        K::Estate => Spec {
            length: 4.8,
            roof_rear_x: -2.02,
            rear_x: -2.3,
            height: 1.49,
            ..car
        },
        K::Coupe => Spec {
            length: 4.45,
            width: 1.82,
            height: 1.32,
            wheel_r: 0.33,
            axles: [1.35, -1.3],
            nose_z: 0.6,
            hood_z: 0.84,
            belt_z: 0.92,
            deck_z: 0.94,
            ws_x: 0.7,
            roof_front_x: -0.15,
            roof_rear_x: -0.7,
            rear_x: -1.6,
            doors: 2,
            ..car
        },
        K::Suv => Spec {
            length: 4.75,
            width: 1.9,
            height: 1.75,
            wheel_r: 0.37,
            tyre_w: 0.24,
            axles: [1.45, -1.4],
            floor_z: 0.24,
            nose_z: 0.85,
            hood_z: 1.06,
            belt_z: 1.12,
            deck_z: 1.1,
            ws_x: 0.95,
            roof_front_x: 0.3,
            roof_rear_x: -1.95,
            rear_x: -2.25,
            plan_p: 10.0,
            section_n: 7.0,
            ..car
        },
        K::Pickup => Spec {
            length: 5.3,
            width: 1.95,
            height: 1.85,
            wheel_r: 0.39,
            tyre_w: 0.26,
            axles: [1.75, -1.65],
            floor_z: 0.3,
            nose_z: 0.98,
            hood_z: 1.15,
            belt_z: 1.2,
            deck_z: 1.18,
            ws_x: 1.2,
            roof_front_x: 0.62,
            roof_rear_x: -0.42,
            rear_x: -0.55,
            plan_p: 12.0,
            section_n: 8.0,
            doors: 2,
            // Open from behind the cab to a 12 cm tailgate, 28 cm deep.
            bed: Some(Bed {
                front_x: -0.65,
                tail_x: -2.53,
                floor_z: 0.86,
                rail_steps: 4,
            }),
            ..car
        },
        K::Van => Spec {
            length: 5.3,
            width: 2.0,
            height: 2.3,
            wheel_r: 0.36,
            tyre_w: 0.24,
            axles: [1.95, -1.65],
            floor_z: 0.3,
            nose_z: 0.85,
            hood_z: 1.05,
            belt_z: 1.12,
            deck_z: 1.12,
            ws_x: 1.6,
            roof_front_x: 0.95,
            roof_rear_x: -2.5,
            rear_x: -2.62,
            plan_p: 12.0,
            section_n: 9.0,
            doors: 1,
            ..car
        },
        K::Truck => Spec {
            length: 7.5,
            width: 2.35,
            height: 2.75,
            wheel_r: 0.48,
            tyre_w: 0.3,
            axles: [2.6, -2.2],
            floor_z: 0.45,
            nose_z: 1.0,
            hood_z: 1.35,
            belt_z: 1.45,
            deck_z: 1.3,
            ws_x: 3.4,
            roof_front_x: 3.05,
            roof_rear_x: 2.2,
            rear_x: 2.1,
            plan_p: 16.0,
            section_n: 10.0,
            doors: 1,
            cargo_front_x: Some(1.95),
            bed: None,
        },
        K::Bus => Spec {
            length: 11.5,
            width: 2.45,
            height: 3.05,
            wheel_r: 0.5,
            tyre_w: 0.3,
            axles: [3.6, -3.0],
            floor_z: 0.35,
            nose_z: 1.0,
            hood_z: 1.08,
            belt_z: 1.15,
            deck_z: 1.15,
            ws_x: 5.66,
            roof_front_x: 5.45,
            roof_rear_x: -5.5,
            rear_x: -5.66,
            plan_p: 24.0,
            section_n: 10.0,
            doors: 1,
            ..car
        },
        K::Motorcycle | K::Bicycle => return None,
    })
}
