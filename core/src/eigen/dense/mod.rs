//! Dense generalized eigenanalysis of a linear DAE ([`super::ModalAnalysis::compute`],
//! [`super::ModalAnalysis::of_dae`]): degenerate pencils refused before QZ, rows and columns
//! balanced, QZ with right and left vectors on the whole pencil or, after the exact deflation
//! of the eigenvalues the constraint structure fixes (eqs. 29–30), on its dynamic part; an
//! undamped structure at rest's dynamic part at half its size (`second_order`).

mod balance;
mod deflate;
mod deflated_qz;
mod degenerate;
mod qz;
mod second_order;
