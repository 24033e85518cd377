//! The `data` block (`problem: initial value;`) and the `initial value` block (input
//! manual, "Problems", §Initial-Value Problem) into an [`InitialValueProblem`]: times,
//! step, `method`, Newton `tolerance` and `max iterations`, the derivatives phase, and the
//! `eigenanalysis` request (§Eigenanalysis). Statements that only tune MBDyn's own
//! numerics (nonlinear and linear solver, threads, time-step strategy, dummy steps, output
//! and real-time settings) are accepted and ignored: romdyn uses its own.

use crate::mbdyn::syntax::cursor::Cursor;
use crate::limits::readable;
use crate::mbdyn::syntax::diagnostic::{MbdynError, Sources};
use crate::mbdyn::drives::callers::{drive, Drives};
use crate::mbdyn::syntax::parser::{known, Block};
use crate::model::{AbortAfter, AutoCoefficient, EigenFileSuffix, EigenOutput, EigenRequest, EigenSolverRequest, InitialValueProblem, Method, ResidualNorm, SuffixWidth};
use crate::element::drive::Drive;

/// Reads the `data` block.
pub fn data(block: &Block, sources: &Sources) -> Result<(), MbdynError> {
    for st in &block.statements {
        let mut c = Cursor::new(st, sources);
        match known(&st.keyword, &["problem", "integrator"]) {
            Some("integrator") => {
                // MBDyn's older name of the same card.
                c.keyword("the integrator", &["multistep", "initial value"])?;
                c.finish()?;
            }
            Some(_) => {
                let span = c.here();
                if c.accept("inverse dynamics") {
                    return Err(c.error_at(span, "problem 'inverse dynamics' is not supported by romdyn (MBDyn 1.7.3 runs it) (supported: initial value)"));
                }
                // `multistep` is MBDyn's deprecated name of the initial value problem.
                c.keyword("the problem", &["initial value", "multistep"])?;
                c.finish()?;
            }
            None => return Err(c.error_at(st.span, format!("statement '{}' in the data block is not supported by romdyn", st.keyword))),
        }
    }
    Ok(())
}

/// MBDyn's numerics settings romdyn ignores (`nonlinear solver` and its deprecated spelling
/// `newton raphson: …` are read for the Newton–Raphson kind, before these), with their
/// deprecated spellings (`fictitious steps …` for `dummy steps …`, `solver`, `interface
/// solver`, `preconditioner`: solver.cc, Solver::ReadData).
const IGNORED: [&str; 28] = [
    "strategy", "min time step", "max time step", "modify residual test", "linear solver", "solver", "threads",
    "dummy steps tolerance", "dummy steps max iterations", "dummy steps number", "dummy steps ratio",
    "dummy steps method", "output", "output meter", "real time", "fictitious steps tolerance", "fictitious steps max iterations",
    "fictitious steps number", "fictitious steps ratio", "fictitious steps method", "interface linear solver",
    "interface solver", "preconditioner", "max residual", "enforce constraint equations", "pod", "time step pattern", "min time step pattern",
];

const STATEMENTS: [&str; 11] = [
    "initial time", "final time", "time step", "tolerance", "max iterations", "method", "eigenanalysis", "derivatives tolerance", "derivatives max iterations", "abort after",
    "derivatives coefficient",
];

/// MBDyn's settings when the file does not give them (solver_impl.h: `dDefaultTol = 1e-6`,
/// `iDefaultMaxIterations = 1`, `dDefaultDerivativesCoefficient = 1e-6`; solver.cc,
/// `Solver::ReadData`: without `method:` the integrator is `ms` with a null drive for ρ∞,
/// i.e. ρ∞ = 0; the initial time step is 1 s; the derivatives use the same tolerance and
/// iteration defaults; the residual test is the 2-norm, `test, norm`, and no solution
/// test: `dSolutionTol = 0`, nonlin.cc `MakeSolTest`).
pub fn mbdyn_defaults() -> InitialValueProblem {
    InitialValueProblem {
        initial_time: 0.0,
        final_time: 0.0,
        time_step: 1.0,
        method: Method::Ms { rho: 0.0 },
        varying_radius: None,
        tolerance: 1e-6,
        max_iterations: 1,
        derivatives_tolerance: 1e-6,
        derivatives_max_iterations: 1,
        derivatives_coefficient: 1e-6,
        residual_norm: ResidualNorm::Euclidean,
        increment_tolerance: 0.0,
        ..InitialValueProblem::default()
    }
}

/// Reads the `initial value` block (defaults when absent).
pub fn initial_value(block: Option<&Block>, sources: &Sources, drives: &Drives) -> Result<InitialValueProblem, MbdynError> {
    let mut a = mbdyn_defaults();
    let Some(iv) = block else { return Ok(a) };
    let mut eigen_span = None;
    for st in &iv.statements {
        let mut c = Cursor::new(st, sources);
        if let Some(card) = known(&st.keyword, &["nonlinear solver", "newton raphson"]) {
            if let Some(modified) = newton_kind(&mut c, card == "newton raphson")? {
                a.modified_newton = modified;
            }
            continue;
        }
        if known(&st.keyword, &IGNORED).is_some() {
            c.skip_rest();
            continue;
        }
        match known(&st.keyword, &STATEMENTS) {
            Some("initial time") => a.initial_time = c.real("initial time [s]")?,
            Some("final time") => a.final_time = if c.accept("forever") { f64::INFINITY } else { c.real("final time [s] (or forever)")? },
            Some("time step") => {
                let span = c.here();
                a.time_step = c.real("time step [s]")?;
                if a.time_step <= 0.0 {
                    return Err(c.error_at(span, format!("the time step must be positive, found {}", a.time_step)));
                }
            }
            Some("tolerance") => tolerance(&mut c, &mut a)?,
            Some("max iterations") => {
                a.max_iterations = c.count("maximum number of iterations")?;
                c.accept("at most");
            }
            Some("method") => (a.method, a.varying_radius) = method(&mut c, drives, a.initial_time, st.seq)?,
            Some("eigenanalysis") => {
                if let Some(first) = eigen_span.replace(st.span) {
                    return Err(c.error_at(st.span, format!("'eigenanalysis' appears twice (first at line {}): use 'list' for several times", first.line)));
                }
                a.eigenanalysis = Some(eigenanalysis(&mut c)?);
            }
            Some("derivatives tolerance") => {
                a.derivatives_tolerance = c.real("derivatives tolerance")?;
                // MBDyn 1.7.3 reads one value (solver.cc, case DERIVATIVESTOLERANCE) and
                // skips what follows; files written for the later residual/solution pair
                // give two.
                if !c.is_done() {
                    c.real("derivatives solution tolerance")?;
                }
            }
            Some("derivatives coefficient") => derivatives_coefficient(&mut c, &mut a)?,
            Some("derivatives max iterations") => a.derivatives_max_iterations = c.count("derivatives max iterations")?,
            Some(_) => {
                a.abort_after = Some(match c.keyword("where to stop", &["input", "assembly", "derivatives", "dummy steps", "fictitious steps"])? {
                    "input" => AbortAfter::Input,
                    "assembly" => AbortAfter::Assembly,
                    "derivatives" => AbortAfter::Derivatives,
                    _ => AbortAfter::DummySteps,
                })
            }
            None => return Err(c.error_at(st.span, format!("statement '{}' in the initial value block is not supported by romdyn", st.keyword))),
        }
        c.finish()?;
    }
    if a.final_time < a.initial_time {
        return Err(sources.error(iv.span, format!("final time {} is before initial time {}", a.final_time, a.initial_time)));
    }
    if let (Some(span), Some(t)) = (eigen_span, a.eigenanalysis.as_ref().and_then(|r| r.times.iter().copied().find(|t| *t < a.initial_time))) {
        return Err(sources.error(span, format!("eigenanalysis time {t} s is before the initial time {} s: it would never be reached", a.initial_time)));
    }
    let steps = (a.final_time - a.initial_time) / a.time_step;
    if a.final_time.is_finite() && !(steps <= crate::limits::MAX_TIME_STEPS) {
        return Err(sources.error(
            iv.span,
            format!(
                "initial time {} s to final time {} s with time step {} s is {} steps, more than romdyn's limit of {:e} steps per run",
                readable(a.initial_time),
                readable(a.final_time),
                readable(a.time_step),
                readable(steps.round()),
                crate::limits::MAX_TIME_STEPS
            ),
        ));
    }
    Ok(a)
}

/// Whether a Newton card asks for the modified method (`None`: it leaves the choice as it
/// was), read as MBDyn 1.7.3 does (solver.cc, `Solver::ReadData`, cases NONLINEARSOLVER and
/// NEWTONRAPHSON; input manual, "Nonlinear Solver"):
/// - `nonlinear solver: {newton raphson | line search} [, true | , modified, ITERATIONS [,
///   keep jacobian [matrix]] [, honor element requests]] …` sets full or modified Newton
///   (`true` only after `newton raphson`; line search's own settings follow and are
///   ignored: romdyn runs its Newton); `default` and `matrix free` leave it as it was;
/// - the deprecated `newton raphson: {true | modified [, ITERATIONS]};` (MBDyn warns that it
///   is deprecated; without ITERATIONS it reuses the matrix for 2).
///
/// With `modified` romdyn keeps a factorization while the residual falls fast
/// (`InitialValueProblem::modified_newton`) instead of for ITERATIONS iterations, which it
/// reads and checks but does not use.
fn newton_kind(c: &mut Cursor, deprecated: bool) -> Result<Option<bool>, MbdynError> {
    if deprecated {
        // MBDyn warns and runs full Newton after another word; romdyn asks for one it knows.
        let modified = c.keyword("the Newton-Raphson kind", &["true", "modified"])? == "modified";
        if modified && !c.is_done() {
            reuse_count(c)?;
        }
        c.finish()?;
        return Ok(Some(modified));
    }
    let solver = c.keyword("the nonlinear solver", &["newton raphson", "line search", "default", "matrix free"])?;
    if matches!(solver, "default" | "matrix free") {
        c.skip_rest();
        return Ok(None);
    }
    let modified = !(solver == "newton raphson" && c.accept("true")) && c.accept("modified");
    if modified {
        reuse_count(c)?;
        c.accept_any(&["keep jacobian", "keep jacobian matrix"]);
        c.accept("honor element requests");
    }
    if solver == "newton raphson" {
        c.finish()?;
    } else {
        c.skip_rest();
    }
    Ok(Some(modified))
}

/// The iterations a modified Newton reuses one matrix for (MBDyn reads an integer).
fn reuse_count(c: &mut Cursor) -> Result<(), MbdynError> {
    let span = c.here();
    let n = c.integer("the iterations one Jacobian matrix is reused for")?;
    if n < 0 {
        return Err(c.error_at(span, format!("the iterations one Jacobian matrix is reused for cannot be negative, found {n}")));
    }
    Ok(())
}

/// `tolerance: {null | RES} [, test, …[, scale]] [, {null | SOL} [, test, …]]`: romdyn tests
/// the residual; `null` keeps romdyn's default, the solution tolerance is ignored.
fn tolerance(c: &mut Cursor, a: &mut InitialValueProblem) -> Result<(), MbdynError> {
    if !c.accept("null") {
        let span = c.here();
        a.tolerance = c.real("residual tolerance")?;
        if a.tolerance <= 0.0 {
            return Err(c.error_at(span, format!("the residual tolerance must be positive, found {}", a.tolerance)));
        }
    }
    if c.accept("test") {
        // `norm` (MBDyn's default) is the 2-norm of the residual, `minmax` its largest
        // entry; `none` leaves only the solution test, which romdyn does not run: the
        // residual is then tested with the default norm.
        match c.keyword("a convergence test", &["none", "norm", "minmax"])? {
            "minmax" => a.residual_norm = ResidualNorm::Max,
            _ => a.residual_norm = ResidualNorm::Euclidean,
        }
        c.accept("scale");
    }
    if !c.is_done() {
        if !c.accept("null") {
            c.real("solution tolerance")?;
        }
        if c.accept("test") {
            c.keyword("a convergence test", &["none", "norm", "minmax"])?;
            c.accept("scale");
        }
    }
    Ok(())
}

/// `derivatives coefficient: {COEF | [COEF,] auto [, max iterations, N] [, factor, F]}`:
/// the derivatives solve with dCoef = COEF · time step (solver.cc: `dInitialTimeStep *
/// dDerivativesCoef`); `auto` retries other coefficients, which romdyn does not: it keeps
/// COEF.
fn derivatives_coefficient(c: &mut Cursor, a: &mut InitialValueProblem) -> Result<(), MbdynError> {
    if c.next_is_number() {
        let span = c.here();
        let k = c.real("derivatives coefficient")?;
        if k <= 0.0 {
            return Err(c.error_at(span, format!("the derivatives coefficient must be positive, found {k}")));
        }
        a.derivatives_coefficient = k;
    }
    if c.accept("auto") {
        let mut auto = AutoCoefficient::default();
        if c.accept("max iterations") {
            let span = c.here();
            auto.retries = c.count("derivatives coefficient max iterations")?;
            if auto.retries > 100 {
                return Err(c.error_at(span, format!("at most 100 derivatives coefficient iterations are supported, found {}", auto.retries)));
            }
        }
        if c.accept("factor") {
            let span = c.here();
            auto.factor = c.real("derivatives coefficient factor")?;
            if !(auto.factor > 1.0) {
                return Err(c.error_at(span, format!("the derivatives coefficient factor must be greater than one, found {}", auto.factor)));
            }
        }
        a.derivatives_coefficient_auto = Some(auto);
    }
    Ok(())
}

/// `ms, RHO [, ALG_RHO]` (radii as drive callers, evaluated at the initial time),
/// `crank nicolson`, `implicit euler`, `bdf [, order, {1 | 2}]`; of later MBDyn versions
/// (their input manual, §Method; solver.cc `Solver::ReadData`): `Bathe, RHO [, ALG_RHO]`
/// and `hybrid, {implicit euler | crank nicolson | ms | ms2 | hope} [, RHO [, ALG_RHO]]`.
fn method(c: &mut Cursor, drives: &Drives, t0: f64, seq: usize) -> Result<(Method, Option<Drive>), MbdynError> {
    const SUPPORTED: &str = "supported: ms, crank nicolson, implicit euler, bdf, Bathe, hybrid";
    let span = c.here();
    if let Some(m) = c.accept_any(&["hope", "third order", "thirdorder"]) {
        return Err(c.error_at(span, format!("integration method '{m}' is not supported by romdyn (MBDyn 1.7.3 runs it) ({SUPPORTED})")));
    }
    // Methods of later MBDyn versions romdyn does not implement.
    if let Some(m) = c.accept_any(&["dirk33", "dirk43", "dirk54", "ms3", "ms4", "msstc3", "msstc4", "msstc5", "mssth3", "mssth4", "mssth5", "ss2", "ss3", "ss4", "ss5"]) {
        return Err(c.error_at(span, format!("integration method '{m}' is not known to MBDyn 1.7.3 (its reader stops with \"Unknown integration method\") and is not supported by romdyn ({SUPPORTED})")));
    }
    // The asymptotic spectral radius, then the algebraic one (romdyn integrates all unknowns
    // with one formula: read and not used). A radius that varies is evaluated before every
    // step (`varying`; MBDyn's `MultistepSolver::SetCoef`), one that reads the model's state
    // from the solution; its value at the initial time is checked here when it can be.
    let mut varying: Option<Drive> = None;
    let mut radius = |c: &mut Cursor| -> Result<f64, MbdynError> {
        let rho_span = c.here();
        let d = drive(c, drives, seq)?;
        let rho = if d.reads_state() { f64::NAN } else { d.value(t0) };
        if !rho.is_nan() && !(0.0..=1.0).contains(&rho) {
            return Err(c.error_at(rho_span, format!("the asymptotic spectral radius must be between 0 and 1, found {rho}")));
        }
        if !matches!(d, Drive::Const(_)) {
            varying = Some(d);
        }
        if !c.is_done() {
            drive(c, drives, seq)?;
        }
        Ok(rho)
    };
    // `crank nicholson` is MBDyn's deprecated spelling (solver.cc, Solver::ReadData).
    let method = match c.keyword("an integration method", &["ms", "crank nicolson", "crank nicholson", "implicit euler", "bdf", "bathe", "hybrid"])? {
        "ms" => Method::Ms { rho: radius(c)? },
        "bathe" => Method::Bathe { rho: radius(c)? },
        "hybrid" => {
            // Every unknown with the default method (only a loadable module of later MBDyn
            // versions chooses another for its own), after a Crank–Nicolson first step
            // (solver.cc): the radius is 0 when not given.
            let span = c.here();
            let default = c.keyword("the hybrid method's default method", &["implicit euler", "crank nicolson", "crank nicholson", "ms", "ms2", "hope"])?;
            let rho = if c.is_done() { 0.0 } else { radius(c)? };
            match default {
                "implicit euler" => Method::HybridImplicitEuler,
                "crank nicolson" | "crank nicholson" => Method::CrankNicolson,
                "hope" => return Err(c.error_at(span, format!("integration method 'hope' (the hybrid method's default) is not supported by romdyn (MBDyn 1.7.3 runs it) ({SUPPORTED})"))),
                _ => Method::Ms { rho },
            }
        }
        "crank nicolson" | "crank nicholson" => Method::CrankNicolson,
        "implicit euler" => Method::ImplicitEuler,
        _ => {
            if c.accept("order") {
                let span = c.here();
                match c.integer("BDF order (1 or 2)")? {
                    1 => return Ok((Method::ImplicitEuler, None)),
                    2 => {}
                    k => return Err(c.error_at(span, format!("BDF order must be 1 or 2, found {k}"))),
                }
            }
            Method::Ms { rho: 0.0 }
        }
    };
    Ok((method, varying))
}

/// `eigenanalysis: {WHEN | list, N, WHEN…} [, option …]` (input manual, §Eigenanalysis).
fn eigenanalysis(c: &mut Cursor) -> Result<EigenRequest, MbdynError> {
    let times = if c.accept("list") {
        let span = c.here();
        let n = c.count("number of eigenanalysis times")?;
        if n == 0 {
            return Err(c.error_at(span, "eigenanalysis: the list needs at least one time"));
        }
        let mut times: Vec<f64> = Vec::new();
        for _ in 0..n {
            let span = c.here();
            let t = c.real("eigenanalysis time [s]")?;
            if times.last().is_some_and(|prev| t <= *prev) {
                return Err(c.error_at(span, format!("eigenanalysis times must increase, {t} does not follow {}", times.last().copied().unwrap_or(0.0))));
            }
            times.push(t);
        }
        times
    } else {
        vec![c.real("eigenanalysis time [s] (or list)")?]
    };
    let mut r = EigenRequest { times, dcoef: None, lower_frequency_hz: None, upper_frequency_hz: None, output: EigenOutput::default(), file_suffix: EigenFileSuffix::default(), solver: EigenSolverRequest::Dense };
    let options = [
        "output matrices", "output full matrices", "output sparse matrices", "output eigenvectors", "output geometry", "parameter", "lower frequency limit",
        "upper frequency limit", "use lapack", "use arpack", "use jdqz", "use external", "balance", "suffix width", "suffix format",
        "matrix output precision", "results output precision",
    ];
    let mut chosen = None;
    while !c.is_done() {
        let span = c.here();
        match c.keyword("an eigenanalysis option", &options)? {
            "output matrices" | "output full matrices" => r.output.full_matrices = true,
            "output sparse matrices" => r.output.sparse_matrices = true,
            "output eigenvectors" => r.output.eigenvectors = true,
            "output geometry" => r.output.geometry = true,
            "parameter" => {
                let span = c.here();
                let p = c.real("parameter (a step h [s]; dCoef = h/2)")?;
                if p <= 0.0 {
                    return Err(c.error_at(span, format!("the eigenanalysis parameter must be positive, found {p}")));
                }
                // MBDyn assembles Aplus/Aminus as J(±h/2) with h = parameter (solver.cc).
                r.dcoef = Some(p / 2.0);
            }
            "lower frequency limit" => r.lower_frequency_hz = Some(c.real("lower frequency limit [Hz]")?),
            "upper frequency limit" => r.upper_frequency_hz = Some(c.real("upper frequency limit [Hz]")?),
            // `use external` maps onto the dense route as `use lapack`.
            "use external" => {}
            card @ ("use lapack" | "use arpack" | "use jdqz") => {
                if chosen.replace(span).is_some() {
                    return Err(c.error_at(span, "eigenanalysis: the solver is already selected (one 'use lapack', 'use arpack' or 'use jdqz', as in MBDyn)"));
                }
                r.solver = solver(c, card)?;
            }
            "balance" => {
                c.keyword("a balancing", &["no", "scale", "permute", "all"])?;
            }
            // Kept apart: a width (not 0) wins over a format, whichever comes first (solver.cc `Eig`).
            "suffix width" => r.file_suffix.width = if c.accept("compute") { SuffixWidth::Compute } else { SuffixWidth::Digits(c.count("suffix width")?) },
            "suffix format" => {
                let span = c.here();
                let format = c.string("suffix format (a printf format with one %d)")?;
                EigenFileSuffix::format(&format, 0).map_err(|m| c.error_at(span, format!("suffix format: {m}")))?;
                r.file_suffix.format = Some(format);
            }
            _ => {
                c.count("output precision (digits)")?;
            }
        }
    }
    if let (Some(lo), Some(hi)) = (r.lower_frequency_hz, r.upper_frequency_hz)
        && lo > hi
    {
        return Err(c.error_at(c.statement().span, format!("eigenanalysis: lower frequency limit {lo} Hz is above the upper limit {hi} Hz")));
    }
    Ok(r)
}

/// The arguments of `use lapack` (none), `use arpack, NEV, NCV, TOL` and `use jdqz, NEV,
/// JMAX, EPS`, checked as MBDyn 1.7.3 checks them (solver.cc, `ReadData`): NEV > 0,
/// NCV > NEV + 2, JMAX ≥ 20 and ≥ 2 NEV. Both sparse requests are the NEV lowest dynamic
/// modes of romdyn's sparse route (MBDyn's ARPACK and JDQZ both look for Λ nearest 1, λ
/// nearest 0); NCV, JMAX and the tolerance tune MBDyn's solvers and are read, not used:
/// every returned pair passes romdyn's own true-residual test (1e-10).
fn solver(c: &mut Cursor, card: &'static str) -> Result<EigenSolverRequest, MbdynError> {
    if card == "use lapack" {
        return Ok(EigenSolverRequest::Dense);
    }
    let span = c.here();
    let modes = c.count("number of eigenvalues (NEV)")?;
    if modes == 0 {
        return Err(c.error_at(span, format!("{card}: the number of eigenvalues must be positive, found 0")));
    }
    let span = c.here();
    if card == "use arpack" {
        let ncv = c.count("number of Arnoldi vectors (NCV)")?;
        if ncv <= modes + 2 {
            return Err(c.error_at(span, format!("use arpack: the number of Arnoldi vectors must be more than NEV + 2 = {}, found {ncv}", modes + 2)));
        }
    } else {
        let jmax = c.count("size of the search space (JMAX)")?;
        if jmax < 20 || jmax < 2 * modes {
            return Err(c.error_at(span, format!("use jdqz: the size of the search space must be at least 20 and at least 2 NEV = {}, found {jmax}", 2 * modes)));
        }
    }
    c.real("tolerance")?;
    Ok(EigenSolverRequest::Lowest { modes, card })
}
