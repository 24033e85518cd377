//! Round trip through a minimal Level-5 reader (independent of the writer's helpers).

use super::*;

#[derive(Debug, PartialEq)]
enum Value {
    Real { dims: Vec<usize>, data: Vec<f64> },
    Complex { dims: Vec<usize>, re: Vec<f64>, im: Vec<f64> },
    Char(String),
    Cell(Vec<Value>),
}

fn u32_at(b: &[u8], i: usize) -> u32 {
    u32::from_le_bytes(b[i..i + 4].try_into().unwrap())
}

/// Reads one tagged element at `i`: (type, data, next offset).
fn tagged(b: &[u8], i: usize) -> (u32, &[u8], usize) {
    let (ty, n) = (u32_at(b, i), u32_at(b, i + 4) as usize);
    (ty, &b[i + 8..i + 8 + n], i + 8 + (n.next_multiple_of(8)))
}

fn read_matrix(body: &[u8]) -> (String, Value) {
    let (ty, flags, i) = tagged(body, 0);
    assert_eq!(ty, MI_UINT32);
    let class = u32_at(flags, 0) & 0xff;
    let complex = u32_at(flags, 0) & COMPLEX_FLAG != 0;
    let (_, dims, i) = tagged(body, i);
    let dims: Vec<usize> = dims.chunks(4).map(|c| i32::from_le_bytes(c.try_into().unwrap()) as usize).collect();
    let (_, name, mut i) = tagged(body, i);
    let name = String::from_utf8(name.to_vec()).unwrap();
    let f64s = |d: &[u8]| d.chunks(8).map(|c| f64::from_le_bytes(c.try_into().unwrap())).collect::<Vec<f64>>();
    let value = match class {
        MX_DOUBLE => {
            let (ty, re, j) = tagged(body, i);
            assert_eq!(ty, MI_DOUBLE, "doubles must be stored as miDOUBLE");
            if complex {
                let (_, im, _) = tagged(body, j);
                Value::Complex { dims, re: f64s(re), im: f64s(im) }
            } else {
                Value::Real { dims, data: f64s(re) }
            }
        }
        MX_CHAR => {
            let (_, d, _) = tagged(body, i);
            let units: Vec<u16> = d.chunks(2).map(|c| u16::from_le_bytes(c.try_into().unwrap())).collect();
            Value::Char(String::from_utf16(&units).unwrap())
        }
        MX_CELL => {
            let mut cells = Vec::new();
            for _ in 0..dims.iter().product::<usize>() {
                let (ty, inner, next) = tagged(body, i);
                assert_eq!(ty, MI_MATRIX);
                cells.push(read_matrix(inner).1);
                i = next;
            }
            Value::Cell(cells)
        }
        c => panic!("unexpected class {c}"),
    };
    (name, value)
}

fn read_file(b: &[u8]) -> Vec<(String, Value)> {
    assert!(b[..116].starts_with(b"MATLAB 5.0 MAT-file"));
    assert_eq!(&b[124..128], &[0x00, 0x01, b'I', b'M']);
    let mut out = Vec::new();
    let mut i = 128;
    while i < b.len() {
        let (ty, body, next) = tagged(b, i);
        assert_eq!(ty, MI_MATRIX);
        out.push(read_matrix(body));
        i = next;
    }
    out
}

#[test]
fn every_kind_round_trips() {
    let m = Mat::from_fn(2, 3, |i, j| (10 * i + j) as f64);
    let mut f = MatFile::new();
    f.add_matrix("A", &m).unwrap();
    f.add_complex_column("eigenvalues", &[c64::new(-0.5, 9.9), c64::new(-0.5, -9.9)]).unwrap();
    f.add_scalar("dCoef", 1e-3).unwrap();
    f.add_string("kind", "ordinary").unwrap();
    f.add_string_list("inputs", &["node 2 Fy".into(), "x²".into()]).unwrap();
    f.add_matrix("Empty", &Mat::zeros(0, 3)).unwrap();
    let got = read_file(&f.to_bytes());
    assert_eq!(got[0], ("A".into(), Value::Real { dims: vec![2, 3], data: vec![0., 10., 1., 11., 2., 12.] }));
    assert_eq!(got[1], ("eigenvalues".into(), Value::Complex { dims: vec![2, 1], re: vec![-0.5, -0.5], im: vec![9.9, -9.9] }));
    assert_eq!(got[2], ("dCoef".into(), Value::Real { dims: vec![1, 1], data: vec![1e-3] }));
    assert_eq!(got[3], ("kind".into(), Value::Char("ordinary".into())));
    assert_eq!(got[4], ("inputs".into(), Value::Cell(vec![Value::Char("node 2 Fy".into()), Value::Char("x²".into())])));
    assert_eq!(got[5], ("Empty".into(), Value::Real { dims: vec![0, 3], data: vec![] }));
}

#[test]
fn invalid_or_repeated_names_are_refused() {
    let mut f = MatFile::new();
    assert!(f.add_scalar("1x", 1.0).is_err());
    assert!(f.add_scalar("a b", 1.0).is_err());
    f.add_scalar("x", 1.0).unwrap();
    assert!(f.add_scalar("x", 2.0).is_err());
}
