//! The 19 AdelaideRMF fundamental-matrix scenes, checked against values read
//! with scipy.io.loadmat.

mod common;

use common::mat_writer::write_mat;
use datasets::adelaidermf::{
    load_scene, parse_scene, AdelaideRmf, LoadOptions, FUNDAMENTAL_SCENES,
};
use datasets::mat::{parse_mat, MatValues};
use datasets::DatasetError;
use std::path::Path;

/// (scene, N, motions, outliers), as scipy.io.loadmat reads the files.
const TABLE: [(&str, usize, usize, usize); 19] = [
    ("biscuit", 330, 1, 184),
    ("biscuitbook", 341, 2, 162),
    ("biscuitbookbox", 259, 3, 97),
    ("boardgame", 279, 3, 113),
    ("book", 187, 1, 82),
    ("breadcartoychips", 237, 4, 82),
    ("breadcube", 242, 2, 77),
    ("breadcubechips", 230, 3, 81),
    ("breadtoy", 288, 2, 106),
    ("breadtoycar", 166, 3, 56),
    ("carchipscube", 165, 3, 60),
    ("cube", 302, 1, 205),
    ("cubebreadtoychips", 327, 4, 88),
    ("cubechips", 284, 2, 143),
    ("cubetoy", 249, 2, 99),
    ("dinobooks", 360, 3, 155),
    ("game", 233, 1, 170),
    ("gamebiscuit", 328, 2, 167),
    ("toycubecar", 200, 3, 72),
];

#[test]
fn all_19_scenes_load_with_the_expected_counts() {
    let data = AdelaideRmf::open(common::adelaidermf_dir()).unwrap();
    let scenes = data.load_all(LoadOptions::default()).unwrap();
    assert_eq!(scenes.len(), 19);
    for (scene, &(name, n, motions, outliers)) in scenes.iter().zip(TABLE.iter()) {
        assert_eq!(scene.name, name);
        assert_eq!(scene.len(), n, "{name}: N");
        assert_eq!(scene.num_motions(), motions, "{name}: motions");
        assert_eq!(scene.num_outliers(), outliers, "{name}: outliers");
        // Labels are exactly 0..=motions.
        let labels = scene.labels.as_ref().unwrap();
        assert_eq!(labels.iter().copied().max(), Some(motions as i32), "{name}");
        assert_eq!(scene.image_size, (640, 480), "{name}");
        assert_eq!(scene.principal_point, [319.5, 239.5], "{name}");
        assert_eq!(scene.focal_prior(), 640.0);
        assert_eq!(scene.true_focal, None);
        assert!(scene.gt_fundamentals.is_empty());
        let (a, b) = scene.images.as_ref().expect("images");
        assert_eq!(a.dimensions(), (640, 480));
        assert_eq!(b.dimensions(), (640, 480));
        // Every point lies inside its image.
        for (i, (p, q)) in scene.points1.iter().zip(&scene.points2).enumerate() {
            for pt in [p, q] {
                assert!(
                    (0.0..=639.0).contains(&pt[0]) && (0.0..=479.0).contains(&pt[1]),
                    "{name}: point {i} = {pt:?} outside the 640 x 480 image"
                );
            }
        }
    }
}

#[test]
fn scene_list_matches_the_readme() {
    let readme =
        std::fs::read_to_string(common::shared_dir().join("datasets/adelaidermf/readme.txt"))
            .expect("../shared/datasets/adelaidermf/readme.txt (see datasets/README.md)");
    let after = readme.split("[Fundamental Matrix Data]").nth(1).unwrap();
    let line = after.lines().find(|l| !l.trim().is_empty()).unwrap();
    let mut names: Vec<&str> = line.split(',').map(str::trim).collect();
    names.sort_unstable();
    assert_eq!(names, FUNDAMENTAL_SCENES.to_vec());
    assert_eq!(TABLE.map(|t| t.0), FUNDAMENTAL_SCENES);
}

/// A pixel and a correspondence of one scene, as scipy.io.loadmat reads them.
struct Probe {
    scene: &'static str,
    /// (row, column) of the probed pixel.
    at: (u32, u32),
    /// img1 and img2 at that pixel; grayscale scenes repeat the gray value.
    rgb: ([u8; 3], [u8; 3]),
    /// data(:, 8) in MATLAB terms: x1, y1, x2, y2 of correspondence 7.
    column7: [f64; 4],
}

#[test]
fn orientation_matches_scipy() {
    let dir = common::adelaidermf_dir();
    let probes = [
        Probe {
            scene: "biscuit",
            at: (10, 20),
            rgb: ([114, 111, 102], [120, 118, 106]),
            column7: [
                79.26056671142578,
                297.7234191894531,
                319.1898498535156,
                318.4884338378906,
            ],
        },
        Probe {
            scene: "dinobooks",
            at: (100, 200),
            rgb: ([138; 3], [150; 3]),
            column7: [
                95.9728012084961,
                210.85069274902344,
                567.1683959960938,
                349.4267883300781,
            ],
        },
        Probe {
            scene: "boardgame",
            at: (479, 639),
            rgb: ([20; 3], [150; 3]),
            column7: [
                97.93812561035156,
                250.6055145263672,
                511.32525634765625,
                192.60491943359375,
            ],
        },
        Probe {
            scene: "cubechips",
            at: (300, 5),
            rgb: ([112, 112, 102], [140, 142, 137]),
            column7: [
                36.55895233154297,
                85.11503601074219,
                522.5128784179688,
                55.20391082763672,
            ],
        },
    ];
    for p in probes {
        let name = p.scene;
        let scene = load_scene(dir.join(format!("{name}.mat"))).unwrap();
        let (a, b) = scene.images.as_ref().unwrap();
        let (row, col) = p.at;
        assert_eq!(
            a.get_pixel(col, row).0,
            p.rgb.0,
            "{name} img1 ({row}, {col})"
        );
        assert_eq!(
            b.get_pixel(col, row).0,
            p.rgb.1,
            "{name} img2 ({row}, {col})"
        );
        assert_eq!(scene.points1[7], [p.column7[0], p.column7[1]], "{name}");
        assert_eq!(scene.points2[7], [p.column7[2], p.column7[3]], "{name}");
    }
}

#[test]
fn image_sums_match_scipy() {
    // Sum of all img1 values (scipy: int64 sum over H x W x 3, or H x W for grayscale).
    let dir = common::adelaidermf_dir();
    for (name, sum, channels) in [
        ("biscuit", 127_180_873u64, 3u64),
        ("dinobooks", 37_813_264, 1),
    ] {
        let scene = load_scene(dir.join(format!("{name}.mat"))).unwrap();
        let img = &scene.images.as_ref().unwrap().0;
        let total: u64 = img.as_raw().iter().map(|&v| u64::from(v)).sum();
        assert_eq!(total, sum * (3 / channels), "{name}");
    }
}

#[test]
fn without_images_the_scene_is_otherwise_identical() {
    let data = AdelaideRmf::open(common::adelaidermf_dir()).unwrap();
    let full = data.load("breadtoy").unwrap();
    let light = data
        .load_with("breadtoy", LoadOptions { images: false })
        .unwrap();
    assert!(light.images.is_none());
    assert_eq!(
        light,
        datasets::Scene {
            images: None,
            ..full
        }
    );
}

#[test]
fn unknown_scene_and_missing_directory_are_reported() {
    let data = AdelaideRmf::open(common::adelaidermf_dir()).unwrap();
    let err = data.load("barrsmith").unwrap_err();
    assert!(matches!(err, DatasetError::UnknownScene { .. }));
    assert!(
        err.to_string().contains("no scene named `barrsmith`"),
        "{err}"
    );

    let err = AdelaideRmf::open("/nonexistent/adelaidermf/F").unwrap_err();
    let msg = err.to_string();
    assert!(msg.contains("/nonexistent/adelaidermf/F"), "{msg}");
    assert!(
        msg.contains("scripts/link-datasets.sh") && msg.contains("datasets/README.md"),
        "{msg}"
    );
}

/// Re-encodes a real file uncompressed after `edit`, and parses it as a scene.
fn edited(edit: impl FnOnce(&mut datasets::mat::MatFile)) -> Result<datasets::Scene, DatasetError> {
    let bytes = std::fs::read(common::adelaidermf_dir().join("book.mat")).unwrap();
    let mut mat = parse_mat(&bytes).unwrap();
    edit(&mut mat);
    parse_scene(
        &write_mat(&mat),
        "book",
        Path::new("book.mat"),
        LoadOptions::default(),
    )
}

#[test]
fn test_writer_round_trips_every_numeric_variable() {
    for name in ["book", "dinobooks"] {
        let bytes = std::fs::read(common::adelaidermf_dir().join(format!("{name}.mat"))).unwrap();
        let mat = parse_mat(&bytes).unwrap();
        assert_eq!(mat.variables.len(), 5, "{name}");
        assert_eq!(parse_mat(&write_mat(&mat)).unwrap(), mat, "{name}");
    }
}

#[test]
fn uncompressed_re_encoding_loads_identically() {
    let dir = common::adelaidermf_dir();
    let original = load_scene(dir.join("book.mat")).unwrap();
    assert_eq!(edited(|_| {}).unwrap(), original);
}

#[test]
fn malformed_variables_give_errors_naming_file_and_field() {
    type Edit = Box<dyn FnOnce(&mut datasets::mat::MatFile)>;
    let cases: Vec<(Edit, &str)> = vec![
        (
            Box::new(|m| m.variables.retain(|v| v.name != "label")),
            "book.mat: missing variable `label`",
        ),
        (
            Box::new(|m| m.variables.retain(|v| v.name != "img2")),
            "book.mat: missing variable `img2`",
        ),
        (
            Box::new(|m| {
                let v = m.variables.iter_mut().find(|v| v.name == "data").unwrap();
                v.dims = vec![3, 374];
            }),
            "book.mat: variable `data`: dimensions [3, 374], expected 6 x N",
        ),
        (
            Box::new(|m| {
                let v = m.variables.iter_mut().find(|v| v.name == "data").unwrap();
                if let MatValues::Float(x) = &mut v.values {
                    x[6 * 4 + 1] = f64::NAN;
                }
            }),
            "book.mat: scene `book`: field `points1` at index 4: non-finite coordinate",
        ),
        (
            Box::new(|m| {
                let v = m.variables.iter_mut().find(|v| v.name == "data").unwrap();
                if let MatValues::Float(x) = &mut v.values {
                    x[6 * 2 + 5] = 0.0;
                }
            }),
            "book.mat: variable `data`: column 2: image-2 point has third coordinate 0",
        ),
        (
            Box::new(|m| {
                let v = m.variables.iter_mut().find(|v| v.name == "label").unwrap();
                v.values = MatValues::Float(vec![0.5; 187]);
            }),
            "book.mat: variable `label`: element 0 is 0.5, not a label 0, 1, 2, …",
        ),
        (
            Box::new(|m| {
                let v = m.variables.iter_mut().find(|v| v.name == "label").unwrap();
                v.dims = vec![1, 7];
                v.values = MatValues::UInt8(vec![1; 7]);
            }),
            "book.mat: scene `book`: field `labels`: 7 labels for 187 points",
        ),
        (
            Box::new(|m| {
                for v in &mut m.variables {
                    if v.name == "data" {
                        v.dims = vec![6, 5];
                        if let MatValues::Float(x) = &mut v.values {
                            x.truncate(30);
                        }
                    }
                    if v.name == "label" {
                        v.dims = vec![1, 5];
                        v.values = MatValues::UInt8(vec![1; 5]);
                    }
                }
            }),
            "book.mat: scene `book`: field `points1`: 5 correspondences, at least 8 needed",
        ),
        (
            Box::new(|m| {
                let v = m.variables.iter_mut().find(|v| v.name == "img2").unwrap();
                v.dims = vec![240, 1280, 3];
            }),
            "book.mat: variable `img2`: size (1280, 240) differs from img1 (640, 480)",
        ),
    ];
    for (edit, expected) in cases {
        let err = edited(edit).unwrap_err();
        assert_eq!(err.to_string(), expected);
    }
}

#[test]
fn truncated_and_corrupt_files_name_the_file() {
    let path = common::adelaidermf_dir().join("boardgame.mat");
    let bytes = std::fs::read(&path).unwrap();
    let err = parse_scene(
        &bytes[..bytes.len() / 2],
        "boardgame",
        &path,
        LoadOptions::default(),
    )
    .unwrap_err();
    let msg = err.to_string();
    assert!(
        msg.starts_with(&format!("{}: not a readable MAT v5 file", path.display())),
        "{msg}"
    );

    let err = load_scene("/nonexistent/x.mat").unwrap_err();
    assert!(err.to_string().starts_with("/nonexistent/x.mat: "), "{err}");
}

/// Small files in the AdelaideRMF format written by `scipy.io.savemat`
/// (fuzz/make_seeds.py), compressed and not, RGB and grayscale.
#[test]
fn files_written_by_scipy_load() {
    let data_dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let load = |name: &str| load_scene(data_dir.join(format!("scipy_{name}.mat"))).unwrap();
    let rgb = load("rgb");
    assert_eq!(
        rgb,
        datasets::Scene {
            name: "scipy_rgb".into(),
            ..load("rgb_plain")
        }
    );
    assert_eq!(rgb.len(), 10);
    assert_eq!(rgb.labels, Some(vec![2, 1, 0, 0, 2, 1, 1, 1, 2, 1]));
    assert_eq!(rgb.points1[3], [0.08263817764264547, 0.16792787652732177]);
    assert_eq!(rgb.points2[3], [3.2359475578712504, 3.6074417009704085]);
    assert_eq!(rgb.image_size, (5, 6));
    assert_eq!(rgb.principal_point, [2.0, 2.5]);
    assert_eq!(
        rgb.images.as_ref().unwrap().0.get_pixel(2, 4).0,
        [153, 241, 4]
    );
    let gray = load("gray");
    assert_eq!(
        gray,
        datasets::Scene {
            name: "scipy_gray".into(),
            ..load("gray_plain")
        }
    );
    assert_eq!(gray.images.as_ref().unwrap().0.get_pixel(4, 5).0, [67; 3]);
}
