//! Microfacet-based normal mapping: Schüssler, Heitz, Hanika and Dachsbacher
//! 2017, "Microfacet-based Normal Mapping for Robust Monte Carlo Path
//! Tracing" (ACM TOG 36(6), SIGGRAPH Asia).
//!
//! A perturbed normal ωp (bump, interpolated normal) is not used as the
//! shading frame. The macro-surface instead becomes a right-angled V-groove
//! microsurface of two facets: ωp, carrying the material's BSDF (`Facet`),
//! and ωt ⊥ ωp, a perfect mirror, sized so that the groove's mean normal is
//! the geometric one. Per unit of macro-surface the facets' areas are cos θp
//! and sin θp, so the projected areas towards ω are
//! a_p(ω) = cos θp ⟨ω, ωp⟩⁺ and a_t(ω) = sin θp ⟨ω, ωt⟩⁺; a ray from ω hits
//! ωp first with probability λp = a_p/(a_p + a_t), and a direction leaving
//! ωp escapes with probability G1(ω) = min(1, ⟨ω, z⟩⁺/(a_p + a_t)).
//! Light reaching ωt is mirrored onto ωp; light leaving ωp and blocked is
//! mirrored by ωt out of the groove (a right-angled groove returns it
//! upward). Those four paths are all the paths of this microsurface, so
//! `eval` sums them exactly (the paper's explicit evaluation, with its
//! fourth, ωt → ωp → ωt, term) and `sample` follows one of them — the
//! paper's random walk — with the matching pdf. Energy is conserved: a
//! white Lambertian facet reflects everything (sampling weight exactly the
//! albedo), with no black or bright seams and no light below the geometric
//! surface.
//!
//! Directions are in the geometric normal's frame (z = n_geo, `wo` above).
//! A normal pointing away from `wo` (⟨wo, ωp⟩ below 0.1 ⟨wo, z⟩) is bent
//! towards z until it does not, so the facet always faces the viewer; the
//! normal's own tilt is limited to 72°.

use glam::{Vec2, Vec3, Vec4};

use super::{coat, conductor, lambert, BsdfSample, CoatBase};
use crate::sampling::Frame;

/// The BSDF on the ωp facet: a reflection-only model without delta lobes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Facet {
    /// Lambertian, as `Bsdf::Lambert`.
    Lambert {
        /// Reflectance per channel in [0, 1].
        albedo: Vec3,
    },
    /// Rough GGX conductor, as `Bsdf::Conductor`.
    Conductor {
        /// Real part of the complex IOR per channel.
        eta: Vec3,
        /// Imaginary part per channel.
        k: Vec3,
        /// GGX alpha (not effectively smooth).
        alpha: f32,
    },
    /// A rough coat over a rough base, as `Bsdf::Coated`.
    Coated {
        /// The base.
        base: CoatBase,
        /// Coat IOR.
        eta: f32,
        /// Coat GGX alpha (not effectively smooth).
        alpha: f32,
    },
}

impl Facet {
    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        match *self {
            Facet::Lambert { albedo } => lambert::eval(albedo, wo, wi),
            Facet::Conductor { eta, k, alpha } => conductor::eval(eta, k, alpha, wo, wi),
            Facet::Coated { base, eta, alpha } => coat::eval(&base, eta, alpha, wo, wi),
        }
    }
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        match *self {
            Facet::Lambert { .. } => lambert::pdf(wo, wi),
            Facet::Conductor { alpha, .. } => conductor::pdf(alpha, wo, wi),
            Facet::Coated { base, eta, alpha } => coat::pdf(&base, eta, alpha, wo, wi),
        }
    }
    fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        match *self {
            Facet::Lambert { albedo } => lambert::sample(albedo, wo, u),
            Facet::Conductor { eta, k, alpha } => conductor::sample(eta, k, alpha, wo, u),
            Facet::Coated { base, eta, alpha } => coat::sample(&base, eta, alpha, wo, u_lobe, u),
        }
    }
    /// A rough colour for debug views (as `Bsdf::albedo_hint`).
    pub fn albedo_hint(&self) -> Vec3 {
        match *self {
            Facet::Lambert { albedo } => albedo,
            Facet::Conductor { eta, k, .. } => super::fresnel::fr_complex_rgb(1.0, eta, k),
            Facet::Coated { base, .. } => base.albedo_hint(),
        }
    }
}

/// Smallest cosine of the perturbed normal with the geometric one (72°).
const MIN_COS: f32 = 0.3;
/// ⟨wo, ωp⟩ is kept at least this fraction of ⟨wo, z⟩.
const MIN_FACING: f32 = 0.1;

/// The groove seen from one `wo`.
struct Groove {
    wp: Vec3,
    wt: Vec3,
    cos_p: f32,
    sin_p: f32,
    frame: Frame,
}

/// `wp` moved towards z until ⟨a, wp⟩ ≥ `target` (a.z > target): the
/// normalised (1 − t)·wp + t·z whose unnormalised dot is `target`.
fn bend(wp: Vec3, a: Vec3, target: f32) -> Vec3 {
    let d = a.dot(wp);
    if d >= target {
        return wp;
    }
    let t = (target - d) / (a.z - d);
    (wp * (1.0 - t) + Vec3::Z * t).normalize()
}

impl Groove {
    fn new(wp: Vec3, wo: Vec3) -> Groove {
        let wp = bend(wp.normalize(), Vec3::Z, MIN_COS);
        let wp = bend(wp, wo, MIN_FACING * wo.z);
        let cos_p = wp.z.min(1.0);
        // From ωp's horizontal part, not √(1 − cos²): near z that
        // difference cancels to a few bits, and ωt built on it was far
        // from unit length (its mirror then lengthened directions).
        let sin_p = wp.x.hypot(wp.y);
        // ωt lies in the plane of z and ωp, perpendicular to ωp, facing
        // up: (z − ωp cos θp) / sin θp, its z component cos² + sin² − cos²
        // taken as sin θp directly.
        let wt = if sin_p > 1e-6 {
            let k = -cos_p / sin_p;
            Vec3::new(wp.x * k, wp.y * k, sin_p)
        } else {
            Vec3::X
        };
        Groove {
            wp,
            wt,
            cos_p,
            sin_p,
            frame: Frame::from_z(wp),
        }
    }
    fn proj(&self, w: Vec3) -> (f32, f32) {
        (
            self.cos_p * w.dot(self.wp).max(0.0),
            self.sin_p * w.dot(self.wt).max(0.0),
        )
    }
    /// Probability that a ray from `w` meets ωp first.
    fn lambda_p(&self, w: Vec3) -> f32 {
        let (ap, at) = self.proj(w);
        if ap + at > 0.0 {
            ap / (ap + at)
        } else {
            0.0
        }
    }
    /// Probability that a direction leaving ωp escapes.
    fn g1(&self, w: Vec3) -> f32 {
        let (ap, at) = self.proj(w);
        if w.z <= 0.0 || ap + at <= 0.0 {
            0.0
        } else {
            (w.z / (ap + at)).min(1.0)
        }
    }
    /// The mirror image of `w` in ωt.
    fn mirror(&self, w: Vec3) -> Vec3 {
        w - self.wt * (2.0 * w.dot(self.wt))
    }
    /// Σ over the four paths of weight(path) · q(facet in, facet out), with
    /// q the facet's f·cos (eval) or its pdf.
    fn sum<T, F>(&self, wo: Vec3, wi: Vec3, zero: T, q: F) -> T
    where
        T: Copy + std::ops::Add<Output = T> + std::ops::Mul<f32, Output = T>,
        F: Fn(Vec3, Vec3) -> T,
    {
        let lp = self.lambda_p(wo);
        let (wo_m, wi_m) = (self.mirror(wo), self.mirror(wi));
        let (g_i, g_im) = (self.g1(wi), 1.0 - self.g1(wi_m));
        let mut s = zero;
        for (lam, wf) in [(lp, wo), (1.0 - lp, wo_m)] {
            if lam <= 0.0 {
                continue;
            }
            let a = self.frame.to_local(wf);
            if g_i > 0.0 {
                s = s + q(a, self.frame.to_local(wi)) * (lam * g_i);
            }
            if g_im > 0.0 && wi_m.dot(self.wp) > 0.0 {
                s = s + q(a, self.frame.to_local(wi_m)) * (lam * g_im);
            }
        }
        s
    }
}

impl Groove {
    /// f(wo, wi) and the pdf of `wi` together: one walk over the four
    /// paths with the facet's f·cos in xyz and its pdf in w (each lane's
    /// arithmetic is that of the separate sums, so the bits are theirs).
    fn eval_pdf(&self, facet: &Facet, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        let s = self.sum(wo, wi, Vec4::ZERO, |a, b| {
            (facet.eval(a, b) * b.z.max(0.0)).extend(facet.pdf(a, b))
        });
        (s.truncate() / wi.z, s.w)
    }
}

/// f(wo, wi) of the normal-mapped surface (geometric frame).
pub fn eval(facet: &Facet, wp: Vec3, wo: Vec3, wi: Vec3) -> Vec3 {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return Vec3::ZERO;
    }
    let g = Groove::new(wp, wo);
    let s = g.sum(wo, wi, Vec3::ZERO, |a, b| facet.eval(a, b) * b.z.max(0.0));
    s / wi.z
}

/// [`eval`] and [`pdf`] at once, the groove built once (next-event
/// estimation needs both for every light sample it keeps).
pub fn eval_pdf(facet: &Facet, wp: Vec3, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return (Vec3::ZERO, 0.0);
    }
    Groove::new(wp, wo).eval_pdf(facet, wo, wi)
}

/// Pdf of [`sample`] per solid angle.
pub fn pdf(facet: &Facet, wp: Vec3, wo: Vec3, wi: Vec3) -> f32 {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return 0.0;
    }
    let g = Groove::new(wp, wo);
    g.sum(wo, wi, 0.0, |a, b| facet.pdf(a, b))
}

/// Follows one path of the groove: the first facet by λp (`u_lobe`), the
/// facet's own sample, then escape or the mirror by G1 (the low bits of
/// the rescaled `u_lobe`).
pub fn sample(facet: &Facet, wp: Vec3, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
    if wo.z <= 0.0 {
        return None;
    }
    let g = Groove::new(wp, wo);
    let lp = g.lambda_p(wo);
    let (wf, v) = if u_lobe < lp {
        (wo, u_lobe / lp)
    } else {
        (g.mirror(wo), (u_lobe - lp) / (1.0 - lp))
    };
    let v = v.clamp(0.0, 1.0 - f32::EPSILON);
    let s = facet.sample(g.frame.to_local(wf), v, u)?;
    if s.delta || s.wi.z <= 0.0 {
        return None;
    }
    let w = g.frame.from_local(s.wi);
    let v2 = (v * 4096.0).fract();
    let wi = if v2 < g.g1(w) { w } else { g.mirror(w) };
    if wi.z <= 0.0 {
        return None;
    }
    let (f, pdf) = g.eval_pdf(facet, wo, wi);
    if pdf <= 0.0 {
        return None;
    }
    Some(BsdfSample {
        wi,
        f,
        pdf,
        delta: false,
    })
}
