//! Town descriptions: the short TOML parameter file (`scenes/townNN.toml`)
//! the generator turns into a full `SceneDesc`, with its validation.
//!
//! Units: metres, km/h for speeds, degrees in files. The town grid's road
//! centrelines run along world x (east–west) and y (north–south), z up.

use std::path::Path;

use serde::{Deserialize, Serialize};

/// A town parameter file. Every field is documented as the town-format manual.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TownDesc {
    /// Town name (`town01` …), used in messages and metadata.
    pub name: String,
    /// Road network style: `grid` (straight streets), `organic` (the grid
    /// bent by a smooth seeded warp into curving streets, see `organic`;
    /// no `ramps` or `overpass`) or `highway` (the outer roads divided by
    /// a median barrier, with hard shoulders; twin-arm masts, guard rails
    /// and billboards along the roads, see docs/towns.md).
    #[serde(default)]
    pub road_style: RoadStyle,
    /// Size of the road grid along x and y, metres (rounded to whole blocks).
    pub extent_m: [f64; 2],
    /// Distance between parallel road centrelines, metres, ≥ `min_block_size_m`.
    pub block_size_m: f64,
    /// Lanes per travel direction, 1–3.
    #[serde(default = "one")]
    pub lanes_per_direction: u32,
    /// Lane width, metres, in [3.2, 4.5] (default 3.5); cars must fit the
    /// turns inside their own lane (see `routes`).
    #[serde(default = "default_lane_width")]
    pub lane_width_m: f64,
    /// Sidewalk width (curb included), metres, in [1.5, 8] (default 3); the
    /// width of the gravel shoulder when `sidewalks = false`.
    #[serde(default = "default_sidewalk")]
    pub sidewalk_width_m: f64,
    /// Raised sidewalks with curbs, crosswalks and pedestrians (default true);
    /// false gives country roads with flat gravel shoulders and no pedestrians.
    #[serde(default = "crate::scene::desc::default_true")]
    pub sidewalks: bool,
    /// Fraction of building lots that hold a building, in [0, 1].
    pub building_density: f64,
    /// Floors of ordinary buildings, [min, max], 1 ≤ min ≤ max ≤ 12.
    pub floors: [u32; 2],
    /// Fraction of buildings that are towers, in [0, 1] (default 0).
    #[serde(default)]
    pub tower_fraction: f64,
    /// Floors of towers, [min, max], 8 ≤ min ≤ max ≤ 60 (default [15, 30]).
    #[serde(default = "default_tower_floors")]
    pub tower_floors: [u32; 2],
    /// Trees and parks, in [0, 1].
    pub vegetation_density: f64,
    /// A river along x in place of the middle block row, crossed by every
    /// y-road on a bridge (default false; needs at least 3 block rows).
    #[serde(default)]
    pub river: bool,
    /// A roundabout in place of the most central cross junction (default
    /// false; needs 2 × 3 blocks or more and blocks ≥ 80 m). Traffic of
    /// the four blocks around it turns right round the ring; pedestrians
    /// keep away from it.
    #[serde(default)]
    pub roundabout: bool,
    /// An underpass (default false): the y-road of block column 1 passes
    /// under the middle x-road in a cut between retaining walls, the
    /// x-road straight over it on a deck; no junction there (see
    /// `underpass`). Needs a level `grid` or `organic` town (no grade, hills, river,
    /// ramps or overpass) with 2 × 2 blocks or more, blocks long enough
    /// for a 5.5 m cut at ≤ 10 % and, with a roundabout, 6 block columns.
    #[serde(default, skip_serializing_if = "is_false")]
    pub underpass: bool,
    /// Highway slip roads (default false): beside every block segment of the
    /// outer x-roads, on their outer side, an off-ramp leaving the outer lane
    /// by a taper and an S-curve and an on-ramp merging back, with edge
    /// lines, hatched gores and gravel shoulders (see `ramps`). Needs long
    /// blocks: `block_size_m` ≥ road width + 254 m (highway towns).
    #[serde(default)]
    pub ramps: bool,
    /// Radius of the curved corners of the highway loop, metres, measured
    /// on the road centreline (default 0: square corners with T junctions).
    /// When > 0, the four corners where the outer roads meet become quarter
    /// circles of this radius (asphalt, markings and shoulders follow the
    /// arc; no junction there); the ring and the corner blocks' loops drive
    /// the arcs in their lanes, and the corner blocks' lots keep clear of
    /// them. Range [2 × road width, block_size_m − min_block_size_m / 2];
    /// needs country roads (`sidewalks = false`), no `ramps` and at least
    /// 2 × 2 blocks.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub loop_corner_radius_m: f64,
    /// Ground cover between and around the blocks.
    #[serde(default)]
    pub terrain: TerrainKind,
    /// Height of the hills around the town, metres, in [0, 150] (default 0:
    /// flat). The ground stays exactly flat on and within 8 m of the roads,
    /// blocks and river, then blends over 90 m into hills whose highest point
    /// is `hills_m`, with trees on them; the town lies in a valley.
    #[serde(default)]
    pub hills_m: f64,
    /// Typical distance between hill tops, metres, in [50, 2000] (default 300).
    #[serde(default = "default_hill_wavelength")]
    pub hill_wavelength_m: f64,
    /// Amplitude of the ground-elevation field under the whole town,
    /// metres, in [0, 50] (default 0: level). Roads, markings, shoulders,
    /// junctions, lots, buildings, furniture, hills and every vehicle,
    /// pedestrian and the ego follow h(x, y) = A/2 · (sin(k·u + φ₀) +
    /// sin(k·v + φ₁)) with k = 2π / `road_grade_wavelength_m` and (u, v) the
    /// ground turned by a seeded angle (see `grade`). The steepest grade,
    /// A · k / √2, must stay ≤ 6 %; not with a river (water lies level).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub road_grade_m: f64,
    /// Wavelength of the ground-elevation field, metres, in [200, 5000]
    /// (default 800): the distance from one crest to the next.
    #[serde(
        default = "default_grade_wavelength",
        skip_serializing_if = "is_default_grade_wavelength"
    )]
    pub road_grade_wavelength_m: f64,
    /// An overpass (default false): a two-lane road on a bridge crossing
    /// over the first outer x-road (the south highway) in the middle of the
    /// block column nearest the town centre, with approach grades, a deck
    /// with parapets and piers, from a turning loop in the country south of
    /// the town to one inside the block (see `overpass`). Its traffic loop
    /// meets no other road. Needs `ramps` and a level town (no grade).
    #[serde(default, skip_serializing_if = "is_false")]
    pub overpass: bool,
    /// Outskirts (default false): rows of buildings on lots beyond the
    /// outer roads' far sidewalks, and a line of trees past the road stubs,
    /// so that a view out of the town ends at a street front rather than an
    /// empty field (see `outskirts`). Needs a level `grid` or `organic` town
    /// with square corners on `grass` or `dry` ground, without hills, grade
    /// or ramps.
    #[serde(default, skip_serializing_if = "is_false")]
    pub outskirts: bool,
    /// Fraction of traffic slots holding a vehicle, in [0, 1].
    pub traffic_density: f64,
    /// Fraction of kerbside parking bays holding a parked car, in [0, 1]
    /// (default 0: no lay-bys). Above 0 the sidewalks get lay-bys (see
    /// `parking`), which needs a level grid town with sidewalks at least
    /// `parking::min_sidewalk_m()` wide.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub parking_density: f64,
    /// Width of a parking lane on each side of every road, metres: 0 (the
    /// default: none) or in `parking::LANE_RANGE_M`. The strip lies at road
    /// level between the outer driving lane and the kerb, so the road (kerb
    /// to kerb) is 2 × `parking_lane_m` wider while the driving lanes keep
    /// their place; with `parking_density` > 0 parked cars stand in it
    /// instead of in lay-bys (see `parking::lane`). Needs a level grid or
    /// organic town with sidewalks narrower than `parking::min_sidewalk_m()`
    /// (wider ones take lay-bys).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub parking_lane_m: f64,
    /// Cruising speed of all traffic and the ego vehicle, km/h, in [5, 130].
    pub speed_kmh: f64,
    /// Frames per second of sequences, in (0, 120] (default 10).
    #[serde(default = "default_fps")]
    pub fps: f64,
    /// Sun elevation above the horizon, degrees, in (0, 90].
    pub sun_elevation_deg: f64,
    /// Sun azimuth counter-clockwise from +x, degrees.
    pub sun_azimuth_deg: f64,
    /// Sky appearance.
    #[serde(default)]
    pub sky: SkyKind,
}

/// Road network style.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RoadStyle {
    /// A rectangular grid of streets with T and cross junctions.
    #[default]
    Grid,
    /// Curving streets: the grid bent by a smooth, seeded, area-keeping
    /// warp (streets keep their width within 3.3 %, headings turn ≤ 8.7°).
    Organic,
    /// Fast roads: the outer roads are a divided highway (median barrier,
    /// gravel hard shoulders, right-in/right-out junctions) with highway
    /// street furniture (twin-arm masts, guard rails along the outer roads,
    /// billboards) whatever the speed.
    Highway,
}

/// Ground cover.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TerrainKind {
    /// Green lawn.
    #[default]
    Grass,
    /// Dry, yellowish grass.
    Dry,
    /// Ploughed fields (brown).
    Field,
}

/// Sky appearance (a gradient sky scaled to the sun).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SkyKind {
    /// Deep blue clear sky.
    #[default]
    Clear,
    /// Pale, hazy sky.
    Hazy,
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}
fn is_false(v: &bool) -> bool {
    !*v
}
fn default_grade_wavelength() -> f64 {
    800.0
}
fn is_default_grade_wavelength(v: &f64) -> bool {
    *v == default_grade_wavelength()
}
fn one() -> u32 {
    1
}
fn default_lane_width() -> f64 {
    3.5
}
fn default_sidewalk() -> f64 {
    3.0
}
fn default_tower_floors() -> [u32; 2] {
    [15, 30]
}
fn default_fps() -> f64 {
    10.0
}
fn default_hill_wavelength() -> f64 {
    300.0
}

/// Longest vehicle body, metres (the bus); sets the smallest block.
pub const MAX_VEHICLE_LENGTH_M: f64 = 12.0;
/// Clearance added on each side of the junction window, metres.
pub const JUNCTION_MARGIN_M: f64 = 1.5;

impl TownDesc {
    /// Road width, kerb to kerb, metres: the driving lanes and the
    /// parking lanes either side.
    pub fn road_width_m(&self) -> f64 {
        self.driving_width_m() + 2.0 * self.parking_lane_m
    }

    /// Width of the driving lanes of both directions, metres.
    pub fn driving_width_m(&self) -> f64 {
        2.0 * self.lanes_per_direction as f64 * self.lane_width_m
    }

    /// Smallest block size: room on every side for a queue at the stop
    /// line behind the departing crosswalk (see `traffic`).
    pub fn min_block_size_m(&self) -> f64 {
        2.0 * (self.road_width_m() + MAX_VEHICLE_LENGTH_M + 2.0 * JUNCTION_MARGIN_M)
    }

    /// Checks every range; the message names the field.
    pub fn validate(&self) -> Result<(), String> {
        let range = |name: &str, v: f64, lo: f64, hi: f64| {
            if v.is_finite() && v >= lo && v <= hi {
                Ok(())
            } else {
                Err(format!("{name}: must be in [{lo}, {hi}], got {v}"))
            }
        };
        range(
            "lanes_per_direction",
            self.lanes_per_direction as f64,
            1.0,
            3.0,
        )?;
        range("lane_width_m", self.lane_width_m, 3.2, 4.5)?;
        range("sidewalk_width_m", self.sidewalk_width_m, 1.5, 8.0)?;
        // Before the block size, which depends on the road's width.
        super::parking::lane::validate(self)?;
        let min_block = self.min_block_size_m();
        range("block_size_m", self.block_size_m, min_block, 1000.0)?;
        for (i, e) in self.extent_m.iter().enumerate() {
            range(&format!("extent_m[{i}]"), *e, self.block_size_m, 5000.0)?;
        }
        range("building_density", self.building_density, 0.0, 1.0)?;
        range("tower_fraction", self.tower_fraction, 0.0, 1.0)?;
        range("vegetation_density", self.vegetation_density, 0.0, 1.0)?;
        range("hills_m", self.hills_m, 0.0, 150.0)?;
        range("hill_wavelength_m", self.hill_wavelength_m, 50.0, 2000.0)?;
        range("road_grade_m", self.road_grade_m, 0.0, 50.0)?;
        range(
            "road_grade_wavelength_m",
            self.road_grade_wavelength_m,
            200.0,
            5000.0,
        )?;
        let steepest = super::grade::max_grade(self.road_grade_m, self.road_grade_wavelength_m);
        if steepest > super::grade::MAX_GRADE {
            return Err(format!(
                "road_grade_m: the steepest grade road_grade_m · 2π / road_grade_wavelength_m / √2 \
                 is {:.1} %, more than {} %",
                steepest * 100.0,
                super::grade::MAX_GRADE * 100.0
            ));
        }
        if self.road_grade_m > 0.0 && self.river {
            return Err("road_grade_m: not with a river (the water lies level)".into());
        }
        if self.overpass && (!self.ramps || self.road_grade_m > 0.0) {
            return Err("overpass: needs ramps = true and no road_grade_m".into());
        }
        range("traffic_density", self.traffic_density, 0.0, 1.0)?;
        range("speed_kmh", self.speed_kmh, 5.0, 130.0)?;
        range("fps", self.fps, 1e-3, 120.0)?;
        range("sun_elevation_deg", self.sun_elevation_deg, 1.0, 90.0)?;
        range("sun_azimuth_deg", self.sun_azimuth_deg, -360.0, 360.0)?;
        if self.river && (self.extent_m[1] / self.block_size_m).round() < 3.0 {
            return Err("river: needs at least 3 block rows (extent_m[1] / block_size_m)".into());
        }
        if self.roundabout {
            let blocks = self.extent_m.map(|e| (e / self.block_size_m).round());
            let few = blocks[0] < 2.0 || blocks[1] < 2.0 || blocks[0] * blocks[1] < 6.0;
            if few || self.block_size_m < 80.0 {
                return Err("roundabout: needs 2 × 3 blocks or more and block_size_m ≥ 80".into());
            }
        }
        if self.underpass {
            let level = self.road_grade_m == 0.0 && self.hills_m == 0.0;
            if !level || self.river || self.ramps || self.overpass {
                return Err(
                    "underpass: needs a level town (no road_grade_m or hills_m) without river, ramps or overpass"
                        .into(),
                );
            }
            if self.road_style == RoadStyle::Highway {
                return Err("underpass: on grid or organic towns only".into());
            }
            super::underpass::check(self)?;
        }
        if self.road_style == RoadStyle::Organic && (self.ramps || self.overpass) {
            return Err(format!(
                "road_style: \"organic\" bends every street, so it allows no ramps or overpass (got ramps = {}, overpass = {})",
                self.ramps, self.overpass
            ));
        }
        let ramp_block = super::ramps::min_ramp_block_m(self);
        if self.ramps && self.block_size_m < ramp_block {
            return Err(format!(
                "ramps: needs long blocks (block_size_m ≥ {ramp_block}, as in highway towns), got {}",
                self.block_size_m
            ));
        }
        // An organic town's outskirts bend with it (buildings rigidly, lots
        // per vertex), so only the highway style and uneven ground refuse them.
        let plain = self.road_style != RoadStyle::Highway
            && self.terrain != TerrainKind::Field
            && self.hills_m == 0.0
            && self.road_grade_m == 0.0
            && self.loop_corner_radius_m == 0.0
            && !self.ramps;
        if self.outskirts && !plain {
            return Err(format!(
                "outskirts: needs a level grid or organic town with square corners and no ramps \
                 (road_style = \"grid\" or \"organic\", terrain grass or dry, hills_m = 0, road_grade_m = 0, \
                 loop_corner_radius_m = 0, ramps = false); got road_style = {:?}, terrain = {:?}, \
                 hills_m = {}, road_grade_m = {}, loop_corner_radius_m = {}, ramps = {}",
                self.road_style,
                self.terrain,
                self.hills_m,
                self.road_grade_m,
                self.loop_corner_radius_m,
                self.ramps
            ));
        }
        self.validate_loop_corners()?;
        // Last: its message may name other keys (sidewalks, ramps).
        super::parking::validate(self)?;
        let [lo, hi] = self.floors;
        if !(1 <= lo && lo <= hi && hi <= 12) {
            return Err(format!("floors: need 1 ≤ min ≤ max ≤ 12, got [{lo}, {hi}]"));
        }
        let [lo, hi] = self.tower_floors;
        if !(8 <= lo && lo <= hi && hi <= 60) {
            return Err(format!(
                "tower_floors: need 8 ≤ min ≤ max ≤ 60, got [{lo}, {hi}]"
            ));
        }
        Ok(())
    }

    /// Largest `loop_corner_radius_m`: the straight from the arc's end to
    /// the next junction keeps room for a queue (half the smallest block).
    pub fn max_loop_corner_radius_m(&self) -> f64 {
        self.block_size_m - self.min_block_size_m() / 2.0
    }

    fn validate_loop_corners(&self) -> Result<(), String> {
        let r = self.loop_corner_radius_m;
        if r == 0.0 {
            return Ok(());
        }
        let (lo, hi) = (2.0 * self.road_width_m(), self.max_loop_corner_radius_m());
        if !(r.is_finite() && r >= lo && r <= hi) {
            return Err(format!(
                "loop_corner_radius_m: must be 0 or in [{lo}, {hi}], got {r}"
            ));
        }
        let blocks = self.extent_m.map(|e| (e / self.block_size_m).round());
        if self.sidewalks || self.ramps || blocks[0] < 2.0 || blocks[1] < 2.0 {
            return Err(
                "loop_corner_radius_m: needs sidewalks = false, no ramps and 2 × 2 blocks or more"
                    .into(),
            );
        }
        Ok(())
    }
}

/// Parses and validates town text; errors name `path` and the field.
pub fn parse_town_str(text: &str, path: &Path) -> Result<TownDesc, String> {
    let de = toml::Deserializer::new(text);
    let desc: TownDesc = serde_path_to_error::deserialize(de).map_err(|e| {
        let (msg, pos) = crate::scene::load::toml_error(text, e.inner());
        let at = pos.map_or(String::new(), |(line, col)| format!(":{line}:{col}"));
        match e.path().to_string() {
            key if key == "." => format!("{}{at}: {msg}", path.display()),
            key => format!("{}{at}: {key}: {msg}", path.display()),
        }
    })?;
    desc.validate()
        .map_err(|m| format!("{}: {m}", path.display()))?;
    Ok(desc)
}

/// Reads, parses and validates a town file.
pub fn load_town(path: &Path) -> Result<TownDesc, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("{}: cannot read town file: {e}", path.display()))?;
    parse_town_str(&text, path)
}
