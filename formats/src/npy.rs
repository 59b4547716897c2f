//! NPY files (numpy's `.npy` format, version 1.0), as `numpy.save` writes them.
//!
//! A file is the magic string `\x93NUMPY`, the version bytes `1, 0`, the header's length
//! (little-endian `u16`), then the header: the text of a Python dict literal,
//! `{'descr': '<f4', 'fortran_order': False, 'shape': (2, 512, 3), }`, padded with spaces
//! and ended by `\n` so that magic, version, length and header together are a multiple of
//! 64 bytes; then the data, little-endian, in C order. An object array (`descr` `|O`) holds
//! a pickle instead of raw data ([`super::pickle`]).

/// The magic string every NPY file starts with.
const MAGIC: &[u8; 6] = b"\x93NUMPY";
/// Alignment of the data: magic + version + length + header is a multiple of it.
const ALIGN: usize = 64;

/// The header dict's text for `descr` and `shape`, C order.
fn header_dict(descr: &str, shape: &[usize]) -> String {
    let shape = match shape {
        [] => "()".to_string(),
        [n] => format!("({n},)"),
        _ => format!("({})", shape.iter().map(usize::to_string).collect::<Vec<_>>().join(", ")),
    };
    format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}")
}

/// Magic, version, length and padded header of an array of `descr` and `shape`: the bytes
/// before its data.
pub fn header(descr: &str, shape: &[usize]) -> Vec<u8> {
    let dict = header_dict(descr, shape);
    // 6 magic + 2 version + 2 length + dict + padding + '\n'.
    let unpadded = MAGIC.len() + 4 + dict.len() + 1;
    let padding = (ALIGN - unpadded % ALIGN) % ALIGN;
    let header_len = dict.len() + padding + 1;
    let mut out = Vec::with_capacity(unpadded + padding);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&[1, 0]);
    out.extend_from_slice(
        &u16::try_from(header_len).expect("a header of a few dimensions is short").to_le_bytes(),
    );
    out.extend_from_slice(dict.as_bytes());
    out.resize(out.len() + padding, b' ');
    out.push(b'\n');
    out
}

/// An NPY file of `float32` values (`<f4`), given in C order.
pub fn f32_array(shape: &[usize], values: &[f32]) -> Vec<u8> {
    debug_assert_eq!(values.len(), shape.iter().product::<usize>());
    let mut out = header("<f4", shape);
    out.reserve(4 * values.len());
    for v in values {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out
}

/// An NPY file of `int64` values (`<i8`), given in C order.
pub fn i64_array(shape: &[usize], values: &[i64]) -> Vec<u8> {
    debug_assert_eq!(values.len(), shape.iter().product::<usize>());
    let mut out = header("<i8", shape);
    out.reserve(8 * values.len());
    for v in values {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out
}

/// An NPY file of a 0-d object array (`|O`, shape `()`) whose payload is `pickle`: numpy
/// reads it by unpickling the payload and returning the object it gives.
pub fn object_scalar(pickle: &[u8]) -> Vec<u8> {
    let mut out = header("|O", &[]);
    out.extend_from_slice(pickle);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dict_text(file: &[u8]) -> (usize, String) {
        assert_eq!(&file[..6], MAGIC);
        assert_eq!(&file[6..8], &[1, 0]);
        let len = usize::from(u16::from_le_bytes([file[8], file[9]]));
        (10 + len, String::from_utf8(file[10..10 + len].to_vec()).expect("ASCII header"))
    }

    #[test]
    fn headers_are_aligned_to_64_bytes_and_hold_the_dict() {
        for (descr, shape, dict) in [
            (
                "<f4",
                vec![2, 512, 3],
                "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 512, 3), }",
            ),
            ("<i8", vec![2, 96], "{'descr': '<i8', 'fortran_order': False, 'shape': (2, 96), }"),
            ("<i8", vec![7], "{'descr': '<i8', 'fortran_order': False, 'shape': (7,), }"),
            ("|O", vec![], "{'descr': '|O', 'fortran_order': False, 'shape': (), }"),
        ] {
            let bytes = header(descr, &shape);
            assert_eq!(bytes.len() % 64, 0, "{descr} {shape:?}");
            let (end, text) = dict_text(&bytes);
            assert_eq!(end, bytes.len());
            assert!(text.ends_with('\n'));
            assert_eq!(text.trim_end_matches('\n').trim_end_matches(' '), dict);
        }
    }

    #[test]
    fn data_follows_the_header_little_endian() {
        let file = f32_array(&[1, 2], &[1.0, -2.5]);
        let h = header("<f4", &[1, 2]).len();
        assert_eq!(h, 128, "a 60-character dict needs a second 64-byte block");
        assert_eq!(file.len(), h + 8);
        assert_eq!(&file[h..h + 4], &1.0f32.to_le_bytes());
        assert_eq!(&file[h + 4..h + 8], &(-2.5f32).to_le_bytes());
        let file = i64_array(&[2], &[1, 2]);
        let h = header("<i8", &[2]).len();
        assert_eq!(file.len(), h + 16);
        assert_eq!(&file[h..h + 8], &1i64.to_le_bytes());
        let pickle = [0x80, 2, b'.'];
        let h = header("|O", &[]).len();
        assert_eq!(&object_scalar(&pickle)[h..], &pickle);
    }
}
