//! Static equilibrium `F(y, 0, t) = 0`, loads and gravity ramped in `steps` increments.

use super::newton::{newton, NewtonWorkspace, NewtonFailure, NewtonSettings, Update};
use crate::dae::{Assembler, State};

/// Solves for the static equilibrium at time `st.t`, starting from `st`; derivatives are
/// set to zero and orientations re-based at the end.
pub fn static_solution(asm: &Assembler, st: &mut State, steps: usize, settings: &NewtonSettings) -> Result<usize, NewtonFailure> {
    st.yp.iter_mut().for_each(|x| *x = 0.0);
    let mut ws = NewtonWorkspace::new();
    let mut iterations = 0;
    let steps = steps.max(1);
    for k in 1..=steps {
        st.load = k as f64 / steps as f64;
        let done = newton(asm, st, Update::Static, settings, &mut ws).map_err(|mut failure| {
            let increment = format!("load increment {k} of {steps} (loads and gravity at {} of their value)", k as f64 / steps as f64);
            failure.reason = Some(failure.reason.take().map_or(increment.clone(), |r| format!("{increment}; {r}")));
            failure
        })?;
        iterations += done.iterations;
        st.rebase(&asm.dofs);
    }
    st.load = 1.0;
    Ok(iterations)
}
