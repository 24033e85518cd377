//! Sums and dot products in twice the working precision (Ogita, Rump & Oishi, "Accurate sum
//! and dot product", SIAM J. Sci. Comput. 26 (2005), algorithm `Dot2`): the result is as
//! accurate as if computed in quadruple precision and then rounded, for the price of a few
//! flops per term. The eigenvalues' last refinement uses it where a stiff model's terms cancel
//! (a beam's `uᵀ K v` sums axial and shear stiffnesses of 1e10 N to a bending value 1e7
//! times smaller, which plain sums carry with a relative error of ε · 1e7).

use faer::c64;

/// `a b = p + e` exactly (`e` by a fused multiply–add).
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// A running sum `hi + lo` in twice the working precision.
#[derive(Clone, Copy, Debug, Default)]
pub struct Compensated {
    hi: f64,
    lo: f64,
}

impl Compensated {
    /// Adds `x` (Knuth's TwoSum: the rounding error goes to `lo`).
    pub fn add(&mut self, x: f64) {
        let s = self.hi + x;
        let v = s - self.hi;
        self.lo += (self.hi - (s - v)) + (x - v);
        self.hi = s;
    }

    /// Adds the exact product `a b`.
    pub fn add_product(&mut self, a: f64, b: f64) {
        let (p, e) = two_prod(a, b);
        self.add(p);
        self.lo += e;
    }

    /// Adds `a (hi + lo)` of another compensated value.
    pub fn add_scaled(&mut self, a: f64, x: Compensated) {
        self.add_product(a, x.hi);
        self.add_product(a, x.lo);
    }

    /// The sum rounded to the working precision.
    pub fn value(self) -> f64 {
        self.hi + self.lo
    }
}

/// A complex compensated sum.
#[derive(Clone, Copy, Debug, Default)]
pub struct CompensatedComplex {
    pub re: Compensated,
    pub im: Compensated,
}

impl CompensatedComplex {
    /// Adds the exact product of the real `a` and the complex `z`.
    pub fn add_real_times(&mut self, a: f64, z: c64) {
        self.re.add_product(a, z.re);
        self.im.add_product(a, z.im);
    }

    /// Adds `z w` for a complex `z` and a compensated complex `w`.
    pub fn add_times(&mut self, z: c64, w: CompensatedComplex) {
        self.re.add_scaled(z.re, w.re);
        self.re.add_scaled(-z.im, w.im);
        self.im.add_scaled(z.re, w.im);
        self.im.add_scaled(z.im, w.re);
    }

    pub fn value(self) -> c64 {
        c64::new(self.re.value(), self.im.value())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cancellation_is_carried_exactly() {
        // 1e16 + 1 − 1e16 is 0 in plain doubles, 1 here; (1 + 2⁻⁵²)² − 1 − 2⁻⁵¹ = 2⁻¹⁰⁴ exactly.
        let mut s = Compensated::default();
        s.add(1e16);
        s.add(1.0);
        s.add(-1e16);
        assert_eq!(s.value(), 1.0);
        let a = 1.0 + f64::EPSILON;
        let mut t = Compensated::default();
        t.add_product(a, a);
        t.add(-1.0);
        t.add(-2.0 * f64::EPSILON);
        assert_eq!(t.value(), f64::EPSILON * f64::EPSILON);
    }
}
