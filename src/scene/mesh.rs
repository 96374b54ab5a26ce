//! Primitive tessellation (placeholder).
