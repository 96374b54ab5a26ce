//! Orthonormal frames from a single unit vector.
//!
//! Branchless construction of Duff et al. 2017, "Building an Orthonormal Basis,
//! Revisited" (JCGT 6(1)), as used by pbrt-v4 `CoordinateSystem` (§3.3.3).

use glam::Vec3;

/// A right-handed orthonormal basis (x, y, z); `z` is usually the shading normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// First tangent.
    pub x: Vec3,
    /// Second tangent (`z × x`).
    pub y: Vec3,
    /// Normal axis.
    pub z: Vec3,
}

impl Frame {
    /// Frame whose z axis is `n` (must be unit length); tangents are continuous
    /// except across the n.z = 0 sign flip.
    #[inline]
    pub fn from_z(n: Vec3) -> Frame {
        // copysign instead of a branch on n.z (Duff et al. listing 3).
        let sign = 1.0f32.copysign(n.z);
        let a = -1.0 / (sign + n.z);
        let b = n.x * n.y * a;
        let x = Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
        let y = Vec3::new(b, sign + n.y * n.y * a, -n.y);
        Frame { x, y, z: n }
    }

    /// World (or parent-space) vector → coordinates in this frame.
    #[inline]
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.x), v.dot(self.y), v.dot(self.z))
    }

    /// Coordinates in this frame → world (or parent-space) vector.
    #[inline]
    pub fn from_local(&self, v: Vec3) -> Vec3 {
        self.x * v.x + self.y * v.y + self.z * v.z
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_is_orthonormal_and_round_trips() {
        let normals = [
            Vec3::Z,
            -Vec3::Z,
            Vec3::X,
            Vec3::new(0.3, -0.4, 0.5).normalize(),
            Vec3::new(-1e-4, 2e-4, -1.0).normalize(),
            Vec3::new(0.6, 0.8, 0.0),
        ];
        for n in normals {
            let f = Frame::from_z(n);
            assert!((f.x.length() - 1.0).abs() < 1e-5);
            assert!((f.y.length() - 1.0).abs() < 1e-5);
            assert!(f.x.dot(f.y).abs() < 1e-5);
            assert!(f.x.dot(f.z).abs() < 1e-5);
            assert!(f.y.dot(f.z).abs() < 1e-5);
            // Right-handed: x × y = z.
            assert!((f.x.cross(f.y) - f.z).length() < 1e-5, "n = {n}");
            let v = Vec3::new(0.2, -0.7, 0.4);
            assert!((f.from_local(f.to_local(v)) - v).length() < 1e-5);
            assert!((f.to_local(n) - Vec3::Z).length() < 1e-5);
        }
    }
}
