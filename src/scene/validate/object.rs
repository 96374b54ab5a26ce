//! The checks of one object's own fields (not references that depend on
//! instancing): semantic class, transform, repeats, material presence and
//! each shape's parameters.

use crate::scene::desc::{ObjectDesc, RepeatDesc, ScaleDesc, SceneDesc, ShapeDesc, TransformDesc};
use crate::scene::load::SceneError;
use crate::scene::mesh::{check_inline, MAX_COORD_M};
use crate::scene::ranges::V;
use crate::scene::semantic::{class_id, CLASSES};

impl V<'_> {
    /// Checks object `o` at key path `key`.
    pub(super) fn object(
        &self,
        key: &str,
        o: &ObjectDesc,
        desc: &SceneDesc,
    ) -> Result<(), SceneError> {
        let k = |f: &str| format!("{key}.{f}");
        if let Some(s) = &o.semantic {
            self.semantic(&k("semantic"), s)?;
        }
        self.transform(key, &o.transform)?;
        self.repeats(key, &o.repeat)?;
        let needs_material = !matches!(o.shape, ShapeDesc::Obj { .. } | ShapeDesc::Instance { .. });
        if needs_material && o.material.is_none() {
            return Err(self.err(k("material"), "missing material"));
        }
        self.shape(key, o, desc)
    }

    /// A known semantic class name.
    fn semantic(&self, key: &str, s: &str) -> Result<(), SceneError> {
        if class_id(s).is_none() {
            let known: Vec<&str> = CLASSES.iter().map(|c| c.name).collect();
            return Err(self.err(
                key,
                format!(
                    "unknown semantic class \"{s}\" (known: {})",
                    known.join(", ")
                ),
            ));
        }
        Ok(())
    }

    /// Translation within the coordinate limit, finite angles, positive scale.
    fn transform(&self, key: &str, t: &TransformDesc) -> Result<(), SceneError> {
        let k = |f: &str| format!("{key}.{f}");
        self.coord(&k("transform.translate"), &t.translate.unwrap_or_default())?;
        self.finite(
            &k("transform.rotate_deg"),
            &t.rotate_deg.unwrap_or_default(),
        )?;
        if let Some(s) = t.scale {
            self.positive(&k("transform.scale"), &s.axes())?;
            // A factor beyond the coordinate limit takes any shape beyond it.
            self.range(&k("transform.scale"), &s.axes(), 0.0, MAX_COORD_M)?;
        }
        Ok(())
    }

    /// Each repeat level: at least one copy, offset within the coordinate limit.
    fn repeats(&self, key: &str, repeat: &[RepeatDesc]) -> Result<(), SceneError> {
        for (r, level) in repeat.iter().enumerate() {
            if level.count == 0 {
                return Err(self.err(format!("{key}.repeat[{r}].count"), "must be ≥ 1"));
            }
            self.coord(&format!("{key}.repeat[{r}].offset"), &level.offset)?;
        }
        Ok(())
    }

    /// The parameters of the object's shape.
    fn shape(&self, key: &str, o: &ObjectDesc, desc: &SceneDesc) -> Result<(), SceneError> {
        let k = |f: &str| format!("{key}.{f}");
        match &o.shape {
            ShapeDesc::Quad { size } => self.length(&k("size"), size),
            ShapeDesc::Box { size } => self.length(&k("size"), size),
            ShapeDesc::Sphere { radius } => {
                self.length(&k("radius"), &[*radius])?;
                self.sphere_transform(key, &o.transform)
            }
            ShapeDesc::Cylinder {
                radius,
                height,
                segments,
                ..
            } => {
                self.length(&k("radius"), &[*radius])?;
                self.length(&k("height"), &[*height])?;
                self.count(&k("segments"), *segments, 3)
            }
            ShapeDesc::Ellipsoid {
                radii,
                segments,
                rings,
            } => {
                self.length(&k("radii"), radii)?;
                self.count(&k("segments"), *segments, 3)?;
                self.count(&k("rings"), *rings, 2)
            }
            ShapeDesc::Obj { file } if file.is_empty() => {
                Err(self.err(k("file"), "empty file name"))
            }
            ShapeDesc::Obj { .. } => Ok(()),
            ShapeDesc::Mesh {
                positions,
                normals,
                triangles,
            } => {
                check_inline(positions, normals, triangles).map_err(|(field, msg)| match &o.name {
                    Some(name) => self.err(k(field), format!("mesh \"{name}\": {msg}")),
                    None => self.err(k(field), msg),
                })
            }
            ShapeDesc::Instance { prefab, .. } => {
                if o.material.is_some() {
                    return Err(self.err(
                        k("material"),
                        "not allowed on an instance (use material_map)",
                    ));
                }
                if !desc.prefabs.iter().any(|p| &p.name == prefab) {
                    return Err(self.err(k("prefab"), format!("unknown prefab \"{prefab}\"")));
                }
                Ok(())
            }
        }
    }

    /// A sphere stays a sphere: translated and scaled uniformly only.
    fn sphere_transform(&self, key: &str, t: &TransformDesc) -> Result<(), SceneError> {
        if t.rotate_deg.is_some_and(|r| r != [0.0; 3]) {
            return Err(self.err(
                format!("{key}.transform.rotate_deg"),
                "a sphere may only be translated and scaled uniformly",
            ));
        }
        if let Some(ScaleDesc::Axes([a, b, c])) = t.scale {
            if a != b || b != c {
                return Err(self.err(
                    format!("{key}.transform.scale"),
                    "a sphere may only be scaled uniformly",
                ));
            }
        }
        Ok(())
    }

    /// A tessellation count in [min, 65536].
    fn count(&self, key: &str, n: u32, min: u32) -> Result<(), SceneError> {
        if n < min || n > 1 << 16 {
            return Err(self.err(key, format!("must be in [{min}, 65536], got {n}")));
        }
        Ok(())
    }
}
