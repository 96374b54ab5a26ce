//! Scene descriptions: every shipped scene loads and builds, OBJ/MTL and
//! inline meshes, textures and skies, and bad input named by file and key.

#[path = "../common/mod.rs"]
mod common;

mod bad_input;
mod inline_mesh;
mod instancing;
mod mtl_values;
mod obj_polygons;
mod sky_bad_input;
mod texture_desc;
mod validate;
