//! The Mitsuba 3 scene file, element by element (the mapping is in the
//! parent module's header). Numbers are printed with Rust's shortest
//! round-trip form; `spp`, `sampler` and `max_depth` are XML defaults a
//! caller may override (`mi.load_file(path, spp=…, sampler=…)`).

use std::fmt::Write as _;

use glam::{DAffine3, DMat3, DVec3, Vec3};

use super::MitsubaOptions;
use crate::light::Light;
use crate::scene::desc::{conductor_eta_k, MaterialDesc, MaterialKindDesc};
use shaders_cpu::medium::{Density, Medium};

/// Rotation of the baked sky map: Mitsuba's envmap local (x, y, z) with y up
/// to world (x, z, −y)… as columns: local x → world x, local y → world z,
/// local z → world −y (a proper rotation).
pub const ENVMAP_TO_WORLD: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]];

/// World direction of envmap-local direction `d` ([`ENVMAP_TO_WORLD`]).
pub fn envmap_to_world(d: DVec3) -> DVec3 {
    let m = DMat3::from_cols_array_2d(&ENVMAP_TO_WORLD);
    m * d
}

/// Below this perceptual roughness a GGX lobe is a smooth (delta) one in
/// parallax (`SMOOTH_ALPHA` = 1e-3 on α = roughness²).
const SMOOTH_ROUGHNESS: f64 = 0.0316;

/// Half-size of the medium's box across, metres (beyond any town).
const MEDIUM_HALF_WIDTH: f64 = 20_000.0;

/// A scene file being written.
pub struct Xml {
    out: String,
    medium_id: Option<&'static str>,
}

fn v(c: [f64; 3]) -> String {
    format!("{}, {}, {}", c[0], c[1], c[2])
}

fn v3(c: Vec3) -> String {
    format!("{}, {}, {}", c.x, c.y, c.z)
}

impl Xml {
    /// The header, integrator and sensor.
    pub fn new(origin_world: DVec3, opts: &MitsubaOptions) -> Xml {
        let mut out = String::new();
        let o = origin_world;
        let _ = writeln!(
            out,
            "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n\
             <!-- parallax export: render-space coordinates = world - ({}, {}, {}) -->\n\
             <scene version=\"3.0.0\">\n\
             \t<default name=\"spp\" value=\"{}\"/>\n\
             \t<default name=\"sampler\" value=\"independent\"/>\n\
             \t<default name=\"max_depth\" value=\"{}\"/>",
            o.x,
            o.y,
            o.z,
            opts.spp,
            opts.max_depth + 1
        );
        Xml {
            out,
            medium_id: None,
        }
        .sensor(origin_world, opts)
    }

    fn sensor(mut self, origin_world: DVec3, opts: &MitsubaOptions) -> Xml {
        let cam = opts.camera;
        let k = cam.intrinsics;
        let r = cam.world_from_camera;
        let c = cam.center_world - origin_world;
        // Mitsuba's camera looks down +z with +y up and +x to the image's
        // left; parallax's (OpenCV) has +x right and +y down.
        let (x, y, z) = (-r.x_axis, -r.y_axis, r.z_axis);
        let rows = [
            [x.x, y.x, z.x, c.x],
            [x.y, y.y, z.y, c.y],
            [x.z, y.z, z.z, c.z],
            [0.0, 0.0, 0.0, 1.0],
        ];
        let m: Vec<String> = rows.iter().flatten().map(|v| v.to_string()).collect();
        let _ = writeln!(
            self.out,
            "\t<sensor type=\"perspective\" id=\"camera\">\n\
             \t\t<float name=\"fov\" value=\"{}\"/>\n\
             \t\t<string name=\"fov_axis\" value=\"x\"/>\n\
             \t\t<float name=\"near_clip\" value=\"0.001\"/>\n\
             \t\t<float name=\"far_clip\" value=\"100000\"/>\n\
             \t\t<transform name=\"to_world\"><matrix value=\"{}\"/></transform>\n\
             \t\t<sampler type=\"$sampler\"><integer name=\"sample_count\" value=\"$spp\"/></sampler>\n\
             \t\t<film type=\"hdrfilm\">\n\
             \t\t\t<integer name=\"width\" value=\"{}\"/>\n\
             \t\t\t<integer name=\"height\" value=\"{}\"/>\n\
             \t\t\t<string name=\"pixel_format\" value=\"rgb\"/>\n\
             \t\t\t<rfilter type=\"box\"/>\n\
             \t\t</film>\n\
             \t\t<!--MEDIUM-->\n\
             \t</sensor>",
            k.hfov_rad().to_degrees(),
            m.join(" "),
            k.width,
            k.height
        );
        self
    }

    /// The BSDF of material `i` (id `m{i}`).
    pub fn bsdf(&mut self, i: usize, m: &MaterialDesc) {
        let name = &m.name;
        let ggx = |r: f64| {
            format!(
                "<string name=\"distribution\" value=\"ggx\"/><float name=\"alpha\" value=\"{}\"/>",
                r * r
            )
        };
        let body = match &m.kind {
            MaterialKindDesc::Diffuse { albedo } => two_sided(format!(
                "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"{}\"/></bsdf>",
                v(*albedo)
            )),
            MaterialKindDesc::Conductor {
                preset,
                eta,
                k,
                roughness,
            } => {
                let (eta, k) = conductor_eta_k(preset, eta, k);
                two_sided(conductor(eta, k, *roughness, &ggx))
            }
            MaterialKindDesc::Dielectric {
                ior,
                roughness,
                tint,
            } => {
                let common = format!(
                    "<float name=\"int_ior\" value=\"{ior}\"/><float name=\"ext_ior\" value=\"1\"/>\
                     <rgb name=\"specular_transmittance\" value=\"{}\"/>",
                    v(*tint)
                );
                if *roughness < SMOOTH_ROUGHNESS {
                    format!("<bsdf type=\"dielectric\">{common}</bsdf>")
                } else {
                    format!(
                        "<bsdf type=\"roughdielectric\">{common}{}</bsdf>",
                        ggx(*roughness)
                    )
                }
            }
            MaterialKindDesc::Coated {
                albedo: Some(albedo),
                coat_ior,
                coat_roughness,
                ..
            } => {
                let common = format!(
                    "<float name=\"int_ior\" value=\"{coat_ior}\"/><float name=\"ext_ior\" value=\"1\"/>\
                     <rgb name=\"diffuse_reflectance\" value=\"{}\"/>",
                    v(*albedo)
                );
                two_sided(if *coat_roughness < SMOOTH_ROUGHNESS {
                    format!("<bsdf type=\"plastic\">{common}</bsdf>")
                } else {
                    format!(
                        "<bsdf type=\"roughplastic\">{common}{}</bsdf>",
                        ggx(*coat_roughness)
                    )
                })
            }
            MaterialKindDesc::Coated {
                albedo: None,
                preset,
                eta,
                k,
                base_roughness,
                ..
            } => {
                let (eta, k) = conductor_eta_k(preset, eta, k);
                two_sided(conductor(eta, k, *base_roughness, &ggx))
            }
            MaterialKindDesc::Emissive { .. } => two_sided(
                "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0\"/></bsdf>".into(),
            ),
        };
        let body = body.replacen("<bsdf ", &format!("<bsdf id=\"m{i}\" "), 1);
        let _ = writeln!(self.out, "\t<!-- {name} -->\n\t{body}");
    }

    /// A PLY shape of material `material`, emitting `emission` if given.
    pub fn shape(&mut self, file: &str, material: usize, emission: Option<[f64; 3]>) {
        let _ = writeln!(
            self.out,
            "\t<shape type=\"ply\">\n\t\t<string name=\"filename\" value=\"{file}\"/>\n\
             \t\t<boolean name=\"face_normals\" value=\"{}\"/>\n\t\t<ref id=\"m{material}\"/>{}\n\t</shape>",
            !file.contains("_n"),
            area(emission)
        );
    }

    /// Opens the shape group of prototype `k` (id `p{k}`).
    pub fn begin_group(&mut self, k: usize) {
        let _ = writeln!(self.out, "\t<shape type=\"shapegroup\" id=\"p{k}\">");
    }

    /// Closes the open shape group.
    pub fn end_group(&mut self) {
        let _ = writeln!(self.out, "\t</shape>");
    }

    /// An instance of prototype `k` placed by `render_from_local`.
    pub fn instance(&mut self, k: usize, render_from_local: &DAffine3) {
        let (m, t) = (render_from_local.matrix3, render_from_local.translation);
        let _ = writeln!(
            self.out,
            "\t<shape type=\"instance\"><ref id=\"p{k}\"/><transform name=\"to_world\"><matrix value=\"{} {} {} {} {} {} {} {} {} {} {} {} 0 0 0 1\"/></transform></shape>",
            m.x_axis.x, m.y_axis.x, m.z_axis.x, t.x,
            m.x_axis.y, m.y_axis.y, m.z_axis.y, t.y,
            m.x_axis.z, m.y_axis.z, m.z_axis.z, t.z
        );
    }

    /// An analytic sphere.
    pub fn sphere(
        &mut self,
        c: Vec3,
        radius: f64,
        material: u32,
        emission: Option<([f64; 3], bool)>,
    ) {
        let _ = writeln!(
            self.out,
            "\t<shape type=\"sphere\">\n\t\t<point name=\"center\" value=\"{}\"/>\n\
             \t\t<float name=\"radius\" value=\"{radius}\"/>\n\t\t<ref id=\"m{material}\"/>{}\n\t</shape>",
            v3(c),
            area(emission.map(|e| e.0))
        );
    }

    /// A sun, point or spot light (render space).
    pub fn light(&mut self, l: &Light) {
        let text = match *l {
            Light::Sun {
                dir_to_sun,
                irradiance,
                ..
            } => format!(
                "<emitter type=\"directional\"><vector name=\"direction\" value=\"{}\"/>\
                 <rgb name=\"irradiance\" value=\"{}\"/></emitter>",
                v3(-dir_to_sun),
                v3(irradiance)
            ),
            Light::Point { p, intensity } => format!(
                "<emitter type=\"point\"><point name=\"position\" value=\"{}\"/>\
                 <rgb name=\"intensity\" value=\"{}\"/></emitter>",
                v3(p),
                v3(intensity)
            ),
            Light::Spot {
                p,
                dir,
                intensity,
                cos_inner,
                cos_outer,
            } => {
                let outer = (cos_outer as f64).clamp(-1.0, 1.0).acos().to_degrees();
                let inner = (cos_inner as f64)
                    .clamp(-1.0, 1.0)
                    .acos()
                    .to_degrees()
                    .min(outer);
                let up = if dir.z.abs() < 0.9 { Vec3::Z } else { Vec3::X };
                format!(
                    "<emitter type=\"spot\"><transform name=\"to_world\"><lookat origin=\"{}\" target=\"{}\" up=\"{}\"/></transform>\
                     <rgb name=\"intensity\" value=\"{}\"/><float name=\"cutoff_angle\" value=\"{outer}\"/>\
                     <float name=\"beam_width\" value=\"{inner}\"/></emitter>",
                    v3(p),
                    v3(p + dir),
                    v3(up),
                    v3(intensity)
                )
            }
        };
        let _ = writeln!(self.out, "\t{text}");
    }

    /// A constant sky (nothing when black).
    pub fn constant_sky(&mut self, le: Vec3) {
        if le != Vec3::ZERO {
            let _ = writeln!(
                self.out,
                "\t<emitter type=\"constant\"><rgb name=\"radiance\" value=\"{}\"/></emitter>",
                v3(le)
            );
        }
    }

    /// The baked sky map `file`.
    pub fn envmap(&mut self, file: &str) {
        let m = ENVMAP_TO_WORLD;
        let _ = writeln!(
            self.out,
            "\t<emitter type=\"envmap\"><string name=\"filename\" value=\"{file}\"/>\
             <transform name=\"to_world\"><matrix value=\"{} {} {} 0 {} {} {} 0 {} {} {} 0 0 0 0 1\"/></transform></emitter>",
            m[0][0], m[1][0], m[2][0], m[0][1], m[1][1], m[2][1], m[0][2], m[1][2], m[2][2]
        );
    }

    /// A homogeneous medium filling its z range in a null box; the camera
    /// (render-space centre `eye`) looks from inside it when it is in range.
    pub fn medium(&mut self, m: &Medium, eye: DVec3) {
        let Density::Homogeneous { sigma_t } = m.density else {
            return; // refused by `check`
        };
        let _ = writeln!(
            self.out,
            "\t<medium type=\"homogeneous\" id=\"fog\">\n\
             \t\t<float name=\"sigma_t\" value=\"{sigma_t}\"/>\n\
             \t\t<rgb name=\"albedo\" value=\"{}\"/>\n\
             \t\t<phase type=\"hg\"><float name=\"g\" value=\"{}\"/></phase>\n\t</medium>",
            v3(m.albedo),
            m.phase.g
        );
        let z0 = if m.z_min.is_finite() {
            m.z_min
        } else {
            eye.z - MEDIUM_HALF_WIDTH
        };
        let z1 = if m.z_max.is_finite() {
            m.z_max
        } else {
            eye.z + MEDIUM_HALF_WIDTH
        };
        let (cz, hz) = (0.5 * (z0 + z1), 0.5 * (z1 - z0));
        let _ = writeln!(
            self.out,
            "\t<shape type=\"cube\">\n\t\t<transform name=\"to_world\"><scale value=\"{MEDIUM_HALF_WIDTH}, {MEDIUM_HALF_WIDTH}, {hz}\"/>\
             <translate value=\"{}, {}, {cz}\"/></transform>\n\
             \t\t<bsdf type=\"null\"/>\n\t\t<ref name=\"interior\" id=\"fog\"/>\n\t</shape>",
            eye.x, eye.y
        );
        if (z0..=z1).contains(&eye.z) {
            self.medium_id = Some("fog");
        }
    }

    /// The finished file.
    pub fn finish(self) -> String {
        let medium = match self.medium_id {
            Some(id) => format!("<ref id=\"{id}\"/>"),
            None => String::new(),
        };
        let integrator = if self.medium_id.is_some() || self.out.contains("<medium ") {
            "volpath"
        } else {
            "path"
        };
        let out = self.out.replacen("<!--MEDIUM-->", &medium, 1);
        // The integrator goes first, after the defaults.
        let at = out.find("\t<sensor").unwrap_or(out.len());
        format!(
            "{}\t<integrator type=\"{integrator}\"><integer name=\"max_depth\" value=\"$max_depth\"/></integrator>\n{}</scene>\n",
            &out[..at],
            &out[at..]
        )
    }
}

fn two_sided(bsdf: String) -> String {
    format!("<bsdf type=\"twosided\">{bsdf}</bsdf>")
}

fn conductor(eta: [f64; 3], k: [f64; 3], roughness: f64, ggx: &dyn Fn(f64) -> String) -> String {
    let common = format!(
        "<rgb name=\"eta\" value=\"{}\"/><rgb name=\"k\" value=\"{}\"/>",
        v(eta),
        v(k)
    );
    if roughness < SMOOTH_ROUGHNESS {
        format!("<bsdf type=\"conductor\">{common}</bsdf>")
    } else {
        format!(
            "<bsdf type=\"roughconductor\">{common}{}</bsdf>",
            ggx(roughness)
        )
    }
}

fn area(emission: Option<[f64; 3]>) -> String {
    match emission {
        Some(le) => format!(
            "\n\t\t<emitter type=\"area\"><rgb name=\"radiance\" value=\"{}\"/></emitter>",
            v(le)
        ),
        None => String::new(),
    }
}
