//! NumPy `.npy` arrays and `.npz` archives (a zip of `.npy` members), as
//! HOPE-F stores its scenes.
//!
//! `.npy` (NumPy enhancement proposal NEP 1, format versions 1.0–3.0):
//! the magic `\x93NUMPY`, a major and minor version byte, a little-endian
//! header length (`u16` for 1.0, `u32` for 2.0/3.0), then a Python dict
//! literal `{'descr': '<f8', 'fortran_order': False, 'shape': (N, 3), }`
//! padded with spaces and a newline, then the raw data.
//!
//! Reading is done by the `npyz` crate (header dict, dtype strings, element
//! decoding in either byte order). This module adds what `npyz` 0.9 leaves
//! to its caller for untrusted bytes: the header must lie within the input
//! (`npyz` allocates the claimed length, up to 4 GiB, before reading it);
//! the shape's element count must fit in `u64` (`npyz` multiplies the
//! dimensions unchecked, which panics in debug and fuzz builds); and the
//! data section must hold exactly `shape` elements (`npyz` reads lazily and
//! ignores trailing bytes). Writing stays here: [`encode_npy`] pads the
//! header to 64 bytes as NumPy does (`npyz` pads to 16).
//!
//! Supported element types: `f4`, `f8`, `i1`–`i8`, `u1`–`u8`, `b1`, either
//! byte order. Arrays come back in C (row-major) order whatever their
//! `fortran_order`. Malformed input gives an [`NpzError`], never a panic,
//! and no allocation larger than the input.

//!
//! Files: the arrays and errors here, reading (`.npy` checks and decoding,
//! `.npz` members) in `read.rs`, writing in `write.rs`.

mod read;
mod write;

pub use read::{parse_npy, NpzArchive};
pub use write::{encode_npy, write_npz};

/// The magic string that opens every `.npy` file.
const NPY_MAGIC: &[u8; 6] = b"\x93NUMPY";

/// Upper bound on the uncompressed size of one archive member (1 GiB); a
/// guard against decompression bombs. HOPE-F members are a few kB.
pub const MAX_MEMBER_BYTES: u64 = 1024 * 1024 * 1024;

/// Errors reading or writing `.npy` / `.npz` data. The loaders wrap them with
/// the file path and the array name.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum NpzError {
    /// The zip container is unreadable (truncated archive, bad central
    /// directory, CRC mismatch, …).
    #[error("zip archive: {0}")]
    Zip(String),
    /// The member does not start with the `.npy` magic string.
    #[error("not a .npy array (bad magic string)")]
    BadMagic,
    /// The header is truncated, runs past the data, or is not the dict
    /// literal NumPy writes (the message is `npyz`'s).
    #[error("bad .npy header: {0}")]
    BadHeader(String),
    /// A well-formed `descr` that is not one of the supported element types
    /// (a malformed one is a [`NpzError::BadHeader`]).
    #[error("unsupported dtype {0:?} (supported: f4, f8, i1-i8, u1-u8, b1)")]
    UnsupportedDtype(String),
    /// The data section does not hold exactly `shape` elements.
    #[error(
        "data holds {available} bytes, shape {shape:?} of {item_size}-byte items needs {needed}"
    )]
    DataSize {
        /// Shape from the header.
        shape: Vec<usize>,
        /// Bytes per element.
        item_size: usize,
        /// Bytes the shape needs.
        needed: u64,
        /// Bytes present.
        available: usize,
    },
    /// An element is not a valid value of its dtype (a `b1` byte other
    /// than 0 or 1).
    #[error("bad element data: {0}")]
    BadData(String),
    /// An integer value does not fit `i64`.
    #[error("integer value {0} does not fit in i64")]
    IntegerRange(u64),
    /// A member is larger than [`MAX_MEMBER_BYTES`].
    #[error("member is larger than {0} bytes")]
    TooLarge(u64),
    /// An I/O error while writing.
    #[error("write error: {0}")]
    Write(String),
}

/// Element values of an array, widened to 64 bits, in C order.
#[derive(Debug, Clone, PartialEq)]
pub enum NpyData {
    /// Floating-point values (`f4` is widened exactly).
    Float(Vec<f64>),
    /// Integer and boolean values.
    Int(Vec<i64>),
}

impl NpyData {
    /// Number of elements.
    pub fn len(&self) -> usize {
        match self {
            NpyData::Float(v) => v.len(),
            NpyData::Int(v) => v.len(),
        }
    }

    /// True when there are no elements.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// One array: its shape, values in C order, and the `descr` it was stored as.
#[derive(Debug, Clone, PartialEq)]
pub struct NpyArray {
    /// Shape (empty for a scalar).
    pub shape: Vec<usize>,
    /// Values in C (row-major) order.
    pub data: NpyData,
    /// The dtype string as stored (`'<f8'`, `'<i8'`, …).
    pub descr: String,
}

impl NpyArray {
    /// A float64 array (`'<f8'`) of the given shape; `None` if the shape does
    /// not hold `values.len()` elements.
    ///
    /// ```
    /// use datasets::npz::NpyArray;
    /// let a = NpyArray::from_f64(vec![2, 3], vec![0.0; 6]).unwrap();
    /// assert_eq!(a.descr, "<f8");
    /// assert!(NpyArray::from_f64(vec![2, 2], vec![0.0; 6]).is_none());
    /// ```
    pub fn from_f64(shape: Vec<usize>, values: Vec<f64>) -> Option<Self> {
        (checked_count(&shape)? == values.len()).then(|| Self {
            shape,
            data: NpyData::Float(values),
            descr: "<f8".to_string(),
        })
    }

    /// An int64 array (`'<i8'`) of the given shape; `None` if the shape does
    /// not hold `values.len()` elements.
    pub fn from_i64(shape: Vec<usize>, values: Vec<i64>) -> Option<Self> {
        (checked_count(&shape)? == values.len()).then(|| Self {
            shape,
            data: NpyData::Int(values),
            descr: "<i8".to_string(),
        })
    }

    /// The values as `f64` (integers converted).
    pub fn to_f64(&self) -> Vec<f64> {
        match &self.data {
            NpyData::Float(v) => v.clone(),
            NpyData::Int(v) => v.iter().map(|&x| x as f64).collect(),
        }
    }
}

/// The product of the dimensions, `None` on overflow.
fn checked_count(shape: &[usize]) -> Option<usize> {
    shape.iter().try_fold(1usize, |acc, &d| acc.checked_mul(d))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn npy_with_header(header: &str, data: &[u8]) -> Vec<u8> {
        let mut out = NPY_MAGIC.to_vec();
        out.extend_from_slice(&[1, 0]);
        out.extend_from_slice(&(header.len() as u16).to_le_bytes());
        out.extend_from_slice(header.as_bytes());
        out.extend_from_slice(data);
        out
    }

    #[test]
    fn fortran_order_is_converted_to_c_order() {
        // A 2 x 3 array [[1,2,3],[4,5,6]] stored column-major: 1 4 2 5 3 6.
        let data: Vec<u8> = [1.0f64, 4.0, 2.0, 5.0, 3.0, 6.0]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let bytes = npy_with_header(
            "{'descr': '<f8', 'fortran_order': True, 'shape': (2, 3), }\n",
            &data,
        );
        let a = parse_npy(&bytes).unwrap();
        assert_eq!(a.data, NpyData::Float(vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0]));
    }

    #[test]
    fn integer_types_and_byte_orders() {
        let data: Vec<u8> = [-2i32, 7].iter().flat_map(|v| v.to_be_bytes()).collect();
        let bytes = npy_with_header(
            "{'descr': '>i4', 'fortran_order': False, 'shape': (2,), }\n",
            &data,
        );
        assert_eq!(parse_npy(&bytes).unwrap().data, NpyData::Int(vec![-2, 7]));
        let data: Vec<u8> = [3.5f32, -1.0]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let bytes = npy_with_header(
            "{'descr': '<f4', 'fortran_order': False, 'shape': (2,), }\n",
            &data,
        );
        assert_eq!(
            parse_npy(&bytes).unwrap().data,
            NpyData::Float(vec![3.5, -1.0])
        );
        let bytes = npy_with_header(
            "{'descr': '|u1', 'fortran_order': False, 'shape': (3,), }\n",
            &[0, 200, 255],
        );
        assert_eq!(
            parse_npy(&bytes).unwrap().data,
            NpyData::Int(vec![0, 200, 255])
        );
        let bytes = npy_with_header(
            "{'descr': '<u8', 'fortran_order': False, 'shape': (1,), }\n",
            &[255; 8],
        );
        assert_eq!(parse_npy(&bytes), Err(NpzError::IntegerRange(u64::MAX)));
    }

    #[test]
    fn rejects_object_arrays_and_bad_shapes() {
        let bytes = npy_with_header(
            "{'descr': '|O', 'fortran_order': False, 'shape': (1,), }\n",
            &[0; 8],
        );
        assert!(matches!(
            parse_npy(&bytes),
            Err(NpzError::UnsupportedDtype(_))
        ));
        let huge = "{'descr': '<f8', 'fortran_order': False, 'shape': (99999999999, 99999999999, 99999999999), }\n";
        assert!(matches!(
            parse_npy(&npy_with_header(huge, &[])),
            Err(NpzError::BadHeader(_))
        ));
        let short = "{'descr': '<f8', 'fortran_order': False, 'shape': (4,), }\n";
        assert!(matches!(
            parse_npy(&npy_with_header(short, &[0; 16])),
            Err(NpzError::DataSize { .. })
        ));
    }

    #[test]
    fn long_headers_use_version_2() {
        let shape = vec![1usize; 30_000];
        let a = NpyArray::from_f64(shape, vec![2.5]).unwrap();
        let bytes = encode_npy(&a);
        assert_eq!(bytes[6], 2);
        let header_len = u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize;
        assert_eq!((12 + header_len) % 64, 0);
        assert_eq!(parse_npy(&bytes).unwrap(), a);
    }

    #[test]
    fn encoded_header_is_64_byte_aligned() {
        for shape in [vec![], vec![5], vec![5, 3], vec![2, 3, 3]] {
            let count = shape.iter().product();
            let a = NpyArray::from_f64(shape, vec![0.5; count]).unwrap();
            let bytes = encode_npy(&a);
            let header_len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
            assert_eq!((10 + header_len) % 64, 0);
            assert_eq!(parse_npy(&bytes).unwrap(), a);
        }
    }

    #[test]
    fn header_length_past_the_end_is_an_error_without_allocating_it() {
        // Version 2.0 claims a 4 GiB header in a 16-byte input.
        let mut bytes = NPY_MAGIC.to_vec();
        bytes.extend_from_slice(&[2, 0]);
        bytes.extend_from_slice(&u32::MAX.to_le_bytes());
        bytes.extend_from_slice(b"{'de");
        let err = parse_npy(&bytes).unwrap_err();
        assert_eq!(
            err,
            NpzError::BadHeader(
                "header of 4294967295 bytes runs past the end of the data (16 bytes)".into()
            )
        );
        bytes[6] = 4;
        assert_eq!(
            parse_npy(&bytes),
            Err(NpzError::BadHeader("unsupported format version 4".into()))
        );
    }

    #[test]
    fn shapes_whose_count_overflows_are_errors_in_any_order() {
        // npyz multiplies left to right for the count and right to left for
        // the C strides: both orders, and a zero that hides the overflow
        // from a left-to-right product, and a repeated key.
        for shape in [
            "(99999999999, 99999999999, 99999999999)",
            "(0, 99999999999, 99999999999)",
            "(99999999999, 99999999999, 0)",
            "[4294967296, 4294967296]",
        ] {
            let header =
                format!("{{'descr': '<f8', 'fortran_order': False, 'shape': {shape}, }}\n");
            let err = parse_npy(&npy_with_header(&header, &[])).unwrap_err();
            assert!(
                matches!(&err, NpzError::BadHeader(m) if m.contains("overflows")),
                "{shape}: {err}"
            );
        }
        let repeated = "{'shape': (1,), 'descr': '<f8', 'fortran_order': False, 'shape': (4294967296, 4294967296), }\n";
        assert!(matches!(
            parse_npy(&npy_with_header(repeated, &[])),
            Err(NpzError::BadHeader(_))
        ));
        // A zero-sized array with moderate dimensions is fine.
        let empty = "{'descr': '<f8', 'fortran_order': False, 'shape': (0, 3), }\n";
        let a = parse_npy(&npy_with_header(empty, &[])).unwrap();
        assert_eq!((a.shape, a.data), (vec![0, 3], NpyData::Float(vec![])));
    }

    #[test]
    fn deeply_nested_header_is_an_error_not_a_stack_overflow() {
        // 60 000 open parentheses fill a version 1.0 header; the parser
        // stops at its depth limit. Run on a 2 MiB stack, a test thread's.
        let header = format!(
            "{{'descr': '<f8', 'fortran_order': False, 'shape': {}",
            "(".repeat(60_000)
        );
        let bytes = npy_with_header(&header, &[]);
        let result = std::thread::Builder::new()
            .stack_size(2 << 20)
            .spawn(move || parse_npy(&bytes))
            .unwrap()
            .join()
            .unwrap();
        assert!(matches!(result, Err(NpzError::BadHeader(m)) if m.starts_with("could not parse")));
    }

    #[test]
    fn booleans_are_zero_or_one() {
        let header = "{'descr': '|b1', 'fortran_order': False, 'shape': (3,), }\n";
        assert_eq!(
            parse_npy(&npy_with_header(header, &[0, 1, 1]))
                .unwrap()
                .data,
            NpyData::Int(vec![0, 1, 1])
        );
        assert!(matches!(
            parse_npy(&npy_with_header(header, &[0, 2, 1])),
            Err(NpzError::BadData(_))
        ));
    }

    #[test]
    fn version_3_and_fortran_integers_are_read() {
        // Version 3.0 (UTF-8 header, u32 length), a 2 x 2 int16 array
        // [[1, -2], [3, 4]] stored column-major and big-endian.
        let header = "{'descr': '>i2', 'fortran_order': True, 'shape': (2, 2), }\n";
        let mut bytes = NPY_MAGIC.to_vec();
        bytes.extend_from_slice(&[3, 0]);
        bytes.extend_from_slice(&(header.len() as u32).to_le_bytes());
        bytes.extend_from_slice(header.as_bytes());
        for v in [1i16, 3, -2, 4] {
            bytes.extend_from_slice(&v.to_be_bytes());
        }
        let a = parse_npy(&bytes).unwrap();
        assert_eq!(a.descr, ">i2");
        assert_eq!(a.data, NpyData::Int(vec![1, -2, 3, 4]));
    }

    #[test]
    fn trailing_bytes_and_record_dtypes_are_rejected() {
        let header = "{'descr': '<i4', 'fortran_order': False, 'shape': (1,), }\n";
        assert!(matches!(
            parse_npy(&npy_with_header(header, &[0; 5])),
            Err(NpzError::DataSize {
                needed: 4,
                available: 5,
                ..
            })
        ));
        let record =
            "{'descr': [('a', '<i4'), ('b', '<f8')], 'fortran_order': False, 'shape': (1,), }\n";
        assert!(matches!(
            parse_npy(&npy_with_header(record, &[0; 12])),
            Err(NpzError::UnsupportedDtype(_))
        ));
        let text = "{'descr': '<U3', 'fortran_order': False, 'shape': (1,), }\n";
        assert_eq!(
            parse_npy(&npy_with_header(text, &[0; 12])),
            Err(NpzError::UnsupportedDtype("<U3".into()))
        );
    }

    #[test]
    fn spellings_numpy_never_writes() {
        let eight = 1.5f64.to_le_bytes();
        for descr in ["=f8", "|f8"] {
            let header =
                format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': (1,), }}\n");
            assert!(
                matches!(
                    parse_npy(&npy_with_header(&header, &eight)),
                    Err(NpzError::BadHeader(_))
                ),
                "{descr}"
            );
        }
        let header = "{'descr': '<f8', 'fortran_order': False, 'shape': (1,), 'x': 1, }\n";
        let mut bytes = npy_with_header(header, &eight);
        assert_eq!(parse_npy(&bytes).unwrap().data, NpyData::Float(vec![1.5]));
        bytes[7] = 1; // format version 1.1
        assert!(matches!(parse_npy(&bytes), Err(NpzError::BadHeader(_))));
    }
}
