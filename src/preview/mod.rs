//! Pictures a person can open: colour-coded ground-truth maps of a native
//! frame (`parallax preview`), and the drawing surface with a bitmap font that
//! the histogram plots share.

pub mod canvas;
