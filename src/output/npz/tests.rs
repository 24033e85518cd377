//! Round trip through a minimal ZIP + .npy reader.

use super::*;
use crate::output::zip::crc32;

fn u16_at(b: &[u8], i: usize) -> usize {
    u16::from_le_bytes([b[i], b[i + 1]]) as usize
}
fn u32_at(b: &[u8], i: usize) -> u32 {
    u32::from_le_bytes(b[i..i + 4].try_into().unwrap())
}

/// (name, header dict, data) of each member, checking CRCs and the central directory.
fn members(b: &[u8]) -> Vec<(String, String, Vec<u8>)> {
    let end = b.len() - 22;
    assert_eq!(u32_at(b, end), 0x0605_4b50);
    let (n, cd) = (u16_at(b, end + 10), u32_at(b, end + 16) as usize);
    let mut out = Vec::new();
    let mut c = cd;
    for _ in 0..n {
        assert_eq!(u32_at(b, c), 0x0201_4b50);
        let (crc, size, nlen, offset) = (u32_at(b, c + 16), u32_at(b, c + 24) as usize, u16_at(b, c + 28), u32_at(b, c + 42) as usize);
        let name = String::from_utf8(b[c + 46..c + 46 + nlen].to_vec()).unwrap();
        assert_eq!(u32_at(b, offset), 0x0403_4b50);
        let start = offset + 30 + u16_at(b, offset + 26);
        let npy = &b[start..start + size];
        assert_eq!(crc32(npy), crc, "{name}");
        assert_eq!(&npy[..8], b"\x93NUMPY\x01\x00");
        let hlen = u16_at(npy, 8);
        assert_eq!((10 + hlen) % 64, 0, "data aligned to 64 bytes");
        let header = String::from_utf8(npy[10..10 + hlen].to_vec()).unwrap();
        out.push((name, header.trim_end().to_string(), npy[10 + hlen..].to_vec()));
        c += 46 + nlen;
    }
    out
}

#[test]
fn crc32_of_the_standard_check_string() {
    // CRC-32/ISO-HDLC check value of "123456789" is 0xCBF43926 (published catalogue).
    assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
}

#[test]
fn arrays_round_trip() {
    let mut w = NpzWriter::new();
    w.add_matrix("A", &Mat::from_fn(2, 3, |i, j| (10 * i + j) as f64)).unwrap();
    w.add_complex_column("eigenvalues", &[c64::new(-0.5, 9.9)]).unwrap();
    w.add_string_list("inputs", &["Fy".into(), "node 12".into()]).unwrap();
    w.add_scalar("dcoef", 1e-3).unwrap();
    assert!(w.add_scalar("A", 1.0).is_err());
    let m = members(&w.to_bytes());
    assert_eq!(m[0].0, "A.npy");
    assert_eq!(m[0].1, "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }");
    let a: Vec<f64> = m[0].2.chunks(8).map(|c| f64::from_le_bytes(c.try_into().unwrap())).collect();
    assert_eq!(a, [0., 1., 2., 10., 11., 12.]);
    assert_eq!(m[1].1, "{'descr': '<c16', 'fortran_order': False, 'shape': (1,), }");
    assert_eq!(m[1].2.len(), 16);
    assert_eq!(m[2].1, "{'descr': '<U7', 'fortran_order': False, 'shape': (2,), }");
    assert_eq!(m[2].2.len(), 2 * 7 * 4);
    assert_eq!(m[3].1, "{'descr': '<f8', 'fortran_order': False, 'shape': (), }");
}
