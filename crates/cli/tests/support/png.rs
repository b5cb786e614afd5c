//! PNG decoding for the figure tests (the integration tests and the unit
//! tests of `src/plots`, which include this file by path).
#![allow(dead_code)]

use image::RgbImage;
use std::collections::HashSet;
use std::path::Path;

/// Decodes a PNG file, checking that it is one and is not a flat colour.
pub fn decode_png(path: &Path) -> RgbImage {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert!(
        bytes.starts_with(b"\x89PNG\r\n\x1a\n"),
        "{} is not a PNG",
        path.display()
    );
    let image = image::load_from_memory_with_format(&bytes, image::ImageFormat::Png)
        .unwrap()
        .to_rgb8();
    let first = image.get_pixel(0, 0);
    assert!(
        image.pixels().any(|p| p != first),
        "{} is one flat colour",
        path.display()
    );
    image
}

/// As [`decode_png`], and checks the size, that the image has several
/// colours and that the top strip (the title) holds dark text pixels.
pub fn decode_chart(path: &Path, size: (u32, u32)) -> RgbImage {
    let image = decode_png(path);
    assert_eq!(image.dimensions(), size, "{}", path.display());
    let colours: HashSet<[u8; 3]> = image.pixels().map(|p| p.0).collect();
    assert!(colours.len() > 2, "{} is flat: {colours:?}", path.display());
    let dark_title_pixels = (0..50)
        .flat_map(|y| (0..image.width()).map(move |x| (x, y)))
        .filter(|&(x, y)| image.get_pixel(x, y).0.iter().all(|&c| c < 90))
        .count();
    assert!(
        dark_title_pixels > 50,
        "{}: no title text rendered",
        path.display()
    );
    image
}
