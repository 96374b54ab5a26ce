//! Finding and opening Intel Open Image Denoise (OIDN 2.x) at run time.
//! The library is not in Debian 12's apt; PyPI's `pyoidn` wheel ships it
//! (`pip install pyoidn`). Opening it when asked, instead of linking it,
//! keeps the build and the default render free of it.
//!
//! Where it is looked for, in order: `PARALLAX_OIDN` (the library file or
//! its directory), the system loader's path (`libOpenImageDenoise.so.2`),
//! then the `pyoidn` package of `python3` (asked where it is, not imported).

use std::ffi::{c_char, c_int, c_void, CStr};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use libloading::Library;

/// The environment variable naming the library file or its directory.
pub const ENV: &str = "PARALLAX_OIDN";
/// The library's file name (major version 2: the C API below).
pub const SONAME: &str = "libOpenImageDenoise.so.2";

pub type Device = *mut c_void;
pub type Filter = *mut c_void;

/// `OIDN_DEVICE_TYPE_CPU`.
pub const DEVICE_CPU: c_int = 1;
/// `OIDN_FORMAT_FLOAT3`.
pub const FORMAT_FLOAT3: c_int = 3;

/// The entry points parallax calls (OIDN 2.x's C API, `oidn.h`).
pub struct Api {
    pub new_device: unsafe extern "C" fn(c_int) -> Device,
    pub set_device_int: unsafe extern "C" fn(Device, *const c_char, c_int),
    pub set_device_bool: unsafe extern "C" fn(Device, *const c_char, bool),
    pub commit_device: unsafe extern "C" fn(Device),
    pub get_device_error: unsafe extern "C" fn(Device, *mut *const c_char) -> c_int,
    pub release_device: unsafe extern "C" fn(Device),
    pub new_filter: unsafe extern "C" fn(Device, *const c_char) -> Filter,
    #[allow(clippy::type_complexity)]
    pub set_shared_filter_image: unsafe extern "C" fn(
        Filter,
        *const c_char,
        *mut c_void,
        c_int,
        usize,
        usize,
        usize,
        usize,
        usize,
    ),
    pub set_filter_bool: unsafe extern "C" fn(Filter, *const c_char, bool),
    pub set_filter_int: unsafe extern "C" fn(Filter, *const c_char, c_int),
    pub commit_filter: unsafe extern "C" fn(Filter),
    pub execute_filter: unsafe extern "C" fn(Filter),
    pub release_filter: unsafe extern "C" fn(Filter),
    // Keeps the entry points valid; dropped last.
    _lib: Library,
}

/// The library, opened once per process. Err: every place looked in, and
/// how to install it.
pub fn api() -> Result<&'static Api, String> {
    static API: OnceLock<Result<Api, String>> = OnceLock::new();
    API.get_or_init(open).as_ref().map_err(Clone::clone)
}

fn open() -> Result<Api, String> {
    let mut tried = Vec::new();
    for candidate in candidates() {
        // SAFETY: OIDN's initialisers only register its device modules.
        match unsafe { Library::new(&candidate) } {
            Ok(lib) => return bind(lib, &candidate),
            Err(e) => tried.push(format!("{}: {e}", candidate.display())),
        }
    }
    Err(format!(
        "Intel Open Image Denoise 2.x was not found (tried {}); install it with \
         `pip install pyoidn`, or set {ENV} to {SONAME} or its directory",
        tried.join("; ")
    ))
}

/// Where to look, in order (see the module doc).
fn candidates() -> Vec<PathBuf> {
    let mut out = Vec::new();
    if let Some(p) = std::env::var_os(ENV).map(PathBuf::from) {
        out.push(if p.is_dir() { p.join(SONAME) } else { p });
        // A named place is the only one looked in: no silent fallback.
        return out;
    }
    out.push(PathBuf::from(SONAME));
    if let Some(dir) = pyoidn_dir() {
        out.push(dir.join("oidn").join("lib").join(SONAME));
    }
    out
}

/// The directory of python3's `pyoidn` package, found without importing it.
fn pyoidn_dir() -> Option<PathBuf> {
    let script = "import importlib.util as u; s = u.find_spec('pyoidn'); \
                  print(s.submodule_search_locations[0] if s else '')";
    let out = Command::new("python3").args(["-c", script]).output().ok()?;
    let dir = String::from_utf8(out.stdout).ok()?;
    let dir = Path::new(dir.trim());
    (out.status.success() && !dir.as_os_str().is_empty()).then(|| dir.to_path_buf())
}

fn bind(lib: Library, path: &Path) -> Result<Api, String> {
    // SAFETY: the signatures are OIDN 2.x's (`oidn.h`); the SONAME's major
    // version pins that API.
    unsafe {
        macro_rules! sym {
            ($name:literal) => {
                *lib.get($name)
                    .map_err(|e| format!("{}: {e}", path.display()))?
            };
        }
        Ok(Api {
            new_device: sym!(b"oidnNewDevice\0"),
            set_device_int: sym!(b"oidnSetDeviceInt\0"),
            set_device_bool: sym!(b"oidnSetDeviceBool\0"),
            commit_device: sym!(b"oidnCommitDevice\0"),
            get_device_error: sym!(b"oidnGetDeviceError\0"),
            release_device: sym!(b"oidnReleaseDevice\0"),
            new_filter: sym!(b"oidnNewFilter\0"),
            set_shared_filter_image: sym!(b"oidnSetSharedFilterImage\0"),
            set_filter_bool: sym!(b"oidnSetFilterBool\0"),
            set_filter_int: sym!(b"oidnSetFilterInt\0"),
            commit_filter: sym!(b"oidnCommitFilter\0"),
            execute_filter: sym!(b"oidnExecuteFilter\0"),
            release_filter: sym!(b"oidnReleaseFilter\0"),
            _lib: lib,
        })
    }
}

/// The device's pending error, if any, as text.
pub fn device_error(api: &Api, device: Device) -> Option<String> {
    let mut msg: *const c_char = std::ptr::null();
    // SAFETY: `device` is live; OIDN returns a string it owns or null.
    let code = unsafe { (api.get_device_error)(device, &mut msg) };
    (code != 0).then(|| {
        let text = if msg.is_null() {
            String::new()
        } else {
            // SAFETY: a NUL-terminated string valid until the next call.
            unsafe { CStr::from_ptr(msg) }
                .to_string_lossy()
                .into_owned()
        };
        format!("Open Image Denoise error {code}: {text}")
    })
}
