//! TEMPORARY stub (replaced by the shaders helper at merge).
use glam::{Vec2, Vec3};
/// Frame.
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    /// x.
    pub x: Vec3,
    /// y.
    pub y: Vec3,
    /// z.
    pub z: Vec3,
}
impl Frame {
    /// From z.
    pub fn from_z(z: Vec3) -> Self {
        let (x, y) = z.any_orthonormal_pair();
        Frame { x, y, z }
    }
    /// To local.
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.x), v.dot(self.y), v.dot(self.z))
    }
    /// From local.
    pub fn from_local(&self, v: Vec3) -> Vec3 {
        self.x * v.x + self.y * v.y + self.z * v.z
    }
}
/// Cone.
pub fn sample_uniform_cone(_u: Vec2, _c: f32) -> Vec3 {
    unimplemented!()
}
/// Cone pdf.
pub fn uniform_cone_pdf(c: f32) -> f32 {
    1.0 / (2.0 * std::f32::consts::PI * (1.0 - c))
}
/// Lum.
pub fn luminance(c: Vec3) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}
/// Tri.
pub fn sample_uniform_triangle(_u: Vec2) -> [f32; 3] {
    unimplemented!()
}
/// PH.
pub fn power_heuristic(nf: f32, fp: f32, ng: f32, gp: f32) -> f32 {
    let (f, g) = (nf * fp, ng * gp);
    if f.is_infinite() {
        return 1.0;
    }
    if f == 0.0 && g == 0.0 {
        return 0.0;
    }
    f * f / (f * f + g * g)
}
