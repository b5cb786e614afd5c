//! The data elements of a MAT v5 stream: byte order, the 8-byte and
//! 4-byte ("small") tags with their padding, bounds-checked reads, and the
//! capped inflation of `miCOMPRESSED` elements.

use std::io::Read;

use flate2::read::ZlibDecoder;

use super::{MatError, MAX_DECOMPRESSED_BYTES};

/// MAT v5 data element types (Table 1-1 of the format description).
pub(super) const MI_INT8: u32 = 1;
pub(super) const MI_UINT8: u32 = 2;
pub(super) const MI_INT16: u32 = 3;
pub(super) const MI_UINT16: u32 = 4;
pub(super) const MI_INT32: u32 = 5;
pub(super) const MI_UINT32: u32 = 6;
pub(super) const MI_SINGLE: u32 = 7;
pub(super) const MI_DOUBLE: u32 = 9;
pub(super) const MI_INT64: u32 = 12;
pub(super) const MI_UINT64: u32 = 13;
pub(super) const MI_MATRIX: u32 = 14;
pub(super) const MI_COMPRESSED: u32 = 15;
pub(super) const MI_UTF8: u32 = 16;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Endian {
    /// `IM`: little-endian.
    Little,
    /// `MI`: big-endian.
    Big,
}

impl Endian {
    /// A `u32` in this byte order.
    pub(super) fn u32(self, b: [u8; 4]) -> u32 {
        match self {
            Endian::Little => u32::from_le_bytes(b),
            Endian::Big => u32::from_be_bytes(b),
        }
    }
}

/// A data element: its type and the bytes of its data (padding excluded).
pub(super) struct Tag<'a> {
    /// The element type (`MI_*`).
    pub(super) kind: u32,
    /// The element's data.
    pub(super) data: &'a [u8],
}

/// A read position in a byte slice; `base` is the slice's offset in the
/// enclosing stream, for error messages.
pub(super) struct Cursor<'a> {
    /// The bytes read.
    pub(super) bytes: &'a [u8],
    /// The read position in `bytes`.
    pub(super) pos: usize,
    /// The offset of `bytes` in the enclosing stream.
    pub(super) base: usize,
    /// The file's byte order.
    pub(super) endian: Endian,
}

impl<'a> Cursor<'a> {
    /// Bytes left after the read position.
    pub(super) fn remaining(&self) -> usize {
        self.bytes.len() - self.pos
    }

    /// The bytes left.
    pub(super) fn rest(&self) -> &'a [u8] {
        &self.bytes[self.pos..]
    }

    /// The error of an element that needs `needed` bytes here.
    fn truncated(&self, needed: u64) -> MatError {
        MatError::Truncated {
            offset: self.base + self.pos,
            needed,
            available: self.remaining(),
        }
    }

    /// The next `n` bytes.
    fn take(&mut self, n: usize) -> Result<&'a [u8], MatError> {
        if n > self.remaining() {
            return Err(self.truncated(n as u64));
        }
        let out = &self.bytes[self.pos..self.pos + n];
        self.pos += n;
        Ok(out)
    }

    /// The next `u32`.
    fn read_u32(&mut self) -> Result<u32, MatError> {
        let b = self.take(4)?;
        Ok(self.endian.u32([b[0], b[1], b[2], b[3]]))
    }

    /// The type and byte count of an 8-byte element tag, without reading
    /// (or requiring) its data.
    pub(super) fn raw_tag_header(&mut self) -> Result<(u32, u32), MatError> {
        let kind = self.read_u32()?;
        let size = self.read_u32()?;
        Ok((kind, size))
    }

    /// Reads one data element (normal or small format) and skips its padding.
    pub(super) fn tag(&mut self) -> Result<Tag<'a>, MatError> {
        let start = self.pos;
        let first = self.read_u32()?;
        let small_size = first >> 16;
        if small_size != 0 {
            // Small data element: type in the low 16 bits, up to 4 data bytes.
            if small_size > 4 {
                self.pos = start;
                return Err(MatError::Malformed {
                    variable: String::new(),
                    problem: format!(
                        "small data element at offset {} claims {small_size} bytes (at most 4)",
                        self.base + start
                    ),
                });
            }
            let data = self.take(4)?;
            return Ok(Tag {
                kind: first & 0xffff,
                data: &data[..small_size as usize],
            });
        }
        let size = self.read_u32()?;
        let size_usize = usize::try_from(size).map_err(|_| self.truncated(u64::from(size)))?;
        let data = self.take(size_usize).inspect_err(|_| self.pos = start)?;
        let data_start = self.pos - size_usize;
        // Compressed elements are not padded; all others are padded to 8 bytes.
        if first != MI_COMPRESSED {
            let padded_end = (data_start - start + size_usize).div_ceil(8) * 8 + start;
            self.pos = padded_end.min(self.bytes.len());
        }
        Ok(Tag { kind: first, data })
    }
}

/// Inflates a zlib stream, refusing to produce more than
/// [`MAX_DECOMPRESSED_BYTES`]. Once `prefix_len` bytes are out, `stop`
/// sees them and may end the inflation there (`None`): a caller that only
/// needs a variable's header does not inflate the rest. A stream shorter
/// than `prefix_len` is inflated whole without asking.
pub(super) fn inflate(
    compressed: &[u8],
    offset: usize,
    prefix_len: usize,
    stop: impl FnOnce(&[u8]) -> bool,
) -> Result<Option<Vec<u8>>, MatError> {
    let failed = |e: std::io::Error| MatError::Decompress {
        offset,
        message: e.to_string(),
    };
    let mut out = Vec::new();
    let mut decoder = ZlibDecoder::new(compressed).take(MAX_DECOMPRESSED_BYTES + 1);
    (&mut decoder)
        .take(prefix_len as u64)
        .read_to_end(&mut out)
        .map_err(failed)?;
    if out.len() == prefix_len && stop(&out) {
        return Ok(None);
    }
    decoder.read_to_end(&mut out).map_err(failed)?;
    if out.len() as u64 > MAX_DECOMPRESSED_BYTES {
        return Err(MatError::DecompressedTooLarge {
            offset,
            limit: MAX_DECOMPRESSED_BYTES,
        });
    }
    Ok(Some(out))
}
