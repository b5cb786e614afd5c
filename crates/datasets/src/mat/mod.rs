//! A reader for MATLAB level-5 MAT-files (the `.mat` format of AdelaideRMF).
//!
//! Only what the dataset loaders need, written to be safe on arbitrary bytes:
//! numeric arrays of any class, stored as any numeric element type,
//! possibly zlib-compressed (`miCOMPRESSED`), in either byte order.
//! Variables of other classes (cell, struct, char, sparse, object) are listed
//! with their class but carry no values.
//!
//! Layout (MathWorks, "MAT-File Format", level 5): a 128-byte header whose
//! last two bytes are the endian indicator `IM` (little-endian) or `MI`,
//! then a sequence of data elements, each an 8-byte tag (element type,
//! byte count) followed by the data padded to 8 bytes, or a 4-byte "small
//! element" tag when the byte count fits in 4 bytes. A variable is an
//! `miMATRIX` element holding sub-elements: array flags, dimensions, name,
//! real part and optional imaginary part. MATLAB stores arrays
//! column-major; the values here keep that order.
//!
//! Every length read from the file is checked against the bytes actually
//! present, so a corrupt file gives a [`MatError`] rather than a panic or an
//! attempt to allocate a claimed size; decompressed data is capped at
//! [`MAX_DECOMPRESSED_BYTES`] per variable.
//!
//! Files: the variables and [`parse_mat`] here, the data elements (tags,
//! byte order, inflation) in `element.rs`, a variable's `miMATRIX`
//! sub-elements and numeric decoding in `matrix.rs`.

mod element;
mod matrix;

use element::{inflate, Cursor, Endian, MI_COMPRESSED, MI_MATRIX};
use matrix::parse_matrix;

/// Upper bound on the decompressed size of one `miCOMPRESSED` element
/// (512 MiB): a guard against decompression bombs. AdelaideRMF variables
/// are below 3 MB.
pub const MAX_DECOMPRESSED_BYTES: u64 = 512 * 1024 * 1024;

/// Length of the MAT v5 text header, subsystem offset, version and endian
/// indicator.
const HEADER_LEN: usize = 128;

/// Errors of the MAT v5 reader. Each names the part of the file at fault
/// (byte offset of the element within the file, or within the decompressed
/// stream of the variable being read).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum MatError {
    /// The file is shorter than the 128-byte header.
    #[error("file is {len} bytes, shorter than the 128-byte MAT v5 header")]
    TooShort {
        /// File length in bytes.
        len: usize,
    },
    /// The header's endian indicator is neither `IM` nor `MI`.
    #[error("not a MAT v5 file (endian indicator {found:?} is neither \"IM\" nor \"MI\")")]
    BadEndianIndicator {
        /// The two bytes found at offset 126.
        found: [u8; 2],
    },
    /// An element tag or its data runs past the end of the available bytes.
    #[error(
        "element at offset {offset} is truncated: needs {needed} bytes, {available} available"
    )]
    Truncated {
        /// Offset of the element.
        offset: usize,
        /// Bytes the element claims.
        needed: u64,
        /// Bytes left in the file (or stream).
        available: usize,
    },
    /// The zlib stream of a compressed element could not be inflated.
    #[error("compressed element at offset {offset}: {message}")]
    Decompress {
        /// Offset of the `miCOMPRESSED` element in the file.
        offset: usize,
        /// The decoder's message.
        message: String,
    },
    /// A compressed element inflates to more than [`MAX_DECOMPRESSED_BYTES`].
    #[error("compressed element at offset {offset} inflates to more than {limit} bytes")]
    DecompressedTooLarge {
        /// Offset of the `miCOMPRESSED` element in the file.
        offset: usize,
        /// The cap that was exceeded.
        limit: u64,
    },
    /// A structural rule of the format is broken (wrong sub-element type,
    /// data size not matching the dimensions, …).
    #[error("variable {variable:?}: {problem}")]
    Malformed {
        /// Name of the variable being read (empty if not yet known).
        variable: String,
        /// What is wrong.
        problem: String,
    },
}

/// The MATLAB class of an array (the low byte of its array flags).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MatClass {
    /// `cell` (no values read).
    Cell,
    /// `struct` (no values read).
    Struct,
    /// `object` (no values read).
    Object,
    /// `char` (no values read).
    Char,
    /// `sparse` (no values read).
    Sparse,
    /// `double`.
    Double,
    /// `single`.
    Single,
    /// `int8`.
    Int8,
    /// `uint8`.
    UInt8,
    /// `int16`.
    Int16,
    /// `uint16`.
    UInt16,
    /// `int32`.
    Int32,
    /// `uint32`.
    UInt32,
    /// `int64`.
    Int64,
    /// `uint64`.
    UInt64,
    /// A class code outside the documented range.
    Unknown(u8),
}

impl MatClass {
    fn from_code(code: u8) -> Self {
        match code {
            1 => Self::Cell,
            2 => Self::Struct,
            3 => Self::Object,
            4 => Self::Char,
            5 => Self::Sparse,
            6 => Self::Double,
            7 => Self::Single,
            8 => Self::Int8,
            9 => Self::UInt8,
            10 => Self::Int16,
            11 => Self::UInt16,
            12 => Self::Int32,
            13 => Self::UInt32,
            14 => Self::Int64,
            15 => Self::UInt64,
            other => Self::Unknown(other),
        }
    }

    /// The class code of the array flags.
    pub fn code(self) -> u8 {
        match self {
            Self::Cell => 1,
            Self::Struct => 2,
            Self::Object => 3,
            Self::Char => 4,
            Self::Sparse => 5,
            Self::Double => 6,
            Self::Single => 7,
            Self::Int8 => 8,
            Self::UInt8 => 9,
            Self::Int16 => 10,
            Self::UInt16 => 11,
            Self::Int32 => 12,
            Self::UInt32 => 13,
            Self::Int64 => 14,
            Self::UInt64 => 15,
            Self::Unknown(code) => code,
        }
    }

    /// True for the numeric classes, whose values this reader decodes.
    pub fn is_numeric(self) -> bool {
        matches!(
            self,
            Self::Double
                | Self::Single
                | Self::Int8
                | Self::UInt8
                | Self::Int16
                | Self::UInt16
                | Self::Int32
                | Self::UInt32
                | Self::Int64
                | Self::UInt64
        )
    }
}

/// The real part of a numeric array, in MATLAB's column-major order.
///
/// Bytes stay bytes (images are `uint8` stored as `miUINT8`); every other
/// storage type is widened to `f64` (exact for all integer storage types up
/// to 2^53 and for `single`).
#[derive(Debug, Clone, PartialEq)]
pub enum MatValues {
    /// Values stored as `miUINT8`.
    UInt8(Vec<u8>),
    /// Values of any other numeric storage type, as `f64`.
    Float(Vec<f64>),
    /// A non-numeric class: values not decoded.
    NotNumeric,
}

/// One variable of a MAT-file.
#[derive(Debug, Clone, PartialEq)]
pub struct MatVariable {
    /// Variable name.
    pub name: String,
    /// MATLAB class.
    pub class: MatClass,
    /// Dimensions (at least two for arrays MATLAB writes).
    pub dims: Vec<usize>,
    /// True when the array has an imaginary part (ignored by the loaders).
    pub complex: bool,
    /// Real part, column-major.
    pub values: MatValues,
}

impl MatVariable {
    /// Number of elements: the product of [`MatVariable::dims`].
    pub fn numel(&self) -> usize {
        self.dims.iter().product()
    }

    /// The values as `f64`, column-major (bytes are widened). `None` for a
    /// non-numeric class.
    pub fn to_f64(&self) -> Option<Vec<f64>> {
        match &self.values {
            MatValues::UInt8(bytes) => Some(bytes.iter().map(|&b| f64::from(b)).collect()),
            MatValues::Float(values) => Some(values.clone()),
            MatValues::NotNumeric => None,
        }
    }
}

/// The variables of a MAT-file, in file order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MatFile {
    /// All variables (numeric ones with values, others with their class only).
    pub variables: Vec<MatVariable>,
}

impl MatFile {
    /// The first variable called `name`.
    pub fn get(&self, name: &str) -> Option<&MatVariable> {
        self.variables.iter().find(|v| v.name == name)
    }
}

/// Parses a complete MAT v5 file held in memory.
///
/// Never panics; any inconsistency gives a [`MatError`].
///
/// ```
/// // A 128-byte header that claims to be MAT v5 but has no variables.
/// let mut bytes = vec![b' '; 128];
/// bytes[..10].copy_from_slice(b"MATLAB 5.0");
/// bytes[124..128].copy_from_slice(&[0x00, 0x01, b'I', b'M']);
/// let file = datasets::mat::parse_mat(&bytes).unwrap();
/// assert!(file.variables.is_empty());
/// assert!(datasets::mat::parse_mat(&bytes[..100]).is_err());
/// ```
pub fn parse_mat(bytes: &[u8]) -> Result<MatFile, MatError> {
    if bytes.len() < HEADER_LEN {
        return Err(MatError::TooShort { len: bytes.len() });
    }
    let endian = match &bytes[126..128] {
        b"IM" => Endian::Little,
        b"MI" => Endian::Big,
        other => {
            return Err(MatError::BadEndianIndicator {
                found: [other[0], other[1]],
            })
        }
    };
    let mut variables = Vec::new();
    let mut cursor = Cursor {
        bytes,
        pos: HEADER_LEN,
        base: 0,
        endian,
    };
    while cursor.remaining() > 0 {
        // Trailing zero padding after the last element is harmless.
        if cursor.rest().iter().all(|&b| b == 0) && cursor.remaining() < 8 {
            break;
        }
        let offset = cursor.pos;
        let tag = cursor.tag()?;
        match tag.kind {
            MI_COMPRESSED => {
                let inflated = inflate(tag.data, offset)?;
                let mut inner = Cursor {
                    bytes: &inflated,
                    pos: 0,
                    base: 0,
                    endian,
                };
                while inner.remaining() > 0 {
                    let inner_offset = inner.pos;
                    let inner_tag = inner.tag()?;
                    if inner_tag.kind == MI_MATRIX {
                        variables.push(parse_matrix(inner_tag.data, endian, inner_offset)?);
                    }
                }
            }
            MI_MATRIX => variables.push(parse_matrix(tag.data, endian, offset)?),
            // Other top-level elements (e.g. subsystem data) are skipped.
            _ => {}
        }
    }
    Ok(MatFile { variables })
}

#[cfg(test)]
mod tests {
    use super::element::*;
    use super::*;

    /// (name, class code, dims, element type, raw data) of a test variable.
    type TestVar<'a> = (&'a str, u8, &'a [i32], u32, Vec<u8>);

    /// Builds one uncompressed little- or big-endian MAT v5 file from
    /// (name, class code, dims, element type, raw data) tuples.
    fn build_mat(big_endian: bool, vars: &[TestVar]) -> Vec<u8> {
        let u32b = |v: u32| {
            if big_endian {
                v.to_be_bytes()
            } else {
                v.to_le_bytes()
            }
        };
        let element = |kind: u32, data: &[u8]| {
            let mut out = Vec::new();
            out.extend_from_slice(&u32b(kind));
            out.extend_from_slice(&u32b(data.len() as u32));
            out.extend_from_slice(data);
            while out.len() % 8 != 0 {
                out.push(0);
            }
            out
        };
        let mut file = vec![b' '; 128];
        file[124..126].copy_from_slice(&if big_endian { [1u8, 0] } else { [0u8, 1] });
        file[126..128].copy_from_slice(if big_endian { b"MI" } else { b"IM" });
        for (name, class, dims, kind, data) in vars {
            let mut body = Vec::new();
            let mut flags = Vec::new();
            flags.extend_from_slice(&u32b(u32::from(*class)));
            flags.extend_from_slice(&u32b(0));
            body.extend(element(MI_UINT32, &flags));
            let dim_bytes: Vec<u8> = dims.iter().flat_map(|&d| u32b(d as u32)).collect();
            body.extend(element(MI_INT32, &dim_bytes));
            body.extend(element(MI_INT8, name.as_bytes()));
            body.extend(element(*kind, data));
            file.extend(element(MI_MATRIX, &body));
        }
        file
    }

    #[test]
    fn reads_doubles_in_both_byte_orders() {
        for big in [false, true] {
            let values = [1.5f64, -2.0, 3.25, 4.0, 5.0, 6.0];
            let data: Vec<u8> = values
                .iter()
                .flat_map(|v| {
                    if big {
                        v.to_be_bytes()
                    } else {
                        v.to_le_bytes()
                    }
                })
                .collect();
            let bytes = build_mat(big, &[("data", 6, &[2, 3], MI_DOUBLE, data)]);
            let file = parse_mat(&bytes).unwrap();
            let var = file.get("data").unwrap();
            assert_eq!(var.class, MatClass::Double);
            assert_eq!(var.dims, vec![2, 3]);
            assert_eq!(var.to_f64().unwrap(), values.to_vec());
        }
    }

    #[test]
    fn widens_compact_storage_types() {
        // MATLAB stores a double array of small integers as miUINT8 or miINT16.
        let bytes = build_mat(
            false,
            &[
                ("a", 6, &[1, 3], MI_UINT8, vec![0, 7, 255]),
                (
                    "b",
                    6,
                    &[1, 2],
                    MI_INT16,
                    [-3i16, 300].iter().flat_map(|v| v.to_le_bytes()).collect(),
                ),
            ],
        );
        let file = parse_mat(&bytes).unwrap();
        assert_eq!(
            file.get("a").unwrap().to_f64().unwrap(),
            vec![0.0, 7.0, 255.0]
        );
        assert_eq!(file.get("b").unwrap().to_f64().unwrap(), vec![-3.0, 300.0]);
    }

    #[test]
    fn reads_compressed_elements() {
        use flate2::write::ZlibEncoder;
        use std::io::Write;
        let plain = build_mat(false, &[("label", 6, &[1, 4], MI_UINT8, vec![0, 1, 2, 2])]);
        let mut encoder = ZlibEncoder::new(Vec::new(), flate2::Compression::default());
        encoder.write_all(&plain[128..]).unwrap();
        let compressed = encoder.finish().unwrap();
        let mut file = plain[..128].to_vec();
        file.extend_from_slice(&MI_COMPRESSED.to_le_bytes());
        file.extend_from_slice(&(compressed.len() as u32).to_le_bytes());
        file.extend_from_slice(&compressed);
        let parsed = parse_mat(&file).unwrap();
        assert_eq!(
            parsed.get("label").unwrap().to_f64().unwrap(),
            vec![0.0, 1.0, 2.0, 2.0]
        );
    }

    #[test]
    fn small_element_names_are_read() {
        // Names up to 4 bytes are stored as small data elements by MATLAB.
        let mut bytes = build_mat(
            false,
            &[("x", 6, &[1, 1], MI_DOUBLE, 2.0f64.to_le_bytes().to_vec())],
        );
        // Rewrite the name element (8-byte tag + 8 padded bytes) as a small element.
        let name_at = 128 + 8 + 16 + 16;
        let mut small = Vec::new();
        small.extend_from_slice(&((1u32 << 16) | MI_INT8).to_le_bytes());
        small.extend_from_slice(&[b'x', 0, 0, 0]);
        bytes.splice(name_at..name_at + 16, small);
        let size_at = 128 + 4;
        let size = u32::from_le_bytes(bytes[size_at..size_at + 4].try_into().unwrap()) - 8;
        bytes[size_at..size_at + 4].copy_from_slice(&size.to_le_bytes());
        let file = parse_mat(&bytes).unwrap();
        assert_eq!(file.get("x").unwrap().to_f64().unwrap(), vec![2.0]);
    }

    #[test]
    fn dims_not_matching_data_is_an_error() {
        let bytes = build_mat(false, &[("data", 6, &[2, 3], MI_UINT8, vec![1, 2, 3])]);
        let err = parse_mat(&bytes).unwrap_err();
        assert!(err.to_string().contains("\"data\""), "{err}");
        assert!(err.to_string().contains("need 6 values"), "{err}");
    }

    #[test]
    fn truncation_is_an_error_not_a_panic() {
        let bytes = build_mat(
            false,
            &[("data", 6, &[2, 3], MI_UINT8, vec![1, 2, 3, 4, 5, 6])],
        );
        for cut in 0..bytes.len() {
            let _ = parse_mat(&bytes[..cut]);
        }
        assert!(matches!(
            parse_mat(&bytes[..150]),
            Err(MatError::Truncated { .. })
        ));
    }

    #[test]
    fn bad_endian_indicator() {
        let mut bytes = build_mat(false, &[]);
        bytes[126] = b'X';
        assert!(matches!(
            parse_mat(&bytes),
            Err(MatError::BadEndianIndicator { .. })
        ));
    }
}
