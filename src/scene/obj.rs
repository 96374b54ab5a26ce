//! OBJ import through tobj (placeholder).
