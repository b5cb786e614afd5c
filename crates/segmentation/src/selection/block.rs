//! The blocks of image 1 over which a group's models are also tested: a
//! small object's matches lie together, and counted among the matches of
//! the block that holds them they are far less likely by chance than
//! among every match of the image.
//!
//! The family is fixed before the data (so its size counts as tests, a
//! union bound, the number of regions of an a-contrario detection;
//! Desolneux, Moisan & Morel, "From Gestalt Theory to Image Analysis",
//! 2008, chapter 4): at each level l = 2..=[`BLOCK_LEVELS`] the image is
//! cut into a 2^l × 2^l grid and a block is 2 × 2 adjacent cells, so the
//! blocks of a level overlap by a cell and every set of points narrower
//! and lower than a cell lies in one of them; (2^l − 1)² blocks per level,
//! [`block_count`] in all. A group is tested over the smallest block
//! holding its image-1 points ([`smallest_block`]), when one does.

use super::background::ImageRect;
use geometry::Correspondences;

/// The finest level: grids of 4 × 4 and 8 × 8 cells, blocks of half and a
/// quarter of the image's sides. Measured at 2–5 levels on the wide
/// validation: every family within 0.04 points of ME, 3 the smallest mean
/// (results/notes/selection.md, "Blocks").
pub const BLOCK_LEVELS: u32 = 3;

/// Blocks in the family: `Σ_{l=2..=L} (2^l − 1)²` (58 for L = 3).
///
/// ```
/// assert_eq!(segmentation::selection::block::block_count(), 9 + 49);
/// ```
pub fn block_count() -> usize {
    (2..=BLOCK_LEVELS).map(|l| ((1usize << l) - 1).pow(2)).sum()
}

/// The smallest block of the family that holds the image-1 points of the
/// matches `own` of `points` (the finest level first; at a level, the
/// block whose first cell holds their smallest coordinates), or None when
/// no block does (they spread over more than half a side) or `own` is
/// empty.
pub fn smallest_block(
    points: &Correspondences,
    own: &[usize],
    image: &ImageRect,
) -> Option<ImageRect> {
    let (lo, hi) = extent(points, own)?;
    let sides = image.sides();
    (2..=BLOCK_LEVELS).rev().find_map(|level| {
        let cells = f64::from(1u32 << level);
        let cell = sides.map(|s| s / cells);
        let first = [0, 1].map(|i| {
            ((lo[i] - image.min[i]) / cell[i])
                .floor()
                .clamp(0.0, cells - 2.0)
        });
        let min = [0, 1].map(|i| image.min[i] + first[i] * cell[i]);
        let max = [0, 1].map(|i| min[i] + 2.0 * cell[i]);
        let block = ImageRect { min, max };
        (block.contains(lo) && block.contains(hi)).then_some(block)
    })
}

/// The smallest and largest image-1 coordinates of `own`.
fn extent(points: &Correspondences, own: &[usize]) -> Option<([f64; 2], [f64; 2])> {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for &m in own {
        let p = points.point1(m);
        for i in 0..2 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    (!own.is_empty()).then_some((lo, hi))
}

/// Per match of `points`: whether its image-1 point lies in `block`.
pub fn inside(points: &Correspondences, block: &ImageRect) -> Vec<bool> {
    (0..points.len())
        .map(|m| block.contains(points.point1(m)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn points(xy: &[[f64; 2]]) -> Correspondences {
        Correspondences::new(xy, xy).unwrap()
    }

    /// Every block of the family, by brute force.
    fn family(image: &ImageRect) -> Vec<ImageRect> {
        let sides = image.sides();
        let mut blocks = Vec::new();
        for level in 2..=BLOCK_LEVELS {
            let cells = 1usize << level;
            let cell = sides.map(|s| s / cells as f64);
            for j in 0..cells - 1 {
                for i in 0..cells - 1 {
                    let min = [
                        image.min[0] + i as f64 * cell[0],
                        image.min[1] + j as f64 * cell[1],
                    ];
                    let max = [min[0] + 2.0 * cell[0], min[1] + 2.0 * cell[1]];
                    blocks.push(ImageRect { min, max });
                }
            }
        }
        blocks
    }

    #[test]
    fn the_smallest_block_is_the_smallest_of_the_family_that_holds_the_points() {
        let image = ImageRect::centred((640, 480));
        assert_eq!(family(&image).len(), block_count());
        // Point sets from a fixed grid of corners and extents.
        for (x, y, dx, dy) in [
            (-300.0, -220.0, 10.0, 10.0),
            (-10.0, -10.0, 20.0, 20.0),
            (100.0, 50.0, 150.0, 30.0),
            (-300.0, 0.0, 300.0, 100.0),
            (250.0, 200.0, 60.0, 30.0),
            (-200.0, -200.0, 400.0, 10.0),
        ] {
            let p = points(&[[x, y], [x + dx, y + dy], [x + dx / 2.0, y]]);
            let own = [0, 1, 2];
            let found = smallest_block(&p, &own, &image);
            let holding: Vec<ImageRect> = family(&image)
                .into_iter()
                .filter(|b| (0..3).all(|m| b.contains(p.point1(m))))
                .collect();
            let area = |b: &ImageRect| b.sides()[0] * b.sides()[1];
            let smallest = holding.iter().map(area).fold(f64::INFINITY, f64::min);
            match found {
                Some(b) => {
                    assert!(holding.contains(&b), "{x} {y}: {b:?}");
                    assert_eq!(area(&b), smallest, "{x} {y}");
                }
                None => assert!(holding.is_empty(), "{x} {y}: {holding:?}"),
            }
        }
        // Points across more than half the width: no block.
        let wide = points(&[[-200.0, 0.0], [200.0, 0.0]]);
        assert_eq!(smallest_block(&wide, &[0, 1], &image), None);
        assert_eq!(smallest_block(&wide, &[], &image), None);
    }

    #[test]
    fn inside_marks_the_matches_of_the_block() {
        let image = ImageRect::centred((640, 480));
        let p = points(&[[-310.0, -230.0], [-150.0, -130.0], [0.0, 0.0]]);
        let block = smallest_block(&p, &[0], &image).unwrap();
        assert_eq!(block.min, [-320.0, -240.0]);
        assert_eq!(block.max, [-160.0, -120.0]);
        assert_eq!(inside(&p, &block), [true, false, false]);
    }
}
