//! What to compute on a model: an initial-value problem (time span, step, integration
//! formula, Newton settings) and the eigenanalyses requested along it. Plain data, read
//! from MBDyn's `initial value` block or built in Rust; `solve` and the run driver act on it.

/// Integration formula (METHOD §5).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// `y_k = y_{k−1} + h ẏ_k`.
    ImplicitEuler,
    /// `y_k = y_{k−1} + h/2 (ẏ_k + ẏ_{k−1})` (`b₀ = h/2`).
    CrankNicolson,
    /// MBDyn's two-step "ms" family with asymptotic spectral radius `rho` in [0, 1]
    /// (METHOD §5; `rho = 1`: two-step trapezoidal rule, `rho = 0`: BDF2).
    Ms { rho: f64 },
}

/// Which matrices an eigenanalysis writes besides the eigenvalues.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EigenOutput {
    /// `Aplus = J(+c)`, `Aminus = J(−c)` (MBDyn's `output matrices` / `output full matrices`).
    pub full_matrices: bool,
    /// The same matrices as sparse triplets (`output sparse matrices`).
    pub sparse_matrices: bool,
    /// Right and left eigenvectors `VR`, `VL` (`output eigenvectors`).
    pub eigenvectors: bool,
    /// Node positions and orientations at the time of the analysis (`output geometry`).
    pub geometry: bool,
}

/// Eigenanalyses requested along an initial-value problem (MBDyn's `eigenanalysis:`).
#[derive(Clone, Debug, PartialEq)]
pub struct EigenRequest {
    /// Times of the analyses [s], ascending.
    pub times: Vec<f64>,
    /// dCoef `c` of `J(±c)` [s] (half MBDyn's `parameter` h); `None`: romdyn chooses.
    pub dcoef: Option<f64>,
    /// Modes below this natural frequency are not reported [Hz].
    pub lower_frequency_hz: Option<f64>,
    /// Modes above this natural frequency are not reported [Hz].
    pub upper_frequency_hz: Option<f64>,
    pub output: EigenOutput,
}

/// Where MBDyn's `abort after` stops a run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AbortAfter {
    Input,
    Assembly,
    Derivatives,
    DummySteps,
}

/// An initial-value problem (SI units: s).
#[derive(Clone, Debug, PartialEq)]
pub struct InitialValueProblem {
    pub initial_time: f64,
    pub final_time: f64,
    pub time_step: f64,
    pub method: Method,
    /// Newton converges when the residual's max norm is below this (N, N m, …).
    pub tolerance: f64,
    pub max_iterations: usize,
    /// Tolerance and iteration limit of the consistent initial derivatives.
    pub derivatives_tolerance: f64,
    pub derivatives_max_iterations: usize,
    pub eigenanalysis: Option<EigenRequest>,
    pub abort_after: Option<AbortAfter>,
}

impl Default for InitialValueProblem {
    fn default() -> Self {
        InitialValueProblem {
            initial_time: 0.0,
            final_time: 0.0,
            time_step: 1e-3,
            method: Method::Ms { rho: 0.6 },
            tolerance: 1e-6,
            max_iterations: 20,
            derivatives_tolerance: 1e-6,
            derivatives_max_iterations: 20,
            eigenanalysis: None,
            abort_after: None,
        }
    }
}
