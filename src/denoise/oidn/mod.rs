//! Intel Open Image Denoise as the image denoiser (`[render] denoiser =
//! "oidn"`, `--denoiser oidn`): its ray-tracing filter ("RT") on a view's
//! radiance, guided by the view's first-surface albedo and normal, which
//! are averages over each pixel's samples and so taken as clean
//! (`cleanAux`); `"blend"` averages its image with parallax's filters'
//! (`guide::denoise_view`). The library is opened at run time
//! (`library.rs`); the CPU device runs on the render's thread count, which
//! does not change its bytes (the test below checks 1 against 2 threads).

mod library;

use std::ffi::CString;
use std::sync::OnceLock;

use glam::Vec3;

use super::{DepthGuide, SurfaceAux, ViewInputs, Widths};
use crate::film::Film;

pub use library::ENV;
use library::{device_error, Api, Device, Filter, DEVICE_CPU, FORMAT_FLOAT3};

/// `OIDN_QUALITY_HIGH`: the final-frame networks.
const QUALITY_HIGH: i32 = 6;

/// A rendered view denoised the OIDN way: its fog light (the first-scatter
/// part, where the scene has a medium) by parallax's own filter, which
/// knows the medium's opacity along each pixel, then the whole radiance
/// by OIDN, guided by the view's first surfaces (`aux`). Err: OIDN failed.
pub(super) fn denoise_view(
    film: &mut Film,
    inputs: &ViewInputs,
    guide: &DepthGuide<'_>,
    widths: &Widths,
    aux: SurfaceAux<'_>,
) -> Result<(), String> {
    if inputs.has_first_scatter() {
        super::first_scatter::filter_first_scatter(film, inputs, guide, widths);
    }
    let (w, h) = (film.width, film.height);
    let threads = rayon::current_num_threads();
    denoise(&mut film.rgb, aux.albedo, aux.normal, w, h, threads)
}

/// Checks that the library opens and its CPU device runs on this machine
/// (before any work is done); Err says what is missing and how to install it.
/// Tried once per process: a dataset asks before every frame.
pub fn check() -> Result<(), String> {
    static CHECKED: OnceLock<Result<(), String>> = OnceLock::new();
    CHECKED
        .get_or_init(|| OwnedDevice::new(library::api()?, 1).map(drop))
        .clone()
}

/// Denoises `rgb` (linear radiance, `width × height` row-major) in place,
/// guided by `albedo` (clamped to [0, 1]) and unit `normal` (any frame;
/// zero where unknown), on `threads` CPU threads.
pub fn denoise(
    rgb: &mut [Vec3],
    albedo: &[Vec3],
    normal: &[Vec3],
    width: usize,
    height: usize,
    threads: usize,
) -> Result<(), String> {
    let n = width * height;
    assert!(
        rgb.len() == n && albedo.len() == n && normal.len() == n,
        "OIDN inputs' size does not match the image"
    );
    let api = library::api()?;
    let device = OwnedDevice::new(api, threads)?;
    let albedo: Vec<Vec3> = albedo
        .iter()
        .map(|a| a.clamp(Vec3::ZERO, Vec3::ONE))
        .collect();
    let normal: Vec<Vec3> = normal
        .iter()
        .map(|v| v.clamp(-Vec3::ONE, Vec3::ONE))
        .collect();
    let color: Vec<Vec3> = rgb.iter().map(|c| c.max(Vec3::ZERO)).collect();
    let filter = OwnedFilter::new(&device, "RT")?;
    filter.image("color", color.as_ptr(), width, height);
    filter.image("albedo", albedo.as_ptr(), width, height);
    filter.image("normal", normal.as_ptr(), width, height);
    filter.image("output", rgb.as_mut_ptr(), width, height);
    filter.set_bool("hdr", true);
    filter.set_bool("cleanAux", true);
    filter.set_int("quality", QUALITY_HIGH);
    // SAFETY: every image the filter reads or writes outlives this call.
    unsafe {
        (api.commit_filter)(filter.raw);
        (api.execute_filter)(filter.raw);
    }
    device.error()
}

/// A CPU device, released on drop.
struct OwnedDevice {
    api: &'static Api,
    raw: Device,
}

impl OwnedDevice {
    fn new(api: &'static Api, threads: usize) -> Result<OwnedDevice, String> {
        // SAFETY: plain calls of the C API on a device this struct owns.
        let raw = unsafe { (api.new_device)(DEVICE_CPU) };
        if raw.is_null() {
            return Err("Open Image Denoise: no CPU device".into());
        }
        let device = OwnedDevice { api, raw };
        unsafe {
            (api.set_device_int)(raw, c"numThreads".as_ptr(), threads.max(1) as i32);
            // Rayon owns the cores' affinity.
            (api.set_device_bool)(raw, c"setAffinity".as_ptr(), false);
            (api.commit_device)(raw);
        }
        device.error()?;
        Ok(device)
    }

    fn error(&self) -> Result<(), String> {
        device_error(self.api, self.raw).map_or(Ok(()), Err)
    }
}

impl Drop for OwnedDevice {
    fn drop(&mut self) {
        // SAFETY: released once, after every filter of it.
        unsafe { (self.api.release_device)(self.raw) }
    }
}

/// A filter of a device, released on drop.
struct OwnedFilter<'d> {
    device: &'d OwnedDevice,
    raw: Filter,
}

impl<'d> OwnedFilter<'d> {
    fn new(device: &'d OwnedDevice, kind: &str) -> Result<OwnedFilter<'d>, String> {
        let kind = CString::new(kind).expect("filter type has no NUL");
        // SAFETY: a live device; the type string outlives the call.
        let raw = unsafe { (device.api.new_filter)(device.raw, kind.as_ptr()) };
        device.error()?;
        Ok(OwnedFilter { device, raw })
    }

    /// Shares `px` (`width × height` float3 pixels, packed rows) as the
    /// image `name`; OIDN writes only the one named "output".
    fn image(&self, name: &str, px: *const Vec3, width: usize, height: usize) {
        let name = CString::new(name).expect("image name has no NUL");
        // SAFETY: Vec3 is three packed f32; the caller keeps `px` alive
        // (and, for "output", writable) until the filter has run.
        unsafe {
            (self.device.api.set_shared_filter_image)(
                self.raw,
                name.as_ptr(),
                px as *mut _,
                FORMAT_FLOAT3,
                width,
                height,
                0,
                0,
                0,
            )
        }
    }

    fn set_bool(&self, name: &str, value: bool) {
        let name = CString::new(name).expect("parameter name has no NUL");
        unsafe { (self.device.api.set_filter_bool)(self.raw, name.as_ptr(), value) }
    }

    fn set_int(&self, name: &str, value: i32) {
        let name = CString::new(name).expect("parameter name has no NUL");
        unsafe { (self.device.api.set_filter_int)(self.raw, name.as_ptr(), value) }
    }
}

impl Drop for OwnedFilter<'_> {
    fn drop(&mut self) {
        // SAFETY: released once, before its device.
        unsafe { (self.device.api.release_filter)(self.raw) }
    }
}
