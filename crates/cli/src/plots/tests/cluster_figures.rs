//! The cluster figures: points at their pixels in their colours, over
//! the images, inconsistent input refused, the ground truth on AdelaideRMF.

use super::*;

/// Points on a coarse lattice (no two markers overlap at scale 4), three
/// clusters by column band and every seventh point an outlier.
fn lattice_scene() -> (Vec<[f64; 2]>, Vec<[f64; 2]>, Vec<i32>) {
    let mut p1 = Vec::new();
    let mut p2 = Vec::new();
    let mut labels = Vec::new();
    for gy in 0..6 {
        for gx in 0..9 {
            let (x, y) = (10.0 + 20.0 * gx as f64, 8.0 + 22.0 * gy as f64);
            p1.push([x, y]);
            p2.push([199.0 - x, y + 3.0]);
            let i = labels.len();
            labels.push(if i % 7 == 3 { -1 } else { gx / 3 });
        }
    }
    (p1, p2, labels)
}

#[test]
fn clusters_are_drawn_at_their_pixels_in_their_colours() {
    let size = (200, 150);
    let (p1, p2, labels) = lattice_scene();
    let layout = ClustersLayout::new(size).unwrap();
    assert_eq!(layout.scale, 4.0);
    assert_eq!(layout.panel_size, (800, 600));
    // Pixel centres map to the centres of the 4 × 4 blocks they become.
    let (ox, oy) = layout.origins[0];
    assert_eq!(layout.to_canvas(0, [10.0, 8.0]), (ox + 42, oy + 34));
    assert_eq!(layout.to_canvas(0, [0.0, 0.0]), (ox + 2, oy + 2));
    // Image 2's panel lies right of image 1's, on the same row.
    let (ox2, oy2) = layout.origins[1];
    assert!(ox2 >= ox + 800 && oy2 == oy);
    assert_eq!(layout.to_canvas(1, [10.0, 8.0]), (ox2 + 42, oy2 + 34));
    assert_eq!(layout.canvas_size.0 as i32, ox2 + 800 + ox);
    let dir = tempfile::tempdir().unwrap();
    let png = out(&dir, "clusters.png");
    clusters_over_images(size, None, &p1, &p2, &labels, "lattice", &png).unwrap();
    let image = decode_png(&png, layout.canvas_size);
    for (view, points) in [&p1, &p2].into_iter().enumerate() {
        for (p, &label) in points.iter().zip(&labels) {
            let (x, y) = layout.to_canvas(view, *p);
            let expected = if label < 0 {
                OUTLIER_COLOUR
            } else {
                cluster_colour(label as usize)
            };
            assert_eq!(
                *image.get_pixel(x as u32, y as u32),
                rgb(expected),
                "view {view}, point {p:?}, label {label}"
            );
        }
    }
    // The blank canvas is drawn where there is no point.
    let (ox, oy) = layout.origins[0];
    assert_eq!(
        image.get_pixel(ox as u32 + 2, oy as u32 + 2).0,
        [236, 236, 236]
    );

    let svg = out(&dir, "clusters.svg");
    clusters_over_images(size, None, &p1, &p2, &labels, "lattice", &svg).unwrap();
    let outliers = labels.iter().filter(|&&l| l < 0).count();
    let cluster0 = labels.iter().filter(|&&l| l == 0).count();
    let text = read_svg(
        &svg,
        &[
            "lattice",
            "image 1",
            "image 2",
            &format!("cluster 0 ({cluster0})"),
            "cluster 2 (",
            &format!("outliers ({outliers})"),
        ],
    );
    assert!(!text.contains("data:image/png"));
}

#[test]
fn clusters_are_drawn_over_the_images() {
    let size = (200, 150);
    let (p1, p2, labels) = lattice_scene();
    let layout = ClustersLayout::new(size).unwrap();
    let left = RgbImage::from_pixel(size.0, size.1, Rgb([250, 220, 40]));
    let right = RgbImage::from_pixel(size.0, size.1, Rgb([40, 60, 90]));
    let dir = tempfile::tempdir().unwrap();
    let png = out(&dir, "over.png");
    clusters_over_images(size, Some((&left, &right)), &p1, &p2, &labels, "over", &png).unwrap();
    let image = decode_png(&png, layout.canvas_size);
    for (view, colour) in [[250, 220, 40], [40, 60, 90]].into_iter().enumerate() {
        let (ox, oy) = layout.origins[view];
        assert_eq!(
            image.get_pixel(ox as u32 + 2, oy as u32 + 2).0,
            colour,
            "view {view}"
        );
        // Points stay on top of the image.
        let (x, y) = layout.to_canvas(view, p1[0]);
        let (x, y) = if view == 0 {
            (x, y)
        } else {
            layout.to_canvas(1, p2[0])
        };
        assert_eq!(*image.get_pixel(x as u32, y as u32), rgb(cluster_colour(0)));
    }

    let svg = out(&dir, "over.svg");
    clusters_over_images(size, Some((&left, &right)), &p1, &p2, &labels, "over", &svg).unwrap();
    let text = read_svg(&svg, &["over", "image 1"]);
    assert_eq!(
        text.matches("xlink:href=\"data:image/png;base64,").count(),
        2
    );
    // The images lie under the drawing: right after the root element.
    let first_image = text.find("<image").unwrap();
    let first_circle = text.find("<circle").unwrap();
    assert!(first_image < first_circle);
}

#[test]
fn clusters_reject_inconsistent_input() {
    let dir = tempfile::tempdir().unwrap();
    let path = out(&dir, "bad.svg");
    let p = vec![[1.0, 1.0]; 3];
    let err = clusters_over_images((10, 10), None, &p, &p, &[0, 0], "t", &path).unwrap_err();
    assert_eq!(
        err.to_string(),
        format!(
            "{}: invalid plot input: `points1` has 3 points, `points2` 3 and `labels` 2",
            path.display()
        )
    );
    let err = clusters_over_images((0, 10), None, &p, &p, &[0, 0, 0], "t", &path).unwrap_err();
    assert!(
        err.to_string().ends_with("`image_size` 0 x 10 is empty"),
        "{err}"
    );
    let small = RgbImage::new(9, 10);
    let full = RgbImage::new(10, 10);
    let err = clusters_over_images(
        (10, 10),
        Some((&full, &small)),
        &p,
        &p,
        &[0, 0, 0],
        "t",
        &path,
    )
    .unwrap_err();
    assert!(
        err.to_string()
            .ends_with("image 2 is 9 x 10, `image_size` is 10 x 10"),
        "{err}"
    );
    assert!(!path.exists());
}

#[test]
fn ground_truth_clusters_sit_on_the_adelaidermf_objects() {
    let file = datasets::workspace_datasets_dir().join("adelaidermf/F/biscuitbook.mat");
    if !file.exists() {
        // CI links the shared datasets first: there, a missing file fails.
        assert!(
            std::env::var_os("CI").is_none(),
            "{} not found under CI (scripts/link-datasets.sh links it)",
            file.display()
        );
        eprintln!(
            "skipped: {} not found (run scripts/link-datasets.sh)",
            file.display()
        );
        return;
    }
    let scene = datasets::adelaidermf::load_scene(&file).unwrap();
    let (img1, img2) = scene.images.as_ref().expect("AdelaideRMF ships its images");
    let labels = ground_truth_plot_labels(scene.labels.as_ref().unwrap());
    let dir = tempfile::tempdir().unwrap();
    let png = out(&dir, "biscuitbook.png");
    clusters_over_images(
        scene.image_size,
        Some((img1, img2)),
        &scene.points1,
        &scene.points2,
        &labels,
        "biscuitbook: ground truth",
        &png,
    )
    .unwrap();
    let layout = ClustersLayout::new(scene.image_size).unwrap();
    let image = decode_png(&png, layout.canvas_size);
    // Every inlier is drawn at its pixel in its colour, unless a later
    // marker of another motion covers it.
    let mut total = 0;
    let mut matching = 0;
    for (view, points) in [&scene.points1, &scene.points2].into_iter().enumerate() {
        for (p, &label) in points.iter().zip(&labels) {
            if label < 0 {
                continue;
            }
            let (x, y) = layout.to_canvas(view, *p);
            total += 1;
            matching += usize::from(
                *image.get_pixel(x as u32, y as u32) == rgb(cluster_colour(label as usize)),
            );
        }
    }
    assert!(matching * 100 >= total * 95, "{matching} of {total}");

    let svg = out(&dir, "biscuitbook.svg");
    clusters_over_images(
        scene.image_size,
        Some((img1, img2)),
        &scene.points1,
        &scene.points2,
        &labels,
        "biscuitbook: ground truth",
        &svg,
    )
    .unwrap();
    read_svg(&svg, &["biscuitbook: ground truth", "cluster 1 ("]);
}
