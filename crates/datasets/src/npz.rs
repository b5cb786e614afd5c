//! NumPy `.npy` arrays and `.npz` archives (a zip of `.npy` members), read
//! and written by this crate, as HOPE-F stores its scenes.
//!
//! `.npy` (NumPy enhancement proposal NEP 1, format versions 1.0–3.0):
//! the magic `\x93NUMPY`, a major and minor version byte, a little-endian
//! header length (`u16` for 1.0, `u32` for 2.0/3.0), then a Python dict
//! literal `{'descr': '<f8', 'fortran_order': False, 'shape': (N, 3), }`
//! padded with spaces and a newline, then the raw data.
//!
//! Supported element types: `f4`, `f8`, `i1`–`i8`, `u1`–`u8`, `b1`, either
//! byte order. Arrays come back in C (row-major) order whatever their
//! `fortran_order`. Every size read from a file is checked against the bytes
//! present: malformed input gives an [`NpzError`], never a panic, and no
//! allocation larger than the input.

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
    /// The header is truncated or is not the dict literal NumPy writes.
    #[error("bad .npy header: {0}")]
    BadHeader(String),
    /// The `descr` is not one of the supported element types.
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

/// Element type decoded from a `descr` string.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Float,
    Signed,
    Unsigned,
    Bool,
}

#[derive(Debug, Clone, Copy)]
struct Dtype {
    kind: Kind,
    size: usize,
    big_endian: bool,
}

fn parse_dtype(descr: &str) -> Result<Dtype, NpzError> {
    let unsupported = || NpzError::UnsupportedDtype(descr.to_string());
    let mut chars = descr.chars();
    let order = chars.next().ok_or_else(unsupported)?;
    let big_endian = match order {
        '<' | '|' | '=' => false,
        '>' => true,
        _ => return Err(unsupported()),
    };
    let kind = match chars.next().ok_or_else(unsupported)? {
        'f' => Kind::Float,
        'i' => Kind::Signed,
        'u' => Kind::Unsigned,
        'b' => Kind::Bool,
        _ => return Err(unsupported()),
    };
    let size: usize = chars.as_str().parse().map_err(|_| unsupported())?;
    let ok = match kind {
        Kind::Float => size == 4 || size == 8,
        Kind::Signed | Kind::Unsigned => matches!(size, 1 | 2 | 4 | 8),
        Kind::Bool => size == 1,
    };
    if !ok {
        return Err(unsupported());
    }
    Ok(Dtype {
        kind,
        size,
        big_endian,
    })
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
    if bytes.len() < 8 || &bytes[..6] != NPY_MAGIC {
        return Err(NpzError::BadMagic);
    }
    let major = bytes[6];
    let (header_len, header_start): (usize, usize) = match major {
        1 => {
            let b = bytes
                .get(8..10)
                .ok_or_else(|| header_err("truncated length"))?;
            (usize::from(u16::from_le_bytes([b[0], b[1]])), 10)
        }
        2 | 3 => {
            let b = bytes
                .get(8..12)
                .ok_or_else(|| header_err("truncated length"))?;
            let len = u32::from_le_bytes([b[0], b[1], b[2], b[3]]);
            (
                usize::try_from(len).map_err(|_| header_err("header length"))?,
                12,
            )
        }
        v => return Err(header_err(&format!("unsupported format version {v}"))),
    };
    let header_end = header_start
        .checked_add(header_len)
        .filter(|&end| end <= bytes.len())
        .ok_or_else(|| {
            header_err(&format!(
                "header of {header_len} bytes runs past the end of the data ({} bytes)",
                bytes.len()
            ))
        })?;
    let header = std::str::from_utf8(&bytes[header_start..header_end])
        .map_err(|_| header_err("header is not UTF-8"))?;
    let dict = parse_header_dict(header)?;
    let dtype = parse_dtype(&dict.descr)?;
    let count = checked_count(&dict.shape)
        .ok_or_else(|| header_err(&format!("shape {:?} overflows", dict.shape)))?;
    let data = &bytes[header_end..];
    let needed = (count as u64).saturating_mul(dtype.size as u64);
    if data.len() as u64 != needed {
        return Err(NpzError::DataSize {
            shape: dict.shape,
            item_size: dtype.size,
            needed,
            available: data.len(),
        });
    }
    let mut values = decode(data, dtype)?;
    if dict.fortran_order && dict.shape.len() > 1 {
        values = fortran_to_c(values, &dict.shape);
    }
    Ok(NpyArray {
        shape: dict.shape,
        data: values,
        descr: dict.descr,
    })
}

fn header_err(msg: &str) -> NpzError {
    NpzError::BadHeader(msg.to_string())
}

fn decode(data: &[u8], dtype: Dtype) -> Result<NpyData, NpzError> {
    let n = dtype.size;
    let word = |chunk: &[u8]| -> u64 {
        let mut buf = [0u8; 8];
        if dtype.big_endian {
            buf[8 - n..].copy_from_slice(chunk);
            u64::from_be_bytes(buf)
        } else {
            buf[..n].copy_from_slice(chunk);
            u64::from_le_bytes(buf)
        }
    };
    let chunks = data.chunks_exact(n);
    Ok(match dtype.kind {
        Kind::Float if n == 4 => NpyData::Float(
            chunks
                .map(|c| f64::from(f32::from_bits(word(c) as u32)))
                .collect(),
        ),
        Kind::Float => NpyData::Float(chunks.map(|c| f64::from_bits(word(c))).collect()),
        Kind::Signed => {
            let shift = 64 - 8 * n as u32;
            NpyData::Int(
                chunks
                    .map(|c| ((word(c) << shift) as i64) >> shift)
                    .collect(),
            )
        }
        Kind::Unsigned => NpyData::Int(
            chunks
                .map(|c| {
                    let v = word(c);
                    i64::try_from(v).map_err(|_| NpzError::IntegerRange(v))
                })
                .collect::<Result<_, _>>()?,
        ),
        Kind::Bool => NpyData::Int(chunks.map(|c| i64::from(c[0] != 0)).collect()),
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

struct HeaderDict {
    descr: String,
    fortran_order: bool,
    shape: Vec<usize>,
}

/// Parses the Python dict literal of a `.npy` header.
fn parse_header_dict(text: &str) -> Result<HeaderDict, NpzError> {
    let mut p = Parser {
        s: text.as_bytes(),
        i: 0,
    };
    p.expect(b'{')?;
    let (mut descr, mut fortran, mut shape) = (None, None, None);
    loop {
        p.skip_ws();
        if p.eat(b'}') {
            break;
        }
        let key = p.string()?;
        p.expect(b':')?;
        match key.as_str() {
            "descr" => descr = Some(p.string()?),
            "fortran_order" => fortran = Some(p.boolean()?),
            "shape" => shape = Some(p.tuple()?),
            other => return Err(header_err(&format!("unexpected key {other:?}"))),
        }
        p.skip_ws();
        if !p.eat(b',') {
            p.expect(b'}')?;
            break;
        }
    }
    Ok(HeaderDict {
        descr: descr.ok_or_else(|| header_err("missing 'descr'"))?,
        fortran_order: fortran.ok_or_else(|| header_err("missing 'fortran_order'"))?,
        shape: shape.ok_or_else(|| header_err("missing 'shape'"))?,
    })
}

struct Parser<'a> {
    s: &'a [u8],
    i: usize,
}

impl Parser<'_> {
    fn skip_ws(&mut self) {
        while self.i < self.s.len() && self.s[self.i].is_ascii_whitespace() {
            self.i += 1;
        }
    }

    fn eat(&mut self, c: u8) -> bool {
        self.skip_ws();
        if self.s.get(self.i) == Some(&c) {
            self.i += 1;
            true
        } else {
            false
        }
    }

    fn expect(&mut self, c: u8) -> Result<(), NpzError> {
        if self.eat(c) {
            Ok(())
        } else {
            Err(header_err(&format!(
                "expected {:?} at byte {}",
                c as char, self.i
            )))
        }
    }

    fn string(&mut self) -> Result<String, NpzError> {
        self.skip_ws();
        let quote = match self.s.get(self.i) {
            Some(&q @ (b'\'' | b'"')) => q,
            _ => return Err(header_err(&format!("expected a string at byte {}", self.i))),
        };
        let start = self.i + 1;
        let len = self.s[start..]
            .iter()
            .position(|&c| c == quote)
            .ok_or_else(|| header_err("unterminated string"))?;
        self.i = start + len + 1;
        Ok(String::from_utf8_lossy(&self.s[start..start + len]).into_owned())
    }

    fn boolean(&mut self) -> Result<bool, NpzError> {
        self.skip_ws();
        let rest = &self.s[self.i..];
        if rest.starts_with(b"True") {
            self.i += 4;
            Ok(true)
        } else if rest.starts_with(b"False") {
            self.i += 5;
            Ok(false)
        } else {
            Err(header_err("'fortran_order' is not True or False"))
        }
    }

    fn tuple(&mut self) -> Result<Vec<usize>, NpzError> {
        self.expect(b'(')?;
        let mut dims = Vec::new();
        loop {
            if self.eat(b')') {
                break;
            }
            self.skip_ws();
            let start = self.i;
            while self.i < self.s.len() && self.s[self.i].is_ascii_digit() {
                self.i += 1;
            }
            let digits = std::str::from_utf8(&self.s[start..self.i]).unwrap_or("");
            let d: usize = digits
                .parse()
                .map_err(|_| header_err(&format!("bad dimension at byte {start}")))?;
            dims.push(d);
            if !self.eat(b',') {
                self.expect(b')')?;
                break;
            }
        }
        Ok(dims)
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
}
