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
    /// MBDyn's `Bathe` (later MBDyn versions, stepsol.cc `TunableBatheSolver`; Noh and
    /// Bathe's ρ∞-Bathe method): each step in two implicit sub-steps, the trapezoidal rule
    /// over `γh` and `y_k = y_{k−1} + h (q₀ ẏ_{k−1} + q₁ ẏ_{k−1+γ} + q₂ ẏ_k)` over the step, with
    /// asymptotic spectral radius `rho` in [0, 1] and `γ = (2 − √(2 + 2ρ))/(1 − ρ)` (½ at
    /// ρ = 1), for which both sub-steps have dCoef `γh/2` (see `solve::integrate`).
    Bathe { rho: f64 },
    /// MBDyn's `hybrid, implicit euler` (later MBDyn versions, stepsol_impl.cc
    /// `HybridStepIntegrator`, with no element choosing another method for its unknowns):
    /// a Crank–Nicolson first step (solver.cc), then implicit Euler.
    HybridImplicitEuler,
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
    /// How the analyses' files are numbered (`suffix width`, `suffix format`).
    pub file_suffix: EigenFileSuffix,
    /// Which eigensolver the file asks for (`use lapack`, `use arpack`, `use jdqz`).
    pub solver: EigenSolverRequest,
}

/// The eigensolver an eigenanalysis asks for (MBDyn's `use …` option, solver.cc `Eig`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum EigenSolverRequest {
    /// Every eigenvalue of the pencil by QZ (`use lapack`, or no `use`): n x n matrices.
    #[default]
    Dense,
    /// The `modes` lowest dynamic modes (λ nearest 0, Λ nearest 1; a complex pair is one
    /// mode) by the sparse shift-invert route, memory proportional to the non-zeros:
    /// `use arpack, NEV, NCV, TOL` (MBDyn asks ARPACK for the NEV eigenvalues of smallest
    /// magnitude of `Aplus⁻¹ Aminus − I`) and `use jdqz, NEV, …` (the NEV eigenvalues
    /// nearest the target Λ = 1). `card` names the option for messages.
    Lowest { modes: usize, card: &'static str },
}

/// The number in the name of an eigenanalysis's files: MBDyn 1.7.3 writes analysis K
/// (0-based) as `PREFIX_K.m`, one analysis or several (solver.cc `Eig`), `_` then K as
/// the file asks. Both settings are kept as written; a width (not 0) wins over a format,
/// whichever comes first, as in MBDyn.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct EigenFileSuffix {
    /// `suffix width, N` (0: none).
    pub width: SuffixWidth,
    /// `suffix format, "…"`: a printf format with one integer conversion (`%d`, `%03d`,
    /// `%-4i`, …; `%%` is a percent sign), checked by [`EigenFileSuffix::format`].
    pub format: Option<String>,
}

/// `suffix width`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SuffixWidth {
    /// K zero-padded to this many digits (0: K as it is, MBDyn's default).
    #[default]
    None,
    Digits(usize),
    /// `compute`: zero-padded to ⌊log₁₀ count⌋ + 1 digits, count the number of analyses
    /// (MBDyn's formula: 10 analyses give `_00` … `_09`).
    Compute,
}

impl EigenFileSuffix {
    /// `_` and the number of analysis `index` of `count`.
    pub fn suffix(&self, index: usize, count: usize) -> String {
        let width = match self.width {
            SuffixWidth::None => 0,
            SuffixWidth::Digits(w) => w,
            SuffixWidth::Compute => count.max(1).ilog10() as usize + 1,
        };
        match &self.format {
            Some(f) if width == 0 => format!("_{}", Self::format(f, index).unwrap_or_else(|_| index.to_string())),
            _ => format!("_{index:0width$}"),
        }
    }

    /// `format` (a printf format with exactly one `d` or `i` conversion, flags `-0+ ` and a
    /// width allowed, no path separator) applied to `value`; `Err` says what is wrong with the format.
    pub fn format(format: &str, value: usize) -> Result<String, String> {
        if format.contains(['/', '\\']) {
            return Err(format!("the format \"{format}\" has a path separator: the files stay beside the output prefix"));
        }
        let mut out = String::new();
        let mut converted = false;
        let mut chars = format.chars().peekable();
        while let Some(ch) = chars.next() {
            if ch != '%' {
                out.push(ch);
                continue;
            }
            if chars.peek() == Some(&'%') {
                chars.next();
                out.push('%');
                continue;
            }
            let mut flags = String::new();
            while let Some(&f) = chars.peek().filter(|f| "-0+ ".contains(**f)) {
                flags.push(f);
                chars.next();
            }
            let mut digits = String::new();
            while let Some(&d) = chars.peek().filter(|d| d.is_ascii_digit()) {
                digits.push(d);
                chars.next();
            }
            match chars.next() {
                Some('d' | 'i') if !converted => converted = true,
                Some('d' | 'i') => return Err(format!("the format \"{format}\" has more than one conversion; it takes one integer")),
                other => {
                    let found = other.map_or("the end of the format".to_string(), |c| format!("'{c}'"));
                    return Err(format!("the format \"{format}\" takes one integer conversion (%d or %i, with flags -0+ and a width), found {found} after '%'"));
                }
            }
            let width: usize = digits.parse().unwrap_or(0);
            if width > 64 {
                return Err(format!("the format \"{format}\" asks for a width of {width} characters, more than 64"));
            }
            let sign = if flags.contains('+') { "+" } else if flags.contains(' ') { " " } else { "" };
            let number = format!("{sign}{value}");
            if flags.contains('-') {
                out.push_str(&format!("{number:<width$}"));
            } else if flags.contains('0') {
                out.push_str(sign);
                out.push_str(&format!("{value:0w$}", w = width.saturating_sub(sign.len())));
            } else {
                out.push_str(&format!("{number:>width$}"));
            }
        }
        if !converted {
            return Err(format!("the format \"{format}\" has no integer conversion (%d or %i) for the analysis number"));
        }
        Ok(out)
    }
}

/// Where MBDyn's `abort after` stops a run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AbortAfter {
    Input,
    Assembly,
    Derivatives,
    DummySteps,
}

/// The retries of MBDyn's `derivatives coefficient: auto` (defaults: 6 retries each way,
/// factor 10; solver.cc `iDerivativesCoefMaxIter`, `dDerivativesCoefFactor`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AutoCoefficient {
    pub retries: usize,
    pub factor: f64,
}

impl Default for AutoCoefficient {
    fn default() -> Self {
        AutoCoefficient { retries: 6, factor: 10.0 }
    }
}

impl AutoCoefficient {
    /// The coefficients tried in turn from `initial`: `initial`, `initial fᵏ` for
    /// k = 1…retries, then `initial / fᵏ` for k = 1…retries.
    pub fn sequence(self, initial: f64) -> impl Iterator<Item = f64> {
        let up = (0..=self.retries).map(move |k| initial * self.factor.powi(k as i32));
        let down = (1..=self.retries).map(move |k| initial / self.factor.powi(k as i32));
        up.chain(down)
    }
}

/// How Newton measures the residual for its convergence test.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ResidualNorm {
    /// Largest entry, `‖F‖∞` (romdyn's default).
    #[default]
    Max,
    /// `‖F‖₂`, MBDyn's `test, norm` (its default).
    Euclidean,
}

/// An initial-value problem (SI units: s).
#[derive(Clone, Debug, PartialEq)]
pub struct InitialValueProblem {
    pub initial_time: f64,
    pub final_time: f64,
    pub time_step: f64,
    pub method: Method,
    /// The method's asymptotic spectral radius when the file gives a drive that varies (of
    /// time or of the model's state: MBDyn's `ms, DRIVE`, `Bathe, DRIVE`): evaluated before
    /// each regular step at its new time with the last solution, as MBDyn's
    /// `MultistepSolver::SetCoef`; `method` holds its value at the initial time (NaN when it
    /// reads the state). `None`: the radius is constant.
    pub varying_radius: Option<crate::element::drive::Drive>,
    /// Newton converges when the residual's norm is below this (N, N m, …).
    pub tolerance: f64,
    /// The norm of that test.
    pub residual_norm: ResidualNorm,
    /// Newton also stops when its increment's largest entry is below this, with the
    /// residual within 1e3 times the tolerance (0: never, MBDyn's default, which tests the
    /// residual alone).
    pub increment_tolerance: f64,
    pub max_iterations: usize,
    /// MBDyn's `nonlinear solver: newton raphson, modified, …`: a time step's iteration whose
    /// residual fell fast keeps the last factorization
    /// (`solve::NewtonWorkspace::keep_jacobian_below`; MBDyn keeps it for a fixed number of
    /// iterations). `false` (the default, MBDyn's too): every iteration assembles and factors
    /// its Jacobian.
    pub modified_newton: bool,
    /// Tolerance and iteration limit of the consistent initial derivatives.
    pub derivatives_tolerance: f64,
    pub derivatives_max_iterations: usize,
    /// The initial derivatives solve with dCoef = this factor times the time step (MBDyn's
    /// `derivatives coefficient`).
    pub derivatives_coefficient: f64,
    /// MBDyn's `derivatives coefficient: auto`: when the derivatives do not converge, they
    /// are solved again with the coefficient multiplied by `factor` up to `retries` times,
    /// then divided by it as many times (stepsol.cc, `DerivativeSolver::Advance`).
    pub derivatives_coefficient_auto: Option<AutoCoefficient>,
    /// Nodes written to the motion file and how (`None`: every node, every step).
    pub output: Option<MotionOutput>,
    pub eigenanalysis: Option<EigenRequest>,
    pub abort_after: Option<AbortAfter>,
    /// MBDyn's initial assembly before the run (control data).
    pub assembly: InitialAssembly,
}

/// MBDyn's initial joint assembly (input manual, "Control Data", §Assembly-Related Cards;
/// dataman.cc defaults): penalty springs of stiffness `position_stiffness` on every node's
/// position and orientation parameters and `velocity_stiffness` on its velocities hold the
/// configuration written in the file while the joints are made to hold.
#[derive(Clone, Debug, PartialEq)]
pub struct InitialAssembly {
    /// `skip initial joint assembly`: the configuration is used as written.
    pub skip: bool,
    /// `initial stiffness: POSITION [, VELOCITY]` (default 1, 1; a penalty, not SI).
    pub position_stiffness: f64,
    pub velocity_stiffness: f64,
    /// `omega rotates: yes`: the written angular velocity turns with the node.
    pub omega_rotates: bool,
    /// `tolerance`: on `sqrt(|F|² / (1 + |X|²))` (default 1e-6).
    pub tolerance: f64,
    /// `max iterations` (default 1: a correct model needs none).
    pub max_iterations: usize,
    /// A node's own `assembly, POSITION, VELOCITY, OMEGA_ROTATES` settings, by label.
    pub nodes: Vec<(super::Label, NodeAssembly)>,
}

/// One node's penalty settings in the initial assembly.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NodeAssembly {
    pub position_stiffness: f64,
    pub velocity_stiffness: f64,
    pub omega_rotates: bool,
}

impl Default for InitialAssembly {
    fn default() -> Self {
        InitialAssembly { skip: false, position_stiffness: 1.0, velocity_stiffness: 1.0, omega_rotates: false, tolerance: 1e-6, max_iterations: 1, nodes: Vec::new() }
    }
}

impl InitialAssembly {
    /// The settings of the node with `label`.
    pub fn node(&self, label: super::Label) -> NodeAssembly {
        self.nodes.iter().find(|(l, _)| *l == label).map(|(_, n)| *n).unwrap_or(NodeAssembly {
            position_stiffness: self.position_stiffness,
            velocity_stiffness: self.velocity_stiffness,
            omega_rotates: self.omega_rotates,
        })
    }
}

impl Default for InitialValueProblem {
    fn default() -> Self {
        InitialValueProblem {
            initial_time: 0.0,
            final_time: 0.0,
            time_step: 1e-3,
            method: Method::Ms { rho: 0.6 },
            varying_radius: None,
            tolerance: 1e-6,
            residual_norm: ResidualNorm::Max,
            increment_tolerance: 1e-12,
            max_iterations: 20,
            modified_newton: false,
            derivatives_tolerance: 1e-6,
            derivatives_max_iterations: 20,
            derivatives_coefficient: 1e-6,
            derivatives_coefficient_auto: None,
            output: None,
            eigenanalysis: None,
            abort_after: None,
            assembly: InitialAssembly::default(),
        }
    }
}

/// How a motion file writes orientations (MBDyn's `orientation description`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum OrientationOutput {
    /// Euler 1-2-3 angles in degrees (MBDyn's default).
    #[default]
    Euler123Degrees,
    /// Euler 3-1-3 angles in degrees.
    Euler313Degrees,
    /// Euler 3-2-1 angles in degrees.
    Euler321Degrees,
    /// Rotation vector φ n in radians.
    RotationVector,
    /// The nine entries of R by rows.
    Matrix,
    /// No orientation columns: MBDyn 1.7.3's rows of a relative-frame dummy node, whose
    /// orientation description it reads only after an `orientation` (strnode.cc,
    /// `ReadStructNode`) and otherwise leaves unknown, which its `Output` writes as nothing.
    Unwritten,
}

/// Where a written node's motion comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum NodeSource {
    /// A node of the model.
    Node(super::Label),
    /// A point and frame rigidly attached to another written entry (MBDyn's `dummy, BASE,
    /// offset`): `x = x_b + R_b o`, `R = R_b R_o`, `v = v_b + ω_b × R_b o`, `ω = ω_b`;
    /// `base` indexes the list of written nodes.
    Offset { base: usize, offset: crate::kinematics::Vec3, orientation: crate::kinematics::Mat3 },
    /// The motion of entry `base` seen from entry `reference` (MBDyn's `dummy, BASE,
    /// relative frame, REF`): `x = R_rᵀ (x_b − x_r)`, `R = R_rᵀ R_b`,
    /// `v = R_rᵀ (v_b − v_r − ω_r × (x_b − x_r))`, `ω = R_rᵀ (ω_b − ω_r)`.
    RelativeFrame { base: usize, reference: usize },
}

/// One node of the motion file.
#[derive(Clone, Debug, PartialEq)]
pub struct WrittenNode {
    pub label: super::Label,
    pub source: NodeSource,
    /// Whether its rows are written (MBDyn's `output, no` and `default output`); a node
    /// that is not written may still be the base of one that is.
    pub written: bool,
    pub orientation: OrientationOutput,
    /// Whether its rows end with the linear and angular accelerations (MBDyn's
    /// `accelerations, yes` on a dynamic node or `default output: accelerations`; a dummy
    /// node's follow its base, a relative frame's both nodes).
    pub accelerations: bool,
}

/// The motion file's rows: nodes in file order, every `every`-th step (MBDyn's `output
/// frequency`; step 0, the initial state, is always written).
#[derive(Clone, Debug, PartialEq)]
pub struct MotionOutput {
    pub nodes: Vec<WrittenNode>,
    pub every: usize,
    /// MBDyn's `output meter: DRIVE` (dataman2.cc, `DataManager::Output`): a step's rows
    /// are written when the drive is not 0 at its time (step 0 included), instead of every
    /// `every`-th step.
    pub meter: Option<crate::element::drive::Drive>,
    /// Digits after the decimal point of each number (MBDyn's `output precision`, which
    /// writes scientific notation with that many; MBDyn's default is 6); `None`: romdyn's
    /// default, [`MotionOutput::DEFAULT_DIGITS`].
    pub precision: Option<usize>,
}

impl MotionOutput {
    /// Digits after the decimal point when the file sets none: 12, enough for a
    /// double's 16 significant digits to within 1e-12 relative.
    pub const DEFAULT_DIGITS: usize = 12;

    pub fn digits(&self) -> usize {
        self.precision.unwrap_or(Self::DEFAULT_DIGITS)
    }
}

#[cfg(test)]
mod tests {
    use super::{EigenFileSuffix, SuffixWidth};

    #[test]
    fn suffix_format_renders_as_printf() {
        // C printf of 7 with each format (the C standard's flags: '-' left, '0' zeros, '+' and ' ' sign).
        for (format, expected) in [("%d", "7"), ("%i", "7"), ("%03d", "007"), ("%5d", "    7"), ("%-3d|", "7  |"), ("%+d", "+7"), ("% 03d", " 07"), ("m%%%d", "m%7")] {
            assert_eq!(EigenFileSuffix::format(format, 7).as_deref(), Ok(expected), "{format}");
        }
        let compute = EigenFileSuffix { width: SuffixWidth::Compute, format: None };
        assert_eq!(compute.suffix(9, 10), "_09");
        assert_eq!(compute.suffix(99, 100), "_099");
        assert_eq!(compute.suffix(8, 9), "_8");
        assert_eq!(EigenFileSuffix { width: SuffixWidth::Digits(0), format: None }.suffix(3, 4), "_3");
        // A width wins over a format; a width of 0 leaves the format.
        let format = Some("m%d".to_string());
        assert_eq!(EigenFileSuffix { width: SuffixWidth::Digits(2), format: format.clone() }.suffix(3, 4), "_03");
        assert_eq!(EigenFileSuffix { width: SuffixWidth::Digits(0), format }.suffix(3, 4), "_m3");
    }
}
