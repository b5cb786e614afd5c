//! Reading `.npy` arrays (through `npyz`, with the checks it leaves to its
//! caller) and the members of `.npz` archives.

use std::io::{Cursor, Read};

use super::{checked_count, NpyArray, NpyData, NpzError, MAX_MEMBER_BYTES, NPY_MAGIC};

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
