//! SUNDIALS CVODE (Debian's libsundials-dev, SUNDIALS 6.4) through the few C functions the
//! benchmark needs, declared by hand. All of the crate's `unsafe` is in this module: the rest
//! sees [`Cvode`], which owns its solver memory, vectors, matrix and solvers and frees them on
//! drop.
//!
//! BDF runs with Newton iteration on a dense matrix whose Jacobian CVODE forms by difference
//! quotients (no user Jacobian, as our radau5 has none); Adams with fixed-point iteration, its
//! usual set-up for non-stiff problems (no matrix at all).

use crate::problem::Problem;
use std::cell::RefCell;
use std::ffi::{c_char, c_int, c_long, c_void, CStr};
use std::marker::PhantomData;

type SunContext = *mut c_void;
type NVector = *mut c_void;
type SunMatrix = *mut c_void;
type SunLinearSolver = *mut c_void;
type SunNonlinearSolver = *mut c_void;
type RhsFn = extern "C" fn(f64, NVector, NVector, *mut c_void) -> c_int;
type RootFn = extern "C" fn(f64, NVector, *mut f64, *mut c_void) -> c_int;
type ErrHandlerFn = extern "C" fn(c_int, *const c_char, *const c_char, *const c_char, *mut c_void);

const CV_ADAMS: c_int = 1;
const CV_BDF: c_int = 2;
const CV_NORMAL: c_int = 1;
const CV_SUCCESS: c_int = 0;
const CV_TSTOP_RETURN: c_int = 1;
const CV_ROOT_RETURN: c_int = 2;

#[link(name = "sundials_cvode")]
#[link(name = "sundials_nvecserial")]
#[link(name = "sundials_sunmatrixdense")]
#[link(name = "sundials_sunlinsoldense")]
#[link(name = "sundials_sunnonlinsolfixedpoint")]
extern "C" {
    fn SUNContext_Create(comm: *mut c_void, ctx: *mut SunContext) -> c_int;
    fn SUNContext_Free(ctx: *mut SunContext) -> c_int;
    fn N_VNew_Serial(length: i64, ctx: SunContext) -> NVector;
    fn N_VDestroy(v: NVector);
    fn N_VGetArrayPointer(v: NVector) -> *mut f64;
    fn N_VGetLength(v: NVector) -> i64;
    fn SUNDenseMatrix(m: i64, n: i64, ctx: SunContext) -> SunMatrix;
    fn SUNMatDestroy(a: SunMatrix);
    fn SUNLinSol_Dense(y: NVector, a: SunMatrix, ctx: SunContext) -> SunLinearSolver;
    fn SUNLinSolFree(s: SunLinearSolver) -> c_int;
    fn SUNNonlinSol_FixedPoint(y: NVector, m: c_int, ctx: SunContext) -> SunNonlinearSolver;
    fn SUNNonlinSolFree(s: SunNonlinearSolver) -> c_int;
    fn CVodeCreate(lmm: c_int, ctx: SunContext) -> *mut c_void;
    fn CVodeInit(mem: *mut c_void, f: RhsFn, t0: f64, y0: NVector) -> c_int;
    fn CVodeReInit(mem: *mut c_void, t0: f64, y0: NVector) -> c_int;
    fn CVodeSVtolerances(mem: *mut c_void, rtol: f64, atol: NVector) -> c_int;
    fn CVodeSetUserData(mem: *mut c_void, data: *mut c_void) -> c_int;
    fn CVodeSetErrHandlerFn(mem: *mut c_void, f: ErrHandlerFn, data: *mut c_void) -> c_int;
    fn CVodeSetMaxNumSteps(mem: *mut c_void, steps: c_long) -> c_int;
    fn CVodeSetMaxHnilWarns(mem: *mut c_void, warns: c_int) -> c_int;
    fn CVodeSetMaxStep(mem: *mut c_void, hmax: f64) -> c_int;
    fn CVodeSetStopTime(mem: *mut c_void, tstop: f64) -> c_int;
    fn CVodeSetLinearSolver(mem: *mut c_void, ls: SunLinearSolver, a: SunMatrix) -> c_int;
    fn CVodeSetNonlinearSolver(mem: *mut c_void, nls: SunNonlinearSolver) -> c_int;
    fn CVodeRootInit(mem: *mut c_void, count: c_int, g: RootFn) -> c_int;
    fn CVodeGetRootInfo(mem: *mut c_void, found: *mut c_int) -> c_int;
    fn CVodeSetNoInactiveRootWarn(mem: *mut c_void) -> c_int;
    fn CVode(mem: *mut c_void, tout: f64, y: NVector, tret: *mut f64, task: c_int) -> c_int;
    fn CVodeGetNumRhsEvals(mem: *mut c_void, n: *mut c_long) -> c_int;
    fn CVodeGetNumLinRhsEvals(mem: *mut c_void, n: *mut c_long) -> c_int;
    fn CVodeFree(mem: *mut *mut c_void);
}

thread_local! {
    /// CVODE's last error message (it reports through a handler, not the return code).
    static LAST_ERROR: RefCell<String> = const { RefCell::new(String::new()) };
}

extern "C" fn record_error(
    code: c_int,
    _module: *const c_char,
    function: *const c_char,
    message: *const c_char,
    _data: *mut c_void,
) {
    let text = |p: *const c_char| {
        if p.is_null() {
            String::new()
        } else {
            // SAFETY: CVODE passes NUL-terminated strings that live for the call.
            unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned()
        }
    };
    // Warnings (code > 0) are not failures.
    if code < 0 {
        LAST_ERROR
            .with(|e| *e.borrow_mut() = format!("{} ({code}): {}", text(function), text(message)));
    }
}

fn last_error(flag: c_int) -> String {
    let message = LAST_ERROR.with(|e| std::mem::take(&mut *e.borrow_mut()));
    if message.is_empty() {
        format!("CVODE flag {flag}")
    } else {
        message
    }
}

/// The state behind CVODE's `user_data`: the problem.
struct UserData<'a, P: Problem> {
    problem: &'a P,
}

fn slice<'a>(v: NVector) -> &'a [f64] {
    // SAFETY: `v` is a serial N_Vector CVODE hands a callback (or one of ours); its data is
    // N_VGetLength doubles and outlives the callback.
    unsafe { std::slice::from_raw_parts(N_VGetArrayPointer(v), N_VGetLength(v) as usize) }
}

fn slice_mut<'a>(v: NVector) -> &'a mut [f64] {
    // SAFETY: as in `slice`; CVODE gives the callback exclusive use of its output vector.
    unsafe { std::slice::from_raw_parts_mut(N_VGetArrayPointer(v), N_VGetLength(v) as usize) }
}

extern "C" fn rhs<P: Problem>(t: f64, y: NVector, ydot: NVector, data: *mut c_void) -> c_int {
    // SAFETY: `data` is the `UserData<P>` boxed in `Cvode::new`, alive while the solver is.
    let user = unsafe { &*(data as *const UserData<P>) };
    user.problem.rhs(t, slice(y), slice_mut(ydot));
    0
}

extern "C" fn roots<P: Problem>(t: f64, y: NVector, g: *mut f64, data: *mut c_void) -> c_int {
    // SAFETY: as in `rhs`; `g` holds `Problem::root_count` doubles.
    let user = unsafe { &*(data as *const UserData<P>) };
    let count = user.problem.root_count();
    let g = unsafe { std::slice::from_raw_parts_mut(g, count) };
    user.problem.roots(t, slice(y), g);
    0
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    Bdf,
    Adams,
}

/// Where [`Cvode::advance`] stopped.
pub enum Stop {
    /// At the time asked for.
    Reached,
    /// On a root of the problem's root functions, before it (at `Cvode::t`).
    Root,
}

pub struct Cvode<'a, P: Problem> {
    ctx: SunContext,
    mem: *mut c_void,
    y: NVector,
    atol: NVector,
    matrix: SunMatrix,
    linear: SunLinearSolver,
    nonlinear: SunNonlinearSolver,
    user: Box<UserData<'a, P>>,
    pub t: f64,
    _problem: PhantomData<&'a P>,
}

impl<'a, P: Problem> Cvode<'a, P> {
    /// A solver at `(t0, y0)` with relative tolerance `rtol` and absolute tolerances `atol`
    /// (one per state); with the problem's root functions when `with_roots`.
    pub fn new(
        method: Method,
        problem: &'a P,
        t0: f64,
        y0: &[f64],
        rtol: f64,
        atol: &[f64],
        with_roots: bool,
    ) -> Result<Self, String> {
        let n = y0.len() as i64;
        let mut solver = Cvode {
            ctx: std::ptr::null_mut(),
            mem: std::ptr::null_mut(),
            y: std::ptr::null_mut(),
            atol: std::ptr::null_mut(),
            matrix: std::ptr::null_mut(),
            linear: std::ptr::null_mut(),
            nonlinear: std::ptr::null_mut(),
            user: Box::new(UserData { problem }),
            t: t0,
            _problem: PhantomData,
        };
        let check = |flag: c_int, what: &str| {
            if flag == CV_SUCCESS {
                Ok(())
            } else {
                Err(format!("{what}: {}", last_error(flag)))
            }
        };
        // SAFETY: each call gets the objects created just before it, checked for NULL; the
        // pointers stored in `solver` are freed once, in Drop, whatever fails on the way.
        unsafe {
            check(
                SUNContext_Create(std::ptr::null_mut(), &mut solver.ctx),
                "SUNContext_Create",
            )?;
            solver.y = N_VNew_Serial(n, solver.ctx);
            solver.atol = N_VNew_Serial(n, solver.ctx);
            if solver.y.is_null() || solver.atol.is_null() {
                return Err("N_VNew_Serial failed".into());
            }
            slice_mut(solver.y).copy_from_slice(y0);
            slice_mut(solver.atol).copy_from_slice(atol);
            let lmm = match method {
                Method::Bdf => CV_BDF,
                Method::Adams => CV_ADAMS,
            };
            solver.mem = CVodeCreate(lmm, solver.ctx);
            if solver.mem.is_null() {
                return Err("CVodeCreate failed".into());
            }
            let mem = solver.mem;
            check(
                CVodeSetErrHandlerFn(mem, record_error, std::ptr::null_mut()),
                "CVodeSetErrHandlerFn",
            )?;
            check(CVodeInit(mem, rhs::<P>, t0, solver.y), "CVodeInit")?;
            check(
                CVodeSVtolerances(mem, rtol, solver.atol),
                "CVodeSVtolerances",
            )?;
            let data = &*solver.user as *const UserData<P> as *mut c_void;
            check(CVodeSetUserData(mem, data), "CVodeSetUserData")?;
            check(CVodeSetMaxNumSteps(mem, 50_000_000), "CVodeSetMaxNumSteps")?;
            check(CVodeSetMaxHnilWarns(mem, -1), "CVodeSetMaxHnilWarns")?;
            match method {
                Method::Bdf => {
                    solver.matrix = SUNDenseMatrix(n, n, solver.ctx);
                    if solver.matrix.is_null() {
                        return Err("SUNDenseMatrix failed".into());
                    }
                    solver.linear = SUNLinSol_Dense(solver.y, solver.matrix, solver.ctx);
                    if solver.linear.is_null() {
                        return Err("SUNLinSol_Dense failed".into());
                    }
                    check(
                        CVodeSetLinearSolver(mem, solver.linear, solver.matrix),
                        "CVodeSetLinearSolver",
                    )?;
                }
                Method::Adams => {
                    solver.nonlinear = SUNNonlinSol_FixedPoint(solver.y, 0, solver.ctx);
                    if solver.nonlinear.is_null() {
                        return Err("SUNNonlinSol_FixedPoint failed".into());
                    }
                    check(
                        CVodeSetNonlinearSolver(mem, solver.nonlinear),
                        "CVodeSetNonlinearSolver",
                    )?;
                }
            }
            if with_roots {
                let count = problem.root_count() as c_int;
                check(CVodeRootInit(mem, count, roots::<P>), "CVodeRootInit")?;
                check(
                    CVodeSetNoInactiveRootWarn(mem),
                    "CVodeSetNoInactiveRootWarn",
                )?;
            }
        }
        Ok(solver)
    }

    /// Integrates towards `t1` without stepping past it; stops early on a root.
    pub fn advance(&mut self, t1: f64) -> Result<Stop, String> {
        // SAFETY: `mem` and `y` are live (created in `new`, freed only in Drop).
        let flag = unsafe {
            let flag = CVodeSetStopTime(self.mem, t1);
            if flag != CV_SUCCESS {
                return Err(format!("CVodeSetStopTime: {}", last_error(flag)));
            }
            CVode(self.mem, t1, self.y, &mut self.t, CV_NORMAL)
        };
        match flag {
            CV_SUCCESS | CV_TSTOP_RETURN => Ok(Stop::Reached),
            CV_ROOT_RETURN => Ok(Stop::Root),
            _ => Err(last_error(flag)),
        }
    }

    /// Caps the step size.
    pub fn set_max_step(&mut self, h_max: f64) -> Result<(), String> {
        // SAFETY: `mem` is live.
        let flag = unsafe { CVodeSetMaxStep(self.mem, h_max) };
        if flag == CV_SUCCESS {
            Ok(())
        } else {
            Err(format!("CVodeSetMaxStep: {}", last_error(flag)))
        }
    }

    /// Starts afresh at `(t0, y0)` (order 1, a new first step), keeping the tolerances, the
    /// solvers and the root functions: after an event that changes the equations. The counts
    /// of [`Cvode::rhs_evaluations`] start again from 0.
    pub fn reinit(&mut self, t0: f64, y0: &[f64]) -> Result<(), String> {
        slice_mut(self.y).copy_from_slice(y0);
        self.t = t0;
        // SAFETY: `mem` and `y` are live.
        let flag = unsafe { CVodeReInit(self.mem, t0, self.y) };
        if flag == CV_SUCCESS {
            Ok(())
        } else {
            Err(format!("CVodeReInit: {}", last_error(flag)))
        }
    }

    /// Which root functions have a root where the last `advance` stopped (0: none, +-1: the
    /// direction of the crossing).
    pub fn root_info(&self, found: &mut [c_int]) {
        // SAFETY: `found` holds at least `root_count` ints, as CVodeGetRootInfo writes.
        unsafe {
            CVodeGetRootInfo(self.mem, found.as_mut_ptr());
        }
    }

    /// The state at `t`.
    pub fn y(&self) -> &[f64] {
        slice(self.y)
    }

    /// Right-hand-side evaluations, those of the difference-quotient Jacobian included.
    pub fn rhs_evaluations(&self) -> u64 {
        let (mut f, mut lin) = (0 as c_long, 0 as c_long);
        // SAFETY: `mem` is live; the getters write one long each. CVodeGetNumLinRhsEvals fails
        // (and leaves 0) without a linear solver.
        unsafe {
            CVodeGetNumRhsEvals(self.mem, &mut f);
            if !self.linear.is_null() {
                CVodeGetNumLinRhsEvals(self.mem, &mut lin);
            }
        }
        (f + lin) as u64
    }
}

impl<P: Problem> Drop for Cvode<'_, P> {
    fn drop(&mut self) {
        // SAFETY: every pointer is NULL or was created in `new` and is freed here once, the
        // solver memory before the solvers and vectors it uses, the context last.
        unsafe {
            if !self.mem.is_null() {
                CVodeFree(&mut self.mem);
            }
            if !self.nonlinear.is_null() {
                SUNNonlinSolFree(self.nonlinear);
            }
            if !self.linear.is_null() {
                SUNLinSolFree(self.linear);
            }
            if !self.matrix.is_null() {
                SUNMatDestroy(self.matrix);
            }
            if !self.y.is_null() {
                N_VDestroy(self.y);
            }
            if !self.atol.is_null() {
                N_VDestroy(self.atol);
            }
            if !self.ctx.is_null() {
                SUNContext_Free(&mut self.ctx);
            }
        }
    }
}
