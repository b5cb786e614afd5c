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
use matrix::{parse_header, parse_matrix};

/// Bytes of a compressed variable inflated to read its header (flags,
/// dimensions, name) when its values are not wanted.
pub const HEADER_PREFIX_BYTES: usize = 1024;

/// `variable`, its values dropped ([`MatValues::NotRead`]) when numeric
/// and not wanted.
fn unless_unwanted(mut variable: MatVariable, read_values: impl Fn(&str) -> bool) -> MatVariable {
    if variable.class.is_numeric() && !read_values(&variable.name) {
        variable.values = MatValues::NotRead;
    }
    variable
}

/// The header (values [`MatValues::NotRead`], or
/// [`MatValues::NotNumeric`]) of the variable whose inflated stream begins
/// with `prefix`, when `read_values` does not want it; `None` when it is
/// wanted or `prefix` holds no readable `miMATRIX` header.
fn unwanted_header(
    prefix: &[u8],
    endian: Endian,
    offset: usize,
    read_values: impl Fn(&str) -> bool,
) -> Option<MatVariable> {
    let mut cursor = Cursor {
        bytes: prefix,
        pos: 0,
        base: 0,
        endian,
    };
    let (kind, _size) = cursor.raw_tag_header().ok()?;
    if kind != MI_MATRIX {
        return None;
    }
    let header = parse_header(cursor.rest(), endian, offset).ok()?;
    (!read_values(&header.name)).then_some(header)
}

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
    /// A numeric variable whose values were not asked for
    /// ([`parse_mat_selected`]): name, class and dimensions only.
    NotRead,
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
    /// non-numeric class or values not read.
    pub fn to_f64(&self) -> Option<Vec<f64>> {
        match &self.values {
            MatValues::UInt8(bytes) => Some(bytes.iter().map(|&b| f64::from(b)).collect()),
            MatValues::Float(values) => Some(values.clone()),
            MatValues::NotNumeric | MatValues::NotRead => None,
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
    parse_mat_selected(bytes, |_| true)
}

/// [`parse_mat`], decoding the values only of the variables whose name
/// `read_values` accepts; the others keep their name, class and dimensions
/// with [`MatValues::NotRead`]. A compressed variable that is not read is
/// inflated only as far as its header ([`HEADER_PREFIX_BYTES`], plus what
/// the decoder reads ahead), so that skipping a large variable (an image)
/// skips most of its cost; damage further on in its stream goes unnoticed. A compressed element whose
/// header cannot be read from that prefix is read whole, with the errors of
/// [`parse_mat`].
///
/// ```
/// # let mut bytes = vec![b' '; 128];
/// # bytes[..10].copy_from_slice(b"MATLAB 5.0");
/// # bytes[124..128].copy_from_slice(&[0x00, 0x01, b'I', b'M']);
/// let file = datasets::mat::parse_mat_selected(&bytes, |name| name != "img1").unwrap();
/// assert!(file.variables.is_empty());
/// ```
pub fn parse_mat_selected(
    bytes: &[u8],
    read_values: impl Fn(&str) -> bool,
) -> Result<MatFile, MatError> {
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
                let mut skipped = None;
                let inflated = inflate(tag.data, offset, HEADER_PREFIX_BYTES, |prefix| {
                    skipped = unwanted_header(prefix, endian, offset, &read_values);
                    skipped.is_some()
                })?;
                let Some(inflated) = inflated else {
                    variables.extend(skipped);
                    continue;
                };
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
                        let variable = parse_matrix(inner_tag.data, endian, inner_offset)?;
                        variables.push(unless_unwanted(variable, &read_values));
                    }
                }
            }
            MI_MATRIX => {
                let variable = parse_matrix(tag.data, endian, offset)?;
                variables.push(unless_unwanted(variable, &read_values));
            }
            // Other top-level elements (e.g. subsystem data) are skipped.
            _ => {}
        }
    }
    Ok(MatFile { variables })
}

#[cfg(test)]
mod tests;
