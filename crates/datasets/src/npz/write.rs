//! Writing `.npy` arrays (NumPy's 64-byte header alignment) and `.npz`
//! archives.

use std::io::{Seek, Write};

use super::{NpyArray, NpyData, NpzError, NPY_MAGIC};

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
