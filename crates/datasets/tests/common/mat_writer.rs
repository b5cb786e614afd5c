//! A MAT v5 writer for tests and fuzzing seeds: encodes
//! [`datasets::mat::MatFile`] variables as an uncompressed little-endian
//! file that `datasets::mat::parse_mat` (and MATLAB, SciPy) read back, so
//! that edits and mutations reach the element structure instead of a zlib
//! stream. Each numeric variable keeps its class; bytes are stored as
//! `miUINT8` and other values as `miDOUBLE`; non-numeric variables are
//! skipped. Layout: MathWorks, "MAT-File Format", level 5 (a 128-byte
//! header, then one `miMATRIX` element per variable holding array flags,
//! dimensions, name and real part, each padded to 8 bytes).
//!
//! Also compiled into the `mat` fuzz target (`fuzz/fuzz_targets/mat.rs`)
//! through a `#[path]` module, so it uses only the public API.

use datasets::mat::{MatFile, MatValues};

/// MAT v5 data element types (Table 1-1 of the format description).
const MI_INT8: u32 = 1;
const MI_UINT8: u32 = 2;
const MI_INT32: u32 = 5;
const MI_UINT32: u32 = 6;
const MI_DOUBLE: u32 = 9;
const MI_MATRIX: u32 = 14;

/// Appends one data element (8-byte tag, data, zero padding to 8 bytes).
fn element(out: &mut Vec<u8>, kind: u32, data: &[u8]) {
    out.extend_from_slice(&kind.to_le_bytes());
    out.extend_from_slice(&(data.len() as u32).to_le_bytes());
    out.extend_from_slice(data);
    while out.len() % 8 != 0 {
        out.push(0);
    }
}

/// Encodes the numeric variables of `file` (see the module documentation).
pub fn write_mat(file: &MatFile) -> Vec<u8> {
    let mut out = Vec::new();
    let text = b"MATLAB 5.0 MAT-file, written by the datasets tests";
    out.extend_from_slice(text);
    out.resize(116, b' ');
    out.extend_from_slice(&[0; 8]);
    out.extend_from_slice(&[0x00, 0x01, b'I', b'M']);
    for var in &file.variables {
        let (kind, data): (u32, Vec<u8>) = match &var.values {
            MatValues::UInt8(bytes) => (MI_UINT8, bytes.clone()),
            MatValues::Float(values) => (
                MI_DOUBLE,
                values.iter().flat_map(|v| v.to_le_bytes()).collect(),
            ),
            MatValues::NotNumeric | MatValues::NotRead => continue,
        };
        let mut body = Vec::new();
        let flags = u32::from(var.class.code()) | if var.complex { 0x0800 } else { 0 };
        element(
            &mut body,
            MI_UINT32,
            &[flags.to_le_bytes(), [0; 4]].concat(),
        );
        let dims: Vec<u8> = var
            .dims
            .iter()
            .flat_map(|&d| (d as i32).to_le_bytes())
            .collect();
        element(&mut body, MI_INT32, &dims);
        element(&mut body, MI_INT8, var.name.as_bytes());
        element(&mut body, kind, &data);
        element(&mut out, MI_MATRIX, &body);
    }
    out
}
