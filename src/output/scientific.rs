//! Numbers in scientific notation exactly as Rust's `format!("{v:.D$e}")` writes them
//! (`-1.2345678901234e-3`, `1.0000000000000e0`), byte for byte, for the per-step writers
//! (`.mov`, `.act`, `.bst`): the digits are formed by exact integer arithmetic, without
//! `core::fmt`'s digit generation, which took about a tenth of a whole run on the
//! benchmark models (issue 36).
//!
//! `|v| = m 2^q` with an integer `m < 2^53`; for the decimal exponent `E` of `|v|`, the
//! written digits are `N = round(|v| 10^(D − E))`, `10^D ≤ N < 10^(D+1)`, computed as
//! `m 5^s 2^(q + s)` with `s = D − E` in 128-bit integers, the remainder compared exactly
//! with one half. Where that does not fit (`s` outside 0..=32: values below about
//! `10^(D−32)` or of `10^(D+1)` and above, subnormals), where the remainder is exactly one
//! half (Rust's tie rule decides), for infinities and NaN, and for `D > 17`, the number is
//! written by `format!` itself. Zeros (half the numbers of a planar model's `.mov`) are
//! written directly: `0.000e0`, `-0.000e0` for `-0.0`, as `format!` writes them.

use std::io::Write;

/// `base^k` for `k = 0..N`.
const fn powers<const N: usize>(base: u128) -> [u128; N] {
    let mut t = [1u128; N];
    let mut k = 1;
    while k < N {
        t[k] = t[k - 1] * base;
        k += 1;
    }
    t
}

/// `5^k` for `k = 0..=32` (`5^32 < 2^75`, so that `m 5^k < 2^128` for `m < 2^53`).
const POW5: [u128; 33] = powers(5);

/// `10^k` for `k = 0..=18`.
const POW10: [u128; 19] = powers(10);

/// Appends `v` as `format!("{v:.digits$e}")` writes it.
pub fn push_scientific(out: &mut Vec<u8>, v: f64, digits: usize) {
    if !push_exact(out, v, digits) {
        // Writing into a Vec does not fail.
        let _ = write!(out, "{v:.digits$e}");
    }
}

/// `floor(|v| 10^s)` and whether the remainder is below, at or above one half, for `|v| =
/// m 2^q`; `None` when it does not fit 128 bits.
fn scaled(m: u64, q: i32, s: i32) -> Option<(u64, std::cmp::Ordering)> {
    if !(0..=32).contains(&s) {
        return None;
    }
    let num = m as u128 * POW5[s as usize];
    let shift = q + s;
    if shift >= 0 {
        let shift = shift as u32;
        if num.leading_zeros() < shift + 64 {
            return None;
        }
        return Some(((num << shift) as u64, std::cmp::Ordering::Less));
    }
    let k = (-shift) as u32;
    if k >= 127 {
        return None;
    }
    let whole = num >> k;
    if whole > u64::MAX as u128 {
        return None;
    }
    let rest = num & ((1u128 << k) - 1);
    Some((whole as u64, rest.cmp(&(1u128 << (k - 1)))))
}

/// The digits by integer arithmetic; `false` (nothing written) where [`push_scientific`]
/// leaves the number to `format!`.
fn push_exact(out: &mut Vec<u8>, v: f64, digits: usize) -> bool {
    if !v.is_finite() || digits > 17 {
        return false;
    }
    if v == 0.0 {
        push_zero(out, v.is_sign_negative(), digits);
        return true;
    }
    let bits = v.abs().to_bits();
    let biased = (bits >> 52) as i32;
    if biased == 0 {
        return false;
    }
    let m = (bits & ((1u64 << 52) - 1)) | (1u64 << 52);
    let q = biased - 1075;
    let d = digits as i32;
    let (low, high) = (POW10[digits] as u64, POW10[digits + 1] as u64);
    // The decimal exponent: floor(log10 2^b) of the leading bit's power b, which is E or
    // E − 1, corrected by the digits' count.
    let b = q + 52;
    let mut e = (b * 78_913).div_euclid(1 << 18);
    let mut tries = 0;
    let (mut n, rest) = loop {
        let Some((n, rest)) = scaled(m, q, d - e) else { return false };
        if n < low {
            e -= 1;
        } else if n >= high {
            e += 1;
        } else {
            break (n, rest);
        }
        tries += 1;
        if tries > 2 {
            return false;
        }
    };
    match rest {
        std::cmp::Ordering::Equal => return false,
        std::cmp::Ordering::Greater => n += 1,
        std::cmp::Ordering::Less => {}
    }
    if n == high {
        n = low;
        e += 1;
    }
    // Sign, digits with the point after the first, `e`, exponent: at most 1 + 19 + 1 + 5.
    let mut text = [0u8; 32];
    let mut at = 0;
    if v < 0.0 {
        text[at] = b'-';
        at += 1;
    }
    let mut mantissa = [0u8; 18];
    for slot in mantissa[..=digits].iter_mut().rev() {
        *slot = b'0' + (n % 10) as u8;
        n /= 10;
    }
    text[at] = mantissa[0];
    at += 1;
    if digits > 0 {
        text[at] = b'.';
        text[at + 1..at + 1 + digits].copy_from_slice(&mantissa[1..=digits]);
        at += 1 + digits;
    }
    text[at] = b'e';
    at += 1;
    if e < 0 {
        text[at] = b'-';
        at += 1;
    }
    let magnitude = e.unsigned_abs();
    let len = if magnitude >= 100 { 3 } else if magnitude >= 10 { 2 } else { 1 };
    let mut rest = magnitude;
    for k in (0..len).rev() {
        text[at + k] = b'0' + (rest % 10) as u8;
        rest /= 10;
    }
    at += len;
    out.extend_from_slice(&text[..at]);
    true
}

/// Appends `n` in decimal, as `format!("{n}")` writes it (the per-step writers' labels and
/// counts).
pub fn push_unsigned(out: &mut Vec<u8>, n: u64) {
    let mut text = [0u8; 20];
    out.extend_from_slice(decimal(n, &mut text));
}

/// `n` in decimal, written digit by digit into `text` without allocating (also what the
/// command line's allocator prints when memory runs out); the digits are the returned tail.
pub fn decimal(mut n: u64, text: &mut [u8; 20]) -> &[u8] {
    let mut at = text.len();
    loop {
        at -= 1;
        text[at] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    &text[at..]
}

/// A zero with `digits` zeros after the point (`D = 0`: no point), signed as `format!`
/// signs `-0.0`.
fn push_zero(out: &mut Vec<u8>, negative: bool, digits: usize) {
    const ZEROS: &[u8; 17] = b"00000000000000000";
    if negative {
        out.push(b'-');
    }
    out.push(b'0');
    if digits > 0 {
        out.push(b'.');
        out.extend_from_slice(&ZEROS[..digits]);
    }
    out.extend_from_slice(b"e0");
}

#[cfg(test)]
mod tests {
    use super::{push_scientific, push_unsigned};

    /// Decimal integers byte for byte as `format!` writes them (the independent source):
    /// every power of ten and its neighbours up to `u64::MAX`, and pseudo-random values.
    #[test]
    fn writes_integers_as_format_writes() {
        let mut values = vec![0, 1, 9, u64::MAX, u64::MAX - 1, u32::MAX as u64];
        let mut p = 1u64;
        while let Some(next) = p.checked_mul(10) {
            values.extend([p - 1, p, p + 1]);
            p = next;
        }
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..10_000 {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            values.extend([seed, seed >> (seed % 64)]);
        }
        for n in values {
            let mut out = b"x".to_vec();
            push_unsigned(&mut out, n);
            assert_eq!(String::from_utf8(out).unwrap(), format!("x{n}"));
        }
    }

    fn check(v: f64, digits: usize) {
        let mut out = Vec::new();
        push_scientific(&mut out, v, digits);
        let expected = format!("{v:.digits$e}");
        assert_eq!(String::from_utf8(out).unwrap(), expected, "{v:e} ({:#x}) with {digits} digits", v.to_bits());
    }

    /// Byte for byte what `format!` writes (the independent source): pseudo-random bit
    /// patterns across the whole range and in the range motion files hold, every precision
    /// up to 17 and beyond, and the edges: powers of ten and their neighbours, rounding
    /// that carries into a new decade, exact ties, zeros, subnormals, infinities, NaN.
    #[test]
    fn writes_what_format_writes() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for _ in 0..200_000 {
            let bits = next();
            let any = f64::from_bits(bits);
            // Exponents of 1e-30 … 1e20, where the exact path runs.
            let sign = if bits & 1 == 1 { -1.0 } else { 1.0 };
            let typical = sign * (1.0 + (bits >> 12) as f64 / (1u64 << 52) as f64) * 2f64.powi((bits % 167) as i32 - 100);
            for digits in [13, 12, 6, (bits % 19) as usize] {
                check(any, digits);
                check(typical, digits);
            }
        }
        let mut edges = vec![0.0, -0.0, f64::INFINITY, f64::NEG_INFINITY, f64::NAN, f64::MIN_POSITIVE, 5e-324, f64::MAX, 0.5, 2.5, 0.125, 100000000000005.0, 9.9999999999999951, 9.99999999999995, 0.99999999999999994, 1.0 - f64::EPSILON, 123456789012345.6];
        for k in -40..=25 {
            let p = 10f64.powi(k);
            edges.extend([p, p.next_up(), p.next_down(), -p, 9.5 * p, 9.99999999999995 * p]);
        }
        for v in edges {
            for digits in 0..=20 {
                check(v, digits);
            }
        }
    }
}
