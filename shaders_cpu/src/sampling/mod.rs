//! Sampling warps, local frames and MIS weights (shaders helper fills in).
