//! A variable's `miMATRIX` element: its sub-elements (array flags,
//! dimensions, name, real part) read in order, and the numeric element
//! types widened to `f64` (`uint8` kept as bytes).

use super::element::{
    Cursor, Endian, MI_DOUBLE, MI_INT16, MI_INT32, MI_INT64, MI_INT8, MI_SINGLE, MI_UINT16,
    MI_UINT32, MI_UINT64, MI_UINT8, MI_UTF8,
};
use super::{MatClass, MatError, MatValues, MatVariable};

/// The error of a malformed variable.
fn malformed(variable: &str, problem: String) -> MatError {
    MatError::Malformed {
        variable: variable.to_string(),
        problem,
    }
}

/// Parses the contents of an `miMATRIX` element that starts at `offset`.
pub(super) fn parse_matrix(
    data: &[u8],
    endian: Endian,
    offset: usize,
) -> Result<MatVariable, MatError> {
    let mut cursor = contents(data, endian, offset);
    let mut variable = read_header(&mut cursor, offset)?;
    if variable.class.is_numeric() {
        variable.values = read_real_part(&mut cursor, &variable.name, &variable.dims)?;
    }
    Ok(variable)
}

/// The name, class and dimensions of the `miMATRIX` element that starts at
/// `offset`, from the beginning of its contents (the values need not be
/// there): values [`MatValues::NotRead`] for a numeric class.
pub(super) fn parse_header(
    data: &[u8],
    endian: Endian,
    offset: usize,
) -> Result<MatVariable, MatError> {
    read_header(&mut contents(data, endian, offset), offset)
}

/// A cursor over the contents of the `miMATRIX` element at `offset`.
fn contents(data: &[u8], endian: Endian, offset: usize) -> Cursor<'_> {
    Cursor {
        bytes: data,
        pos: 0,
        base: offset + 8,
        endian,
    }
}

/// Array flags, dimensions and name, read in order; values
/// [`MatValues::NotRead`] (numeric) or [`MatValues::NotNumeric`].
fn read_header(cursor: &mut Cursor, offset: usize) -> Result<MatVariable, MatError> {
    let flags = read_array_flags(cursor, offset)?;
    let dims = read_dimensions(cursor, offset)?;
    let name = read_name(cursor, offset)?;
    Ok(MatVariable {
        name,
        class: flags.class,
        dims,
        complex: flags.complex,
        values: if flags.class.is_numeric() {
            MatValues::NotRead
        } else {
            MatValues::NotNumeric
        },
    })
}

/// The array flags of a variable.
struct ArrayFlags {
    class: MatClass,
    complex: bool,
}

/// Array flags: two uint32; class in the low byte of the first.
fn read_array_flags(cursor: &mut Cursor, offset: usize) -> Result<ArrayFlags, MatError> {
    let flags = cursor.tag()?;
    if flags.kind != MI_UINT32 || flags.data.len() != 8 {
        return Err(malformed(
            "",
            format!(
                "array flags at offset {offset}: expected 8 bytes of miUINT32, found type {} with {} bytes",
                flags.kind,
                flags.data.len()
            ),
        ));
    }
    let d = flags.data;
    let flag_word = cursor.endian.u32([d[0], d[1], d[2], d[3]]);
    Ok(ArrayFlags {
        class: MatClass::from_code((flag_word & 0xff) as u8),
        complex: flag_word & 0x0800 != 0,
    })
}

/// The dimensions: `miINT32` values, none negative.
fn read_dimensions(cursor: &mut Cursor, offset: usize) -> Result<Vec<usize>, MatError> {
    let dims_tag = cursor.tag()?;
    if dims_tag.kind != MI_INT32 || dims_tag.data.len() % 4 != 0 {
        return Err(malformed(
            "",
            format!(
                "dimensions at offset {offset}: expected miINT32, found type {} with {} bytes",
                dims_tag.kind,
                dims_tag.data.len()
            ),
        ));
    }
    let mut dims = Vec::with_capacity(dims_tag.data.len() / 4);
    for chunk in dims_tag.data.chunks_exact(4) {
        let d = cursor.endian.u32([chunk[0], chunk[1], chunk[2], chunk[3]]) as i32;
        let d = usize::try_from(d)
            .map_err(|_| malformed("", format!("negative dimension {d} at offset {offset}")))?;
        dims.push(d);
    }
    Ok(dims)
}

/// The variable's name (`miINT8`, `miUINT8` or `miUTF8` bytes).
fn read_name(cursor: &mut Cursor, offset: usize) -> Result<String, MatError> {
    let name_tag = cursor.tag()?;
    if name_tag.kind != MI_INT8 && name_tag.kind != MI_UINT8 && name_tag.kind != MI_UTF8 {
        return Err(malformed(
            "",
            format!(
                "array name at offset {offset}: expected miINT8, found type {}",
                name_tag.kind
            ),
        ));
    }
    Ok(String::from_utf8_lossy(name_tag.data).into_owned())
}

/// The real part of a numeric variable, holding exactly the dimensions'
/// element count.
fn read_real_part(cursor: &mut Cursor, name: &str, dims: &[usize]) -> Result<MatValues, MatError> {
    let numel = dims
        .iter()
        .try_fold(1usize, |acc, &d| acc.checked_mul(d))
        .ok_or_else(|| malformed(name, format!("dimensions {dims:?} overflow")))?;
    let real = cursor.tag()?;
    let values = decode_numeric(real.kind, real.data, cursor.endian).ok_or_else(|| {
        malformed(
            name,
            format!("real part has non-numeric type {}", real.kind),
        )
    })?;
    let count = match &values {
        MatValues::UInt8(v) => v.len(),
        MatValues::Float(v) => v.len(),
        MatValues::NotNumeric | MatValues::NotRead => 0,
    };
    if count != numel {
        return Err(malformed(
            name,
            format!("dimensions {dims:?} need {numel} values, the real part holds {count}"),
        ));
    }
    Ok(values)
}

/// Decodes the data of a numeric element; `None` for a non-numeric type or a
/// byte count that is not a multiple of the element size.
fn decode_numeric(kind: u32, data: &[u8], endian: Endian) -> Option<MatValues> {
    fn widen<const N: usize>(data: &[u8], f: impl Fn([u8; N]) -> f64) -> Option<Vec<f64>> {
        if data.len() % N != 0 {
            return None;
        }
        Some(
            data.chunks_exact(N)
                .map(|c| {
                    let mut b = [0u8; N];
                    b.copy_from_slice(c);
                    f(b)
                })
                .collect(),
        )
    }
    let little = endian == Endian::Little;
    let values = match kind {
        MI_UINT8 => return Some(MatValues::UInt8(data.to_vec())),
        MI_INT8 => widen::<1>(data, |b| f64::from(b[0] as i8)),
        MI_INT16 => widen::<2>(data, |b| {
            f64::from(if little {
                i16::from_le_bytes(b)
            } else {
                i16::from_be_bytes(b)
            })
        }),
        MI_UINT16 => widen::<2>(data, |b| {
            f64::from(if little {
                u16::from_le_bytes(b)
            } else {
                u16::from_be_bytes(b)
            })
        }),
        MI_INT32 => widen::<4>(data, |b| {
            f64::from(if little {
                i32::from_le_bytes(b)
            } else {
                i32::from_be_bytes(b)
            })
        }),
        MI_UINT32 => widen::<4>(data, |b| {
            f64::from(if little {
                u32::from_le_bytes(b)
            } else {
                u32::from_be_bytes(b)
            })
        }),
        MI_SINGLE => widen::<4>(data, |b| {
            f64::from(if little {
                f32::from_le_bytes(b)
            } else {
                f32::from_be_bytes(b)
            })
        }),
        MI_DOUBLE => widen::<8>(data, |b| {
            if little {
                f64::from_le_bytes(b)
            } else {
                f64::from_be_bytes(b)
            }
        }),
        MI_INT64 => widen::<8>(data, |b| {
            (if little {
                i64::from_le_bytes(b)
            } else {
                i64::from_be_bytes(b)
            }) as f64
        }),
        MI_UINT64 => widen::<8>(data, |b| {
            (if little {
                u64::from_le_bytes(b)
            } else {
                u64::from_be_bytes(b)
            }) as f64
        }),
        _ => None,
    }?;
    Some(MatValues::Float(values))
}
