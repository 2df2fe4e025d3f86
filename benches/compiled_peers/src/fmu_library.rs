//! Ours through the library an FMU carries: the TransverseFriction shared library of `binary/`
//! built in the `fmu` profile (release without link-time optimisation, as `friction-fmu build`
//! packs it), loaded with dlopen and driven by fmi2 calls, one fmi2DoStep a period. The rest of
//! the bench runs ours in-process, inlined into this crate's fat-LTO build: this is what a
//! master that imports the FMU gets.
//!
//! The library: `FRICTION_FMU_LIBRARY` if set (e.g. an unpacked FMU's
//! `binaries/linux64/TransverseFriction.so`), else `target/fmu/examples/libTransverseFriction.so`
//! of the main crate, which `cargo build --profile fmu -p friction-fmu-binary --examples` writes
//! (the host-toolchain build `friction-fmu build` packs).

use friction_fmu::fmi2::ffi::{CallbackFunctions, CallbackLogger};
use std::ffi::{c_char, c_int, c_void, CStr, CString};
use std::path::PathBuf;

type Component = *mut c_void;
type Instantiate = unsafe extern "C" fn(
    *const c_char,
    c_int,
    *const c_char,
    *const c_char,
    *const CallbackFunctions,
    c_int,
    c_int,
) -> Component;
type Setup = unsafe extern "C" fn(Component, c_int, f64, f64, c_int, f64) -> c_int;
type Init = unsafe extern "C" fn(Component) -> c_int;
type SetReal = unsafe extern "C" fn(Component, *const u32, usize, *const f64) -> c_int;
type SetInteger = unsafe extern "C" fn(Component, *const u32, usize, *const c_int) -> c_int;
type GetReal = unsafe extern "C" fn(Component, *const u32, usize, *mut f64) -> c_int;
type DoStep = unsafe extern "C" fn(Component, f64, f64, c_int) -> c_int;
type Free = unsafe extern "C" fn(Component);

/// The fmi2 functions the bench calls, from one loaded library (never unloaded: it lives as
/// long as the bench).
pub struct Library {
    instantiate: Instantiate,
    setup: Setup,
    enter: Init,
    exit: Init,
    set_real: SetReal,
    set_integer: SetInteger,
    get_real: GetReal,
    do_step: DoStep,
    terminate: Init,
    free: Free,
    guid: CString,
}

/// One run's parameters: integers (enumerations) and reals, by value reference.
pub struct Setting {
    pub integers: Vec<(u32, i32)>,
    pub reals: Vec<(u32, f64)>,
}

extern "C" fn ignore(
    _env: *mut c_void,
    _name: *const c_char,
    _status: c_int,
    _category: *const c_char,
    _message: *const c_char,
) {
}

fn logger() -> CallbackLogger {
    type Fixed = extern "C" fn(*mut c_void, *const c_char, c_int, *const c_char, *const c_char);
    // SAFETY: a variadic call passes the fixed arguments as a non-variadic one does on the
    // targets this bench runs on (x86-64 and aarch64 Linux); the logger reads none after them.
    unsafe { std::mem::transmute::<Fixed, CallbackLogger>(ignore as Fixed) }
}

/// Where the library is looked for.
pub fn path() -> PathBuf {
    std::env::var_os("FRICTION_FMU_LIBRARY")
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            PathBuf::from(env!("CARGO_MANIFEST_DIR"))
                .join("../../target/fmu/examples/libTransverseFriction.so")
        })
}

impl Library {
    /// Loads the library of `model_identifier`, or says why not.
    pub fn load(model_identifier: &str) -> Result<Library, String> {
        let path = path();
        let c_path = CString::new(path.to_string_lossy().as_bytes()).map_err(|e| e.to_string())?;
        // SAFETY: dlopen with a valid C string; the handle is kept for the process's life.
        let handle = unsafe { libc::dlopen(c_path.as_ptr(), libc::RTLD_NOW | libc::RTLD_LOCAL) };
        if handle.is_null() {
            // SAFETY: dlerror returns NULL or a C string valid until the next dl call.
            let why = unsafe {
                let e = libc::dlerror();
                if e.is_null() {
                    String::new()
                } else {
                    CStr::from_ptr(e).to_string_lossy().into_owned()
                }
            };
            return Err(format!("no FMU library at {}: {why}", path.display()));
        }
        let symbol = |name: &str| -> Result<*mut c_void, String> {
            let c = CString::new(name).expect("symbol name");
            // SAFETY: a live handle and a valid C string.
            let p = unsafe { libc::dlsym(handle, c.as_ptr()) };
            if p.is_null() {
                Err(format!("{} has no {name}", path.display()))
            } else {
                Ok(p)
            }
        };
        // SAFETY: each symbol is the fmi2 function of that name, whose C signature the type
        // spells (fmi2Functions.h).
        unsafe {
            Ok(Library {
                instantiate: std::mem::transmute::<*mut c_void, Instantiate>(symbol(
                    "fmi2Instantiate",
                )?),
                setup: std::mem::transmute::<*mut c_void, Setup>(symbol("fmi2SetupExperiment")?),
                enter: std::mem::transmute::<*mut c_void, Init>(symbol(
                    "fmi2EnterInitializationMode",
                )?),
                exit: std::mem::transmute::<*mut c_void, Init>(symbol(
                    "fmi2ExitInitializationMode",
                )?),
                set_real: std::mem::transmute::<*mut c_void, SetReal>(symbol("fmi2SetReal")?),
                set_integer: std::mem::transmute::<*mut c_void, SetInteger>(symbol(
                    "fmi2SetInteger",
                )?),
                get_real: std::mem::transmute::<*mut c_void, GetReal>(symbol("fmi2GetReal")?),
                do_step: std::mem::transmute::<*mut c_void, DoStep>(symbol("fmi2DoStep")?),
                terminate: std::mem::transmute::<*mut c_void, Init>(symbol("fmi2Terminate")?),
                free: std::mem::transmute::<*mut c_void, Free>(symbol("fmi2FreeInstance")?),
                guid: CString::new(
                    friction_fmu::fmi2::guid(model_identifier)
                        .ok_or_else(|| format!("no GUID for {model_identifier}"))?,
                )
                .expect("GUID"),
            })
        }
    }

    /// Instantiates, sets `setting`, initialises at time 0, takes `periods` fmi2DoStep calls of
    /// `period` each and returns the real output `read` at the end.
    pub fn run(
        &self,
        setting: &Setting,
        period: f64,
        periods: u32,
        read: u32,
    ) -> Result<f64, String> {
        let callbacks = CallbackFunctions {
            logger: Some(logger()),
            allocate_memory: None,
            free_memory: None,
            step_finished: None,
            component_environment: std::ptr::null_mut(),
        };
        let name = CString::new("bench").expect("name");
        let ok = |what: &str, status: c_int| {
            if status == 0 {
                Ok(())
            } else {
                Err(format!("{what}: status {status}"))
            }
        };
        // SAFETY: the pointers passed are live for each call; the component is the one
        // fmi2Instantiate returned, freed once at the end.
        unsafe {
            let c = (self.instantiate)(
                name.as_ptr(),
                1,
                self.guid.as_ptr(),
                std::ptr::null(),
                &callbacks,
                0,
                0,
            );
            if c.is_null() {
                return Err("fmi2Instantiate failed".into());
            }
            let result = (|| {
                for &(vr, v) in &setting.integers {
                    ok("fmi2SetInteger", (self.set_integer)(c, &vr, 1, &v))?;
                }
                for &(vr, v) in &setting.reals {
                    ok("fmi2SetReal", (self.set_real)(c, &vr, 1, &v))?;
                }
                ok("fmi2SetupExperiment", (self.setup)(c, 0, 0.0, 0.0, 0, 0.0))?;
                ok("fmi2EnterInitializationMode", (self.enter)(c))?;
                ok("fmi2ExitInitializationMode", (self.exit)(c))?;
                let mut t = 0.0;
                for i in 0..periods {
                    let next = f64::from(i + 1) * period;
                    ok("fmi2DoStep", (self.do_step)(c, t, next - t, 1))?;
                    t = next;
                }
                let mut value = f64::NAN;
                ok("fmi2GetReal", (self.get_real)(c, &read, 1, &mut value))?;
                ok("fmi2Terminate", (self.terminate)(c))?;
                Ok(value)
            })();
            (self.free)(c);
            result
        }
    }
}
