//! The one Python pickle the MultiBodySync export needs: a 0-d numpy object array holding a
//! dict of lists of 4x4 `float64` matrices, as `numpy.array({...})` would build it.
//!
//! The pickle is protocol 2 and uses only these opcodes (Python's `pickletools` names):
//! `PROTO 2`, `GLOBAL 'numpy array'` (the function `numpy.array`, memoised with `BINPUT`
//! and fetched again with `BINGET`), `EMPTY_DICT`, `EMPTY_LIST`, `MARK`, `SETITEMS`,
//! `APPENDS`, `TUPLE1`, `REDUCE` (call a function on a tuple), `BINUNICODE` (text keys),
//! `BININT1` / `BININT` (integer keys), `BINFLOAT` (a big-endian `float64`) and `STOP`.
//! Unpickled, it evaluates
//!
//! ```python
//! numpy.array({key: [numpy.array([[m00, m01, m02, m03], ...]), ...], ...})
//! ```
//!
//! which is a 0-d array of dtype `object` whose `.item()` is the dict; each matrix is a
//! `float64` array of shape (4, 4). Numbers keep every bit (`BINFLOAT` is exact).

/// A dict key: text or a small integer.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Key {
    /// A `str` key.
    Text(String),
    /// An `int` key.
    Int(i32),
}

/// A 4x4 matrix, row by row.
pub type Matrix4 = [[f64; 4]; 4];

const PROTO: u8 = 0x80;
const GLOBAL: u8 = b'c';
const BINPUT: u8 = b'q';
const BINGET: u8 = b'h';
const EMPTY_DICT: u8 = b'}';
const EMPTY_LIST: u8 = b']';
const MARK: u8 = b'(';
const SETITEMS: u8 = b'u';
const APPENDS: u8 = b'e';
const TUPLE1: u8 = 0x85;
const REDUCE: u8 = b'R';
const BINUNICODE: u8 = b'X';
const BININT1: u8 = b'K';
const BININT: u8 = b'J';
const BINFLOAT: u8 = b'G';
const STOP: u8 = b'.';

/// Pushes `numpy.array` (memo slot 0, stored by the first call).
fn numpy_array(out: &mut Vec<u8>, first: &mut bool) {
    if *first {
        out.push(GLOBAL);
        out.extend_from_slice(b"numpy\narray\n");
        out.extend_from_slice(&[BINPUT, 0]);
        *first = false;
    } else {
        out.extend_from_slice(&[BINGET, 0]);
    }
}

fn key(out: &mut Vec<u8>, key: &Key) {
    match key {
        Key::Text(text) => {
            out.push(BINUNICODE);
            let len = u32::try_from(text.len()).expect("a short key");
            out.extend_from_slice(&len.to_le_bytes());
            out.extend_from_slice(text.as_bytes());
        }
        Key::Int(n) => match u8::try_from(*n) {
            Ok(small) => out.extend_from_slice(&[BININT1, small]),
            Err(_) => {
                out.push(BININT);
                out.extend_from_slice(&n.to_le_bytes());
            }
        },
    }
}

/// `numpy.array([[...], ...])` of a 4x4 matrix.
fn matrix(out: &mut Vec<u8>, m: &Matrix4, first: &mut bool) {
    numpy_array(out, first);
    out.extend_from_slice(&[EMPTY_LIST, MARK]);
    for row in m {
        out.extend_from_slice(&[EMPTY_LIST, MARK]);
        for v in row {
            out.push(BINFLOAT);
            out.extend_from_slice(&v.to_be_bytes());
        }
        out.push(APPENDS);
    }
    out.extend_from_slice(&[APPENDS, TUPLE1, REDUCE]);
}

/// The pickle of `numpy.array({key: [matrix, ...], ...})`, keys in the order given (a
/// Python dict keeps insertion order).
pub fn numpy_dict_of_matrix_lists(entries: &[(Key, Vec<Matrix4>)]) -> Vec<u8> {
    let mut out = vec![PROTO, 2];
    let mut first = true;
    numpy_array(&mut out, &mut first);
    out.extend_from_slice(&[EMPTY_DICT, MARK]);
    for (k, matrices) in entries {
        key(&mut out, k);
        out.extend_from_slice(&[EMPTY_LIST, MARK]);
        for m in matrices {
            matrix(&mut out, m, &mut first);
        }
        out.push(APPENDS);
    }
    out.extend_from_slice(&[SETITEMS, TUPLE1, REDUCE, STOP]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const IDENTITY: Matrix4 =
        [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]];

    #[test]
    fn the_pickle_has_the_documented_opcodes() {
        let bytes = numpy_dict_of_matrix_lists(&[
            (Key::Text("cam".into()), vec![IDENTITY]),
            (Key::Int(300), vec![]),
        ]);
        let mut expected = vec![0x80, 2, b'c'];
        expected.extend_from_slice(b"numpy\narray\n");
        expected.extend_from_slice(&[b'q', 0, b'}', b'(']);
        expected.extend_from_slice(&[b'X', 3, 0, 0, 0, b'c', b'a', b'm', b']', b'(']);
        expected.extend_from_slice(&[b'h', 0, b']', b'(']);
        for row in IDENTITY {
            expected.extend_from_slice(b"](");
            for v in row {
                expected.push(b'G');
                expected.extend_from_slice(&v.to_be_bytes());
            }
            expected.push(b'e');
        }
        expected.extend_from_slice(&[b'e', 0x85, b'R', b'e']);
        expected.extend_from_slice(&[b'J', 0x2c, 0x01, 0, 0, b']', b'(', b'e']);
        expected.extend_from_slice(&[b'u', 0x85, b'R', b'.']);
        assert_eq!(bytes, expected);
    }

    #[test]
    fn small_integer_keys_take_one_byte() {
        let bytes = numpy_dict_of_matrix_lists(&[(Key::Int(7), vec![])]);
        assert!(bytes.windows(2).any(|w| w == [b'K', 7]));
    }
}
