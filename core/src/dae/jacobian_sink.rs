//! The sink an element's Jacobian entries go through on their way to `J = a F_/ẏ + b F_/y`
//! (eq. 5): local rows and columns mapped to global equations and unknowns, `y` columns
//! times `b`, `ẏ` columns times `a`, δθ turned into the Gibbs parameters' columns
//! (`δθ = G δg`), the constraint form of eq. 30 applied.
//!
//! The entries come out in a fixed order for a fixed model, either with their positions
//! ([`Triplets`], which set up the LU's pattern) or as values alone in that order
//! ([`Values`]: a Newton iteration whose pattern is known maps no row or column and pushes
//! no index). Where an entry lands depends only on the sequence of local `(row, column)`
//! calls each element makes (slots, numbering and constraint form are fixed), so both
//! outputs also fold that sequence into a fingerprint ([`Shape`]): equal fingerprints,
//! equal positions; an element whose pattern changes with the state (a different branch, a
//! skipped entry) changes it, and the caller then assembles the positions again.

use super::state::NodeFrame;
use super::{Coefficients, DofMap, Triplets};
use crate::element::{Col, JacobianSink, Row};
use crate::kinematics::Mat3;
use crate::model::{ConstraintForm, NodeKind};

/// Maps an element's local row to its global equation (`None`: a momentum row of a static
/// node, which does not exist). `e` is the element's index (its scalar slots). Inlined into
/// the residual's sink, where it runs for every entry.
#[inline(always)]
pub(super) fn global_row(dofs: &DofMap, e: usize, slots: &[usize], first: usize, row: Row) -> Option<usize> {
    match row {
        Row::Scalar { slot } => Some(dofs.scalar_first + dofs.element_scalars[e][slot]),
        Row::Equilibrium { slot, comp } => Some(dofs.equilibrium_row(slots[slot]) + comp),
        Row::Momentum { slot, comp } => (dofs.node_kind[slots[slot]] == NodeKind::Dynamic).then(|| dofs.node_first[slots[slot]] + comp),
        Row::Constraint(k) => Some(first + k),
    }
}

/// A fingerprint of the local `(row, column)` calls of a whole assembly, in order
/// (FxHash's mixing step on a 64-bit code of each call): what decides the entries'
/// positions.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Shape(u64);

impl Shape {
    /// The fingerprint of an `n`-unknown model with `elements` elements, before any call.
    pub(super) fn of_model(n: usize, elements: usize) -> Self {
        Shape::default().with(n as u64).with(elements as u64)
    }

    #[inline]
    fn with(self, code: u64) -> Self {
        Shape((self.0.rotate_left(5) ^ code).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95))
    }

    /// The fingerprint after one more call.
    #[inline]
    fn call(self, row: Row, col: Col) -> Self {
        self.with(row_code(row) | col_code(col) << 32)
    }

    /// The fingerprint after a call with a block of one node's three columns of one kind
    /// (the first column says which).
    #[inline]
    fn block(self, rows: &[Row; 3], first_col: Col) -> Self {
        self.block_in(&rows.map(row_code), first_col)
    }

    /// [`Shape::block`] with the rows' codes given ([`row_code`]).
    #[inline]
    fn block_in(self, rows: &[u64; 3], first_col: Col) -> Self {
        self.with(col_code(first_col) | 1 << 63).with(rows[0]).with(rows[1]).with(rows[2])
    }

    /// A new element's calls follow.
    #[inline]
    pub(super) fn element(self, e: usize) -> Self {
        self.with(e as u64 | 1 << 62)
    }
}

/// A row as a number: its kind in the low 2 bits, then its slot and component (distinct
/// rows, distinct numbers, for slots and components below 2^13).
#[inline]
fn row_code(row: Row) -> u64 {
    let (kind, a, b) = match row {
        Row::Equilibrium { slot, comp } => (0, slot, comp),
        Row::Momentum { slot, comp } => (1, slot, comp),
        Row::Constraint(k) => (2, k, 0),
        Row::Scalar { slot } => (3, slot, 0),
    };
    kind | (a as u64) << 2 | (b as u64) << 17
}

/// A column as a number: its kind in the low 3 bits, then its slot and component.
#[inline]
fn col_code(col: Col) -> u64 {
    let (kind, a, b) = match col {
        Col::Position { slot, comp } => (0, slot, comp),
        Col::Rotation { slot, comp } => (1, slot, comp),
        Col::Velocity { slot, comp } => (2, slot, comp),
        Col::AngularVelocity { slot, comp } => (3, slot, comp),
        Col::Multiplier(k) => (4, k, 0),
        Col::Rate(k) => (5, k, 0),
        Col::ScalarValue { slot } => (6, slot, 0),
        Col::ScalarRate { slot } => (7, slot, 0),
    };
    kind | (a as u64) << 3 | (b as u64) << 18
}

/// Where the sink puts the entries.
pub(super) trait Entries {
    /// Whether the entries' global positions are wanted (`false`: values alone).
    const POSITIONS: bool;
    fn put(&mut self, row: usize, col: usize, value: f64);
}

impl Entries for Triplets {
    const POSITIONS: bool = true;
    #[inline]
    fn put(&mut self, row: usize, col: usize, value: f64) {
        self.push(row, col, value);
    }
}

/// The values alone, in the order of the triplets the same calls make.
pub(super) struct Values<'a>(pub &'a mut Vec<f64>);

impl Entries for Values<'_> {
    const POSITIONS: bool = false;
    #[inline]
    fn put(&mut self, _: usize, _: usize, value: f64) {
        self.0.push(value);
    }
}

/// One element's sink.
pub(super) struct Jacobian<'a, O: Entries> {
    pub dofs: &'a DofMap,
    pub element: usize,
    pub frames: &'a [NodeFrame],
    pub slots: &'a [usize],
    pub first: usize,
    pub c: Coefficients,
    pub out: &'a mut O,
    pub shape: Shape,
}

impl<O: Entries> Jacobian<'_, O> {
    /// Coefficient of a `y`-derivative in `row`: `y`-derivatives of holonomic constraint rows
    /// belong to `F_/ẏ` in the form of eq. 30.
    #[inline]
    fn y_coefficient(&self, row: Row) -> f64 {
        match row {
            Row::Constraint(k) if self.c.form == ConstraintForm::Scaled && self.dofs.is_multiplier(self.first + k) => self.c.a,
            _ => self.c.b,
        }
    }

    /// The global equation of `row` (any number when only values are wanted), `None` when
    /// it does not exist.
    #[inline]
    fn row(&self, row: Row) -> Option<usize> {
        if O::POSITIONS {
            return global_row(self.dofs, self.element, self.slots, self.first, row);
        }
        match row {
            Row::Momentum { slot, .. } => (self.dofs.node_kind[self.slots[slot]] == NodeKind::Dynamic).then_some(0),
            _ => Some(0),
        }
    }

    /// The first unknown of the node in `slot` (0 when only values are wanted).
    #[inline]
    fn node_first(&self, slot: usize) -> usize {
        if O::POSITIONS {
            self.dofs.node_first[self.slots[slot]]
        } else {
            0
        }
    }

    /// The unknown of the element's scalar node in `slot` (0 when only values are wanted).
    #[inline]
    fn scalar_unknown(&self, slot: usize) -> usize {
        if O::POSITIONS {
            self.dofs.scalar_first + self.dofs.element_scalars[self.element][slot]
        } else {
            0
        }
    }
}

/// The node columns a 3x3 block covers, when it is one kind of one node's.
fn node_block(cols: &[Col; 3]) -> Option<Col> {
    let first = cols[0];
    let same = match first {
        Col::Position { slot, comp: 0 } => *cols == Col::position(slot),
        Col::Rotation { slot, comp: 0 } => *cols == Col::rotation(slot),
        Col::Velocity { slot, comp: 0 } => *cols == Col::velocity(slot),
        Col::AngularVelocity { slot, comp: 0 } => *cols == Col::angular_velocity(slot),
        _ => false,
    };
    same.then_some(first)
}

impl<O: Entries> Jacobian<'_, O> {
    /// Row `i` of a block `m` of one node's columns of one kind (`block`, its first column)
    /// in equation `r`, whose `y` coefficient is `b`: 3 entries.
    #[inline(always)]
    fn put_block_row(&mut self, block: Col, r: usize, b: f64, m: &Mat3, i: usize) {
        let a = self.c.a;
        let mrow = m.row(i);
        // A block row times G (δθ = G δg) gives the row in the g columns: 3 entries.
        let (values, first) = match block {
            Col::Position { slot, .. } => (b * mrow, self.node_first(slot)),
            Col::Velocity { slot, .. } => (a * mrow, self.node_first(slot)),
            Col::Rotation { slot, .. } => (b * mrow * self.frames[self.slots[slot]].g_matrix, self.node_first(slot) + 3),
            Col::AngularVelocity { slot, .. } => {
                let fr = &self.frames[self.slots[slot]];
                (a * mrow * fr.g_matrix + b * mrow * fr.rate_derivative, self.node_first(slot) + 3)
            }
            Col::Multiplier(_) | Col::Rate(_) | Col::ScalarValue { .. } | Col::ScalarRate { .. } => unreachable!("node_block returns node columns only"),
        };
        for k in 0..3 {
            self.out.put(r, first + k, values[k]);
        }
    }

    /// A block whose columns are not one node's of one kind: entry by entry.
    fn add_entries(&mut self, rows: [Row; 3], cols: [Col; 3], m: &Mat3) {
        for (i, row) in rows.into_iter().enumerate() {
            for (j, col) in cols.into_iter().enumerate() {
                self.add(row, col, m[(i, j)]);
            }
        }
    }
}

impl<O: Entries> JacobianSink for Jacobian<'_, O> {
    fn add_block(&mut self, rows: [Row; 3], cols: [Col; 3], m: &Mat3) {
        let Some(block) = node_block(&cols) else {
            self.add_entries(rows, cols, m);
            return;
        };
        self.shape = self.shape.block(&rows, block);
        for (i, row) in rows.into_iter().enumerate() {
            let Some(r) = self.row(row) else { continue };
            let b = self.y_coefficient(row);
            self.put_block_row(block, r, b, m, i);
        }
    }

    /// As one [`JacobianSink::add_block`] per block (the same entries, values and
    /// fingerprint), the rows mapped once.
    fn add_blocks(&mut self, rows: [Row; 3], cols: &[[Col; 3]], m: &[Mat3]) {
        let mapped = rows.map(|row| (self.row(row), self.y_coefficient(row)));
        let codes = rows.map(row_code);
        for (c, m) in cols.iter().zip(m) {
            let Some(block) = node_block(c) else {
                self.add_entries(rows, *c, m);
                continue;
            };
            self.shape = self.shape.block_in(&codes, block);
            for (i, &(r, b)) in mapped.iter().enumerate() {
                if let Some(r) = r {
                    self.put_block_row(block, r, b, m, i);
                }
            }
        }
    }

    fn add(&mut self, row: Row, col: Col, v: f64) {
        self.shape = self.shape.call(row, col);
        let Some(i) = self.row(row) else { return };
        let scaled = self.c.form == ConstraintForm::Scaled;
        let b = self.y_coefficient(row);
        let a = self.c.a;
        match col {
            Col::Position { slot, comp } => self.out.put(i, self.node_first(slot) + comp, b * v),
            Col::Velocity { slot, comp } => self.out.put(i, self.node_first(slot) + comp, a * v),
            Col::Rotation { slot, comp } => {
                let (first, fr) = (self.node_first(slot) + 3, &self.frames[self.slots[slot]]);
                let g = fr.g_matrix;
                for k in 0..3 {
                    self.out.put(i, first + k, b * v * g[(comp, k)]);
                }
            }
            Col::AngularVelocity { slot, comp } => {
                let (first, fr) = (self.node_first(slot) + 3, &self.frames[self.slots[slot]]);
                let (g, rate) = (fr.g_matrix, fr.rate_derivative);
                for k in 0..3 {
                    self.out.put(i, first + k, a * v * g[(comp, k)] + b * v * rate[(comp, k)]);
                }
            }
            Col::Multiplier(k) => {
                // A multiplier is algebraic in eq. 30; any other own unknown (a velocity
                // constraint's, a coordinate) is a `y` like a position, with its row's
                // coefficient (the row of a holonomic constraint is `Φ/c`).
                let j = self.first + k;
                self.out.put(i, j, if scaled && self.dofs.is_multiplier(j) { a } else { b } * v)
            }
            Col::Rate(k) => self.out.put(i, self.first + k, a * v),
            // A scalar node's value is a `y` like a position, its derivative a `ẏ`.
            Col::ScalarValue { slot } => self.out.put(i, self.scalar_unknown(slot), b * v),
            Col::ScalarRate { slot } => self.out.put(i, self.scalar_unknown(slot), a * v),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Jacobian, Shape, Values};
    use crate::dae::{Assembler, Coefficients, State, Triplets};
    use crate::element::{Col, JacobianSink, Row};
    use crate::kinematics::{Mat3, Vec3};
    use crate::model::{ConstraintForm, ModelBuilder};

    /// [`JacobianSink::add_blocks`] against one [`JacobianSink::add_block`] per block (the
    /// path every element took before): the same triplets, bit for bit, the same values
    /// alone and the same fingerprint, on three moving, turned dynamic nodes (their `G` and
    /// `∂(G ġ)/∂g` are not trivial), for blocks of every node column kind and a block whose
    /// columns are not one node's, in force and momentum rows.
    #[test]
    fn blocks_at_once_are_the_blocks_one_by_one() {
        let mut b = ModelBuilder::new();
        for label in 1..=3 {
            let l = label as f64;
            b.dynamic_node(label, Vec3::new(l, 0.1 * l, 0.0), Mat3::identity(), Vec3::new(0.2, -l, 0.3), Vec3::new(0.5, 0.1 * l, -0.7));
        }
        let model = b.build().unwrap();
        let asm = Assembler::new(&model);
        let mut st = State::initial(&model, &asm.dofs);
        for (k, y) in st.y.iter_mut().enumerate() {
            *y += 0.1 * (k as f64).sin();
        }
        let frames = asm.frames(&st);
        let c = Coefficients::newton(0.37, ConstraintForm::Scaled);
        let slots = [0, 1, 2];
        let m = |k: usize| Mat3::from_fn(|i, j| ((10 * k + 3 * i + j) as f64 * 0.77).cos());
        let cols = [Col::position(0), Col::rotation(1), Col::velocity(2), Col::angular_velocity(0), [Col::Position { slot: 0, comp: 0 }, Col::Rotation { slot: 1, comp: 2 }, Col::Velocity { slot: 2, comp: 1 }], Col::rotation(2)];
        let blocks: Vec<Mat3> = (0..cols.len()).map(m).collect();
        let row_sets = [Row::force(1), Row::moment(0), Row::linear_momentum(2), Row::angular_momentum(1)];

        let (mut at_once, mut one_by_one) = (Triplets::new(asm.dofs.len), Triplets::new(asm.dofs.len));
        let (mut values_at_once, mut values_one_by_one) = (Vec::new(), Vec::new());
        let shapes = {
            let sink = |out: &mut Triplets, values: &mut Vec<f64>, together: bool| {
                let mut triplets = Jacobian { dofs: &asm.dofs, element: 0, frames: &frames, slots: &slots, first: 0, c, out, shape: Shape::default() };
                let mut alone = Jacobian { dofs: &asm.dofs, element: 0, frames: &frames, slots: &slots, first: 0, c, out: &mut Values(values), shape: Shape::default() };
                for rows in row_sets {
                    if together {
                        triplets.add_blocks(rows, &cols, &blocks);
                        alone.add_blocks(rows, &cols, &blocks);
                    } else {
                        for (c, m) in cols.iter().zip(&blocks) {
                            triplets.add_block(rows, *c, m);
                            alone.add_block(rows, *c, m);
                        }
                    }
                }
                (triplets.shape, alone.shape)
            };
            [sink(&mut at_once, &mut values_at_once, true), sink(&mut one_by_one, &mut values_one_by_one, false)]
        };
        assert_eq!(shapes[0], shapes[1]);
        assert_eq!(shapes[0].0, shapes[0].1);
        assert_eq!((&at_once.rows, &at_once.cols), (&one_by_one.rows, &one_by_one.cols));
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&at_once.values), bits(&one_by_one.values));
        assert_eq!(bits(&values_at_once), bits(&at_once.values));
        assert_eq!(bits(&values_one_by_one), bits(&one_by_one.values));
        // 4 row sets of 3 rows: 5 node blocks of 3 entries a row, and the mixed block's
        // position, rotation (3 entries, through G) and velocity columns.
        assert_eq!(at_once.values.len(), 4 * 3 * (5 * 3 + 5));
    }
}
