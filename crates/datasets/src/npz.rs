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

use std::io::{Cursor, Read, Seek, Write};

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

fn checked_count(shape: &[usize]) -> Option<usize> {
    shape.iter().try_fold(1usize, |acc, &d| acc.checked_mul(d))
}

/// Parses one `.npy` file held in memory.
///
/// ```
/// use datasets::npz::{encode_npy, parse_npy, NpyArray};
/// let a = NpyArray::from_i64(vec![3], vec![0, 1, 2]).unwrap();
/// let bytes = encode_npy(&a);
/// assert_eq!(parse_npy(&bytes).unwrap(), a);
/// assert!(parse_npy(&bytes[..bytes.len() - 1]).is_err());
/// ```
pub fn parse_npy(bytes: &[u8]) -> Result<NpyArray, NpzError> {
    check_shape_fits(header_text(bytes)?)?;
    let file = npyz::NpyFile::new(bytes).map_err(|e| header_err(&e))?;
    let header = file.header().clone();
    let data = file.into_inner();
    let dtype = match header.dtype() {
        npyz::DType::Plain(ty) => ty,
        other => return Err(NpzError::UnsupportedDtype(other.descr())),
    };
    let item_size = supported_size(&dtype)?;
    let shape = header
        .shape()
        .iter()
        .map(|&d| usize::try_from(d))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|_| header_err(&format!("shape {:?} overflows", header.shape())))?;
    let count =
        checked_count(&shape).ok_or_else(|| header_err(&format!("shape {shape:?} overflows")))?;
    let needed = (count as u64).saturating_mul(item_size as u64);
    if data.len() as u64 != needed {
        return Err(NpzError::DataSize {
            shape,
            item_size,
            needed,
            available: data.len(),
        });
    }
    let order = header.order();
    let mut values = decode(npyz::NpyFile::with_header(header, data), &dtype)?;
    if order == npyz::Order::Fortran && shape.len() > 1 {
        values = fortran_to_c(values, &shape);
    }
    Ok(NpyArray {
        shape,
        data: values,
        descr: dtype.to_string(),
    })
}

/// A [`NpzError::BadHeader`] with the first line of `message` (`npyz`
/// quotes the whole header, with a caret, on the following lines).
fn header_err(message: &dyn std::fmt::Display) -> NpzError {
    let text = message.to_string();
    NpzError::BadHeader(text.lines().next().unwrap_or_default().to_string())
}

/// The header's dict text, after checking the magic string, the version and
/// that the header lies within `bytes`.
fn header_text(bytes: &[u8]) -> Result<&[u8], NpzError> {
    if bytes.len() < 8 || &bytes[..6] != NPY_MAGIC {
        return Err(NpzError::BadMagic);
    }
    let (len_bytes, start) = match bytes[6] {
        1 => (2, 10),
        2 | 3 => (4, 12),
        v => return Err(header_err(&format!("unsupported format version {v}"))),
    };
    let mut len = [0u8; 4];
    len[..len_bytes].copy_from_slice(
        bytes
            .get(8..start)
            .ok_or_else(|| header_err(&"truncated header length"))?,
    );
    let header_len = u32::from_le_bytes(len) as usize;
    start
        .checked_add(header_len)
        .and_then(|end| bytes.get(start..end))
        .ok_or_else(|| {
            header_err(&format!(
                "header of {header_len} bytes runs past the end of the data ({} bytes)",
                bytes.len()
            ))
        })
}

/// Rejects a header whose `shape` has more elements than fit in `u64`,
/// before `npyz` multiplies the dimensions unchecked. Parsed with
/// `py_literal`, the parser `npyz` itself uses; anything this check cannot
/// read is left for `npyz` to report. Every `shape` entry is checked (a
/// repeated key is resolved by `npyz`, not here), and zero dimensions are
/// left out of the product so that no partial product, in either order,
/// can overflow.
fn check_shape_fits(header: &[u8]) -> Result<(), NpzError> {
    use py_literal::Value;
    let Some(Ok(Value::Dict(entries))) = std::str::from_utf8(header)
        .ok()
        .map(|text| text.trim_end().parse::<Value>())
    else {
        return Ok(());
    };
    for (key, value) in &entries {
        let (Value::String(key), Value::Tuple(dims) | Value::List(dims)) = (key, value) else {
            continue;
        };
        if key != "shape" {
            continue;
        }
        let fits = dims
            .iter()
            .filter_map(|d| match d {
                Value::Integer(d) => u64::try_from(d).ok().filter(|&d| d != 0),
                _ => None,
            })
            .try_fold(1u64, u64::checked_mul)
            .is_some();
        if !fits {
            return Err(header_err(&format!("shape {value} overflows")));
        }
    }
    Ok(())
}

/// The item size of a supported element type.
fn supported_size(dtype: &npyz::TypeStr) -> Result<usize, NpzError> {
    use npyz::TypeChar::{Bool, Float, Int, Uint};
    match (dtype.type_char(), dtype.size_field()) {
        (Float, 4 | 8) | (Int | Uint, 1 | 2 | 4 | 8) | (Bool, 1) => Ok(dtype.size_field() as usize),
        _ => Err(NpzError::UnsupportedDtype(dtype.to_string())),
    }
}

/// Reads all elements with `npyz` (the data length already checked) and
/// widens them to `f64` or `i64`.
fn decode(file: npyz::NpyFile<&[u8]>, dtype: &npyz::TypeStr) -> Result<NpyData, NpzError> {
    use npyz::TypeChar::{Bool, Float, Int, Uint};
    fn read<T: npyz::Deserialize>(file: npyz::NpyFile<&[u8]>) -> Result<Vec<T>, NpzError> {
        file.into_vec()
            .map_err(|e| NpzError::BadData(e.to_string()))
    }
    fn ints<T: Into<i64>>(values: Vec<T>) -> NpyData {
        NpyData::Int(values.into_iter().map(Into::into).collect())
    }
    Ok(match (dtype.type_char(), dtype.size_field()) {
        (Float, 4) => NpyData::Float(read::<f32>(file)?.into_iter().map(f64::from).collect()),
        (Float, 8) => NpyData::Float(read(file)?),
        (Int, 1) => ints(read::<i8>(file)?),
        (Int, 2) => ints(read::<i16>(file)?),
        (Int, 4) => ints(read::<i32>(file)?),
        (Int, 8) => ints(read::<i64>(file)?),
        (Uint, 1) => ints(read::<u8>(file)?),
        (Uint, 2) => ints(read::<u16>(file)?),
        (Uint, 4) => ints(read::<u32>(file)?),
        (Uint, 8) => NpyData::Int(
            read::<u64>(file)?
                .into_iter()
                .map(|v| i64::try_from(v).map_err(|_| NpzError::IntegerRange(v)))
                .collect::<Result<_, _>>()?,
        ),
        (Bool, 1) => ints(read::<bool>(file)?),
        _ => return Err(NpzError::UnsupportedDtype(dtype.to_string())),
    })
}

/// Reorders column-major values to row-major.
fn fortran_to_c(values: NpyData, shape: &[usize]) -> NpyData {
    fn reorder<T: Copy>(v: &[T], shape: &[usize]) -> Vec<T> {
        let count = v.len();
        let mut out = Vec::with_capacity(count);
        let mut index = vec![0usize; shape.len()];
        for _ in 0..count {
            // Fortran offset of the current C-order multi-index.
            let mut offset = 0;
            let mut stride = 1;
            for (i, &d) in index.iter().zip(shape) {
                offset += i * stride;
                stride *= d;
            }
            out.push(v[offset]);
            for axis in (0..shape.len()).rev() {
                index[axis] += 1;
                if index[axis] < shape[axis] {
                    break;
                }
                index[axis] = 0;
            }
        }
        out
    }
    match values {
        NpyData::Float(v) => NpyData::Float(reorder(&v, shape)),
        NpyData::Int(v) => NpyData::Int(reorder(&v, shape)),
    }
}

/// Encodes an array as a `.npy` file (version 1.0, or 2.0 for a header over
/// 64 kB), little-endian, C order, header padded so the data starts on a
/// 64-byte boundary (as NumPy does).
pub fn encode_npy(array: &NpyArray) -> Vec<u8> {
    let shape = match array.shape.len() {
        0 => "()".to_string(),
        1 => format!("({},)", array.shape[0]),
        _ => format!(
            "({})",
            array
                .shape
                .iter()
                .map(|d| d.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    };
    let descr = match &array.data {
        NpyData::Float(_) => "<f8",
        NpyData::Int(_) => "<i8",
    };
    let mut header = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
    // Version 1.0 has a u16 header length; longer headers (thousands of
    // dimensions) need version 2.0 and its u32 length.
    let preamble = if header.len() + 64 <= usize::from(u16::MAX) {
        10
    } else {
        12
    };
    // magic + version + length + header (ending in '\n') ≡ 0 mod 64.
    let unpadded = preamble + header.len() + 1;
    header.push_str(&" ".repeat(unpadded.next_multiple_of(64) - unpadded));
    header.push('\n');
    let mut out = Vec::with_capacity(preamble + header.len() + 8 * array.data.len());
    out.extend_from_slice(NPY_MAGIC);
    if preamble == 10 {
        out.extend_from_slice(&[1, 0]);
        out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    } else {
        out.extend_from_slice(&[2, 0]);
        out.extend_from_slice(&(header.len() as u32).to_le_bytes());
    }
    out.extend_from_slice(header.as_bytes());
    match &array.data {
        NpyData::Float(v) => v
            .iter()
            .for_each(|x| out.extend_from_slice(&x.to_le_bytes())),
        NpyData::Int(v) => v
            .iter()
            .for_each(|x| out.extend_from_slice(&x.to_le_bytes())),
    }
    out
}

/// A `.npz` archive read from memory; members are parsed on request, so an
/// unsupported member (e.g. a pickled object array) only matters if asked for.
pub struct NpzArchive<'a> {
    zip: zip::ZipArchive<Cursor<&'a [u8]>>,
}

impl<'a> NpzArchive<'a> {
    /// Opens the archive's central directory.
    ///
    /// ```
    /// use datasets::npz::{write_npz, NpzArchive, NpyArray};
    /// let mut bytes = std::io::Cursor::new(Vec::new());
    /// let k = NpyArray::from_f64(vec![3, 3], vec![1.0, 0.0, 5.0, 0.0, 1.0, 6.0, 0.0, 0.0, 1.0]).unwrap();
    /// write_npz(&mut bytes, &[("K", &k)]).unwrap();
    /// let bytes = bytes.into_inner();
    /// let mut archive = NpzArchive::new(&bytes).unwrap();
    /// assert_eq!(archive.array_names(), vec!["K".to_string()]);
    /// assert_eq!(archive.array("K").unwrap(), Some(k));
    /// assert_eq!(archive.array("R").unwrap(), None);
    /// ```
    pub fn new(bytes: &'a [u8]) -> Result<Self, NpzError> {
        let zip =
            zip::ZipArchive::new(Cursor::new(bytes)).map_err(|e| NpzError::Zip(e.to_string()))?;
        Ok(Self { zip })
    }

    /// Names of the arrays (member names without the `.npy` suffix).
    pub fn array_names(&self) -> Vec<String> {
        self.zip
            .file_names()
            .filter_map(|n| n.strip_suffix(".npy"))
            .map(str::to_string)
            .collect()
    }

    /// Reads and parses the array `name` (member `name.npy`); `Ok(None)` when
    /// the archive has no such member.
    pub fn array(&mut self, name: &str) -> Result<Option<NpyArray>, NpzError> {
        let member = format!("{name}.npy");
        let mut file = match self.zip.by_name(&member) {
            Ok(file) => file,
            Err(zip::result::ZipError::FileNotFound) => return Ok(None),
            Err(e) => return Err(NpzError::Zip(e.to_string())),
        };
        if file.size() > MAX_MEMBER_BYTES {
            return Err(NpzError::TooLarge(MAX_MEMBER_BYTES));
        }
        let mut bytes = Vec::new();
        (&mut file)
            .take(MAX_MEMBER_BYTES + 1)
            .read_to_end(&mut bytes)
            .map_err(|e| NpzError::Zip(format!("member {member}: {e}")))?;
        if bytes.len() as u64 > MAX_MEMBER_BYTES {
            return Err(NpzError::TooLarge(MAX_MEMBER_BYTES));
        }
        parse_npy(&bytes).map(Some)
    }
}

/// Writes named arrays as a `.npz` archive (members stored uncompressed, as
/// `numpy.savez` does), in the given order.
pub fn write_npz<W: Write + Seek>(writer: W, arrays: &[(&str, &NpyArray)]) -> Result<(), NpzError> {
    let write_err = |e: &dyn std::fmt::Display| NpzError::Write(e.to_string());
    let mut zip = zip::ZipWriter::new(writer);
    let options =
        zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Stored);
    for (name, array) in arrays {
        zip.start_file(format!("{name}.npy"), options)
            .map_err(|e| write_err(&e))?;
        zip.write_all(&encode_npy(array))
            .map_err(|e| write_err(&e))?;
    }
    let mut inner = zip.finish().map_err(|e| write_err(&e))?;
    inner.flush().map_err(|e| write_err(&e))
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
