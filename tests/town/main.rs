//! The procedural towns: generation, terrain, grades, highway loop, ramps,
//! overpass, traffic and signals, street furniture, ground truth of town
//! frames, OBJ export and the town command line.

#[path = "../common/mod.rs"]
mod common;

mod cli;
mod drives;
mod export;
mod furniture;
mod generation;
mod grade;
mod gt;
mod highway_loop;
mod junctions;
mod long_turns;
mod median;
mod organic;
mod overpass;
mod parking;
mod parking_lane;
mod ramps;
mod riders;
mod signals;
mod terrain;
mod traffic;
mod traffic_motion;
mod underpass;
