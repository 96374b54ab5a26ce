//! The output writers: file formats read back bit-exact and the non-native
//! layouts of a rendered frame.

#[path = "../common/mod.rs"]
mod common;

mod layouts;
mod mitsuba;
mod roundtrip;
