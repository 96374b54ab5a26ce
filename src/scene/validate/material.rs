//! The `[[material]]` checks: names (no '/', reserved for OBJ materials),
//! textures (not on emitters) and each kind's parameters.

use crate::scene::desc::{MaterialDesc, MaterialKindDesc};
use crate::scene::load::SceneError;
use crate::scene::ranges::V;

impl V<'_> {
    /// `[[material]]` number `i`: its name, texture and kind parameters.
    pub(super) fn material(&self, i: usize, m: &MaterialDesc) -> Result<(), SceneError> {
        let k = |f: &str| format!("material[{i}].{f}");
        if m.name.is_empty() || m.name.contains('/') {
            return Err(self.err(
                k("name"),
                format!(
                    "\"{}\": names must be non-empty without '/' (reserved for OBJ materials)",
                    m.name
                ),
            ));
        }
        if let Some(t) = &m.texture {
            if matches!(m.kind, MaterialKindDesc::Emissive { .. }) {
                return Err(self.err(k("texture"), "emissive materials take no texture"));
            }
            self.range(&k("texture.scale"), &[t.scale], 1e-3, 1e3)?;
            self.range(&k("texture.bump"), &[t.bump], 0.0, 4.0)?;
        }
        match &m.kind {
            MaterialKindDesc::Diffuse { albedo } => self.range(&k("albedo"), albedo, 0.0, 1.0),
            MaterialKindDesc::Conductor {
                preset,
                eta,
                k: kk,
                roughness,
            } => {
                self.range(&k("roughness"), &[*roughness], 0.0, 1.0)?;
                match (preset, eta, kk) {
                    (Some(_), None, None) => Ok(()),
                    (None, Some(eta), Some(kk)) => {
                        self.positive(&k("eta"), eta)?;
                        self.range(&k("k"), kk, 0.0, f64::MAX)
                    }
                    _ => Err(self.err(k("preset"), "give either `preset` or both `eta` and `k`")),
                }
            }
            MaterialKindDesc::Dielectric {
                ior,
                roughness,
                tint,
            } => {
                self.positive(&k("ior"), &[*ior])?;
                self.range(&k("roughness"), &[*roughness], 0.0, 1.0)?;
                self.range(&k("tint"), tint, 0.0, 1.0)
            }
            MaterialKindDesc::Emissive { radiance, .. } => {
                self.range(&k("radiance"), radiance, 0.0, f64::MAX)
            }
            MaterialKindDesc::Coated {
                albedo,
                preset,
                eta,
                k: kk,
                base_roughness,
                coat_ior,
                coat_roughness,
            } => {
                self.range(&k("coat_ior"), &[*coat_ior], 1.0 + 1e-6, 3.0)?;
                self.range(&k("coat_roughness"), &[*coat_roughness], 0.0, 1.0)?;
                self.range(&k("base_roughness"), &[*base_roughness], 0.0, 1.0)?;
                match (albedo, preset, eta, kk) {
                    (Some(a), None, None, None) => self.range(&k("albedo"), a, 0.0, 1.0),
                    (None, Some(_), None, None) => Ok(()),
                    (None, None, Some(eta), Some(kk)) => {
                        self.positive(&k("eta"), eta)?;
                        self.range(&k("k"), kk, 0.0, f64::MAX)
                    }
                    _ => Err(self.err(
                        k("albedo"),
                        "give exactly one base: `albedo`, `preset`, or both `eta` and `k`",
                    )),
                }
            }
        }
    }
}
