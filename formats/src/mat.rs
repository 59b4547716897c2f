//! A minimal MAT-file (level 5, "v5") writer for numeric arrays: what MATLAB's `save -v6`
//! and `scipy.io.savemat` write, read back by `scipy.io.loadmat` and MATLAB's `load`.
//!
//! Layout (MathWorks, "MAT-File Format", level 5):
//! - a 128-byte header: 116 bytes of descriptive text padded with spaces, 8 bytes of
//!   subsystem data offset (zero: none), the version `0x0100` and the endian indicator
//!   `"MI"`, both written as little-endian 16-bit values (so the file holds `00 01 'I' 'M'`);
//! - one `miMATRIX` data element per variable: an 8-byte tag (type 14, byte count of what
//!   follows) and four sub-elements, each an 8-byte tag (type, byte count) then its data
//!   padded with zeros to a multiple of 8 bytes:
//!   1. array flags (`miUINT32`, 8 bytes): the class in the low byte of the first word
//!      (`mxSINGLE_CLASS` = 7, `mxINT32_CLASS` = 12; no complex, global or logical flag),
//!      and a zero word;
//!   2. dimensions (`miINT32`): one word per axis;
//!   3. name (`miINT8`): the variable name's ASCII bytes;
//!   4. real part (`miSINGLE` = 7 or `miINT32` = 5): the elements in MATLAB's
//!      column-major order (first index fastest).
//!
//! No compression (`miCOMPRESSED`), no sparse, complex, cell, struct or character arrays.

use std::io::{self, Write};

/// Data type codes of data element tags.
const MI_INT8: u32 = 1;
const MI_INT32: u32 = 5;
const MI_UINT32: u32 = 6;
const MI_SINGLE: u32 = 7;
const MI_MATRIX: u32 = 14;

/// Array class codes of the array flags.
const MX_SINGLE_CLASS: u32 = 7;
const MX_INT32_CLASS: u32 = 12;

/// Length of the descriptive text of the header.
const TEXT_LEN: usize = 116;
/// Length of the whole header.
pub const HEADER_LEN: usize = 128;

/// A numeric element type a MAT array can hold: 4-byte values.
pub trait MatElement: Copy {
    /// The array class (`mxSINGLE_CLASS`, `mxINT32_CLASS`).
    const CLASS: u32;
    /// The data type of the real part (`miSINGLE`, `miINT32`).
    const DATA_TYPE: u32;
    /// The value's little-endian bytes.
    fn to_le(self) -> [u8; 4];
}

impl MatElement for f32 {
    const CLASS: u32 = MX_SINGLE_CLASS;
    const DATA_TYPE: u32 = MI_SINGLE;
    fn to_le(self) -> [u8; 4] {
        self.to_le_bytes()
    }
}

impl MatElement for i32 {
    const CLASS: u32 = MX_INT32_CLASS;
    const DATA_TYPE: u32 = MI_INT32;
    fn to_le(self) -> [u8; 4] {
        self.to_le_bytes()
    }
}

/// `n` rounded up to a multiple of 8.
fn padded(n: u64) -> u64 {
    n.div_ceil(8) * 8
}

/// Byte count of a variable's `miMATRIX` payload (what its tag announces): the four
/// sub-elements with their tags and padding.
pub fn matrix_payload_bytes(name: &str, dims: &[usize]) -> u64 {
    let elements: u64 = dims.iter().map(|&d| d as u64).product();
    let flags = 8 + 8;
    let dims_bytes = 8 + padded(4 * dims.len() as u64);
    let name_bytes = 8 + padded(name.len() as u64);
    let data = 8 + padded(4 * elements);
    flags + dims_bytes + name_bytes + data
}

/// Whether a variable fits a MAT v5 element (byte counts are 32-bit, dimensions signed
/// 32-bit); `Err` carries the payload's byte count when it does not.
pub fn check_fits(name: &str, dims: &[usize]) -> Result<(), u64> {
    let bytes = matrix_payload_bytes(name, dims);
    let dims_fit = dims.iter().all(|&d| i32::try_from(d).is_ok());
    if bytes <= u64::from(u32::MAX) && dims_fit {
        Ok(())
    } else {
        Err(bytes)
    }
}

/// Writes the 128-byte header; `text` (ASCII, at most 116 bytes, cut otherwise) is padded
/// with spaces.
pub fn write_header(w: &mut impl Write, text: &str) -> io::Result<()> {
    let mut header = [b' '; HEADER_LEN];
    let text = text.as_bytes();
    let n = text.len().min(TEXT_LEN);
    header[..n].copy_from_slice(&text[..n]);
    // Subsystem data offset: zero (no subsystem data).
    header[TEXT_LEN..TEXT_LEN + 8].fill(0);
    header[124..126].copy_from_slice(&0x0100u16.to_le_bytes());
    header[126..128].copy_from_slice(&u16::from_be_bytes(*b"MI").to_le_bytes());
    w.write_all(&header)
}

fn tag(w: &mut impl Write, data_type: u32, bytes: u64) -> io::Result<()> {
    let bytes = u32::try_from(bytes).map_err(|_| {
        io::Error::new(io::ErrorKind::InvalidInput, "MAT v5 data element over 4 GiB")
    })?;
    w.write_all(&data_type.to_le_bytes())?;
    w.write_all(&bytes.to_le_bytes())
}

fn pad(w: &mut impl Write, written: u64) -> io::Result<()> {
    let zeros = [0u8; 8];
    w.write_all(&zeros[..(padded(written) - written) as usize])
}

/// Writes one variable: an array of shape `dims` whose elements `row_major` lists in C
/// order (last index fastest, as a Rust nested loop or numpy writes them); the file gets
/// them in MATLAB's column-major order, so that `loadmat` gives back shape `dims` with the
/// same element at every index.
///
/// # Panics
/// If `row_major.len()` is not the product of `dims`, or the name is not a valid MATLAB
/// identifier of at most 63 ASCII characters (both are the caller's constants).
pub fn write_array<T: MatElement>(
    w: &mut impl Write,
    name: &str,
    dims: &[usize],
    row_major: &[T],
) -> io::Result<()> {
    let count: usize = dims.iter().product();
    assert_eq!(row_major.len(), count, "{name}: {dims:?} needs {count} elements");
    assert!(
        !name.is_empty()
            && name.len() <= 63
            && name.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_')
            && name.as_bytes()[0].is_ascii_alphabetic(),
        "{name:?} is not a MATLAB variable name"
    );
    check_fits(name, dims).map_err(|bytes| {
        io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("{name}: {bytes} bytes do not fit a MAT v5 element (at most 4 GiB)"),
        )
    })?;
    tag(w, MI_MATRIX, matrix_payload_bytes(name, dims))?;
    // Array flags.
    tag(w, MI_UINT32, 8)?;
    w.write_all(&T::CLASS.to_le_bytes())?;
    w.write_all(&0u32.to_le_bytes())?;
    // Dimensions (at least two axes, as MATLAB requires).
    tag(w, MI_INT32, 4 * dims.len() as u64)?;
    for &d in dims {
        w.write_all(&(d as i32).to_le_bytes())?;
    }
    pad(w, 4 * dims.len() as u64)?;
    // Name.
    tag(w, MI_INT8, name.len() as u64)?;
    w.write_all(name.as_bytes())?;
    pad(w, name.len() as u64)?;
    // Real part, column-major.
    tag(w, T::DATA_TYPE, 4 * count as u64)?;
    let mut buffer = Vec::with_capacity((4 * count).min(1 << 20));
    for index in column_major_order(dims) {
        buffer.extend_from_slice(&row_major[index].to_le());
        if buffer.len() >= 1 << 20 {
            w.write_all(&buffer)?;
            buffer.clear();
        }
    }
    w.write_all(&buffer)?;
    pad(w, 4 * count as u64)
}

/// The row-major (C order) offsets of an array's elements, listed in column-major
/// (Fortran) order: the first index runs fastest.
fn column_major_order(dims: &[usize]) -> impl Iterator<Item = usize> + '_ {
    let total: usize = dims.iter().product();
    // Row-major strides: the last axis has stride 1.
    let mut strides = vec![1usize; dims.len()];
    for axis in (0..dims.len().saturating_sub(1)).rev() {
        strides[axis] = strides[axis + 1] * dims[axis + 1];
    }
    let mut index = vec![0usize; dims.len()];
    let mut offset = 0usize;
    (0..total).map(move |_| {
        let current = offset;
        // Advance the odometer, first axis fastest.
        for axis in 0..dims.len() {
            index[axis] += 1;
            offset += strides[axis];
            if index[axis] < dims[axis] {
                break;
            }
            offset -= strides[axis] * dims[axis];
            index[axis] = 0;
        }
        current
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn words(bytes: &[u8]) -> Vec<u32> {
        bytes.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect()
    }

    #[test]
    fn header_is_128_bytes_with_version_and_endian_indicator() {
        let mut out = Vec::new();
        write_header(&mut out, "MATLAB 5.0 MAT-file, test").expect("write");
        assert_eq!(out.len(), 128);
        assert!(out.starts_with(b"MATLAB 5.0 MAT-file, test   "));
        assert!(out[25..116].iter().all(|&b| b == b' '));
        assert_eq!(&out[116..124], &[0u8; 8]);
        assert_eq!(&out[124..128], &[0x00, 0x01, b'I', b'M']);
    }

    #[test]
    fn a_2x3_int32_array_has_the_hand_computed_bytes() {
        // [[0, 1, 2], [10, 11, 12]] named "a".
        let data = [0i32, 1, 2, 10, 11, 12];
        let mut out = Vec::new();
        write_array(&mut out, "a", &[2, 3], &data).expect("write");
        // Tag 8 + flags 16 + dims (8 + 8) + name (8 + 8) + data (8 + 24) = 88 bytes.
        assert_eq!(out.len(), 88);
        assert_eq!(matrix_payload_bytes("a", &[2, 3]), 80);
        let w = words(&out);
        assert_eq!(&w[0..2], &[14, 80], "miMATRIX, 80 bytes");
        assert_eq!(&w[2..6], &[6, 8, 12, 0], "miUINT32 flags: mxINT32_CLASS");
        assert_eq!(&w[6..10], &[5, 8, 2, 3], "miINT32 dimensions 2 x 3");
        assert_eq!(&w[10..12], &[1, 1], "miINT8 name of 1 byte");
        assert_eq!(&out[48..56], b"a\0\0\0\0\0\0\0");
        assert_eq!(&w[14..16], &[5, 24], "miINT32 data, 24 bytes");
        // Column-major: a[0][0], a[1][0], a[0][1], a[1][1], a[0][2], a[1][2].
        assert_eq!(&w[16..22], &[0, 10, 1, 11, 2, 12]);
    }

    #[test]
    fn a_single_array_of_three_axes_is_padded_and_column_major() {
        // Shape (2, 1, 3): element (i, 0, c) = 10 i + c.
        let data: Vec<f32> = vec![0.0, 1.0, 2.0, 10.0, 11.0, 12.0];
        let mut out = Vec::new();
        write_array(&mut out, "pc1", &[2, 1, 3], &data).expect("write");
        // Tag 8 + flags 16 + dims (8 + 16) + name (8 + 8) + data (8 + 24) = 96.
        assert_eq!(out.len(), 96);
        let w = words(&out);
        assert_eq!(&w[0..2], &[14, 88]);
        assert_eq!(&w[2..4], &[6, 8]);
        assert_eq!(w[4], 7, "mxSINGLE_CLASS");
        assert_eq!(&w[6..11], &[5, 12, 2, 1, 3]);
        assert_eq!(w[11], 0, "dimensions padded to 8 bytes");
        assert_eq!(&w[12..14], &[1, 3]);
        assert_eq!(&w[16..18], &[7, 24], "miSINGLE data");
        let values: Vec<f32> = w[18..24].iter().map(|&b| f32::from_bits(b)).collect();
        assert_eq!(values, [0.0, 10.0, 1.0, 11.0, 2.0, 12.0]);
    }

    #[test]
    fn empty_arrays_and_size_limits() {
        let mut out = Vec::new();
        write_array::<f32>(&mut out, "pc1", &[0, 0, 3], &[]).expect("write");
        assert_eq!(out.len(), 8 + 16 + 24 + 16 + 8);
        assert!(check_fits("pc1", &[100, 2048, 3]).is_ok());
        assert!(check_fits("pc1", &[200_000, 2048, 3]).is_err());
    }
}
