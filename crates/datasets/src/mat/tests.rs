//! Unit tests of the MAT v5 reader on files built in memory.
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

/// A file of zlib-compressed variables, one `miCOMPRESSED` element each.
fn build_compressed(vars: &[TestVar]) -> Vec<u8> {
    use flate2::write::ZlibEncoder;
    use std::io::Write;
    let mut file = build_mat(false, &[])[..128].to_vec();
    for var in vars {
        let plain = build_mat(false, std::slice::from_ref(var));
        let mut encoder = ZlibEncoder::new(Vec::new(), flate2::Compression::default());
        encoder.write_all(&plain[128..]).unwrap();
        let compressed = encoder.finish().unwrap();
        file.extend_from_slice(&MI_COMPRESSED.to_le_bytes());
        file.extend_from_slice(&(compressed.len() as u32).to_le_bytes());
        file.extend_from_slice(&compressed);
    }
    file
}

#[test]
fn unwanted_variables_keep_their_header_and_are_not_inflated() {
    // An image large enough to be skipped after its header, a small
    // variable inflated whole either way.
    // 100 kB of pseudo-random pixels (a linear congruential sequence):
    // they do not compress, so the damage at the end of the stream is
    // far past what inflating the header reads.
    let pixels: Vec<u8> = (0..100_000u32)
        .scan(12345u32, |x, _| {
            *x = x.wrapping_mul(1_103_515_245).wrapping_add(12_345);
            Some((*x >> 16) as u8)
        })
        .collect();
    let vars: [TestVar; 2] = [
        ("img1", 9, &[200, 500], MI_UINT8, pixels),
        ("label", 6, &[1, 4], MI_UINT8, vec![0, 1, 2, 2]),
    ];
    let bytes = build_compressed(&vars);
    let all = parse_mat(&bytes).unwrap();
    for skipped in ["img1", "label"] {
        let some = parse_mat_selected(&bytes, |name| name != skipped).unwrap();
        assert_eq!(some.variables.len(), 2);
        for (got, full) in some.variables.iter().zip(&all.variables) {
            assert_eq!(
                (&got.name, got.class, &got.dims),
                (&full.name, full.class, &full.dims)
            );
            if got.name == skipped {
                assert_eq!(got.values, MatValues::NotRead);
            } else {
                assert_eq!(got, full);
            }
        }
    }
    // A stream damaged past the skipped image's header: reading it
    // fails, skipping it does not.
    let mut damaged = bytes.clone();
    let image_end = 128 + 8 + u32::from_le_bytes(bytes[132..136].try_into().unwrap()) as usize;
    damaged[image_end - 40..image_end].fill(0xff);
    assert!(matches!(
        parse_mat(&damaged),
        Err(MatError::Decompress { .. })
    ));
    let some = parse_mat_selected(&damaged, |name| name != "img1").unwrap();
    assert_eq!(some.get("label"), all.get("label"));
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
