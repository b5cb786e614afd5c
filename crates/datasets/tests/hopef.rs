//! HOPE-F layout: the numpy-written fixtures load with the values numpy
//! reads; splits select the right folders; broken files give errors naming
//! the file and the problem.

mod common;

use datasets::hopef::{
    load_scene, load_scene_with, HopeF, LoadOptions, Selection, Split, CAMERA_FILE,
    DEFAULT_IMAGE_SIZE, FEATURES_FILE,
};
use datasets::DatasetError;
use geometry::sampson_distance;
use std::path::Path;

/// Per scene, from numpy: N, label counts [outliers, object 1, …], K[0,0],
/// (K[0,2], K[1,2]), points1[0] (x, y), points2[-1] (x, y), F[-1][2, 1].
#[allow(clippy::type_complexity)]
const TABLE: [(
    &str,
    usize,
    &[usize],
    f64,
    [f64; 2],
    [f64; 2],
    [f64; 2],
    f64,
); 12] = [
    (
        "1/0000",
        128,
        &[32, 96],
        615.7131824922797,
        [518.7987377015498, 390.1236053929297],
        [819.1138967586767, 346.9374121062883],
        [399.89029525257024, 418.3489929275841],
        0.009976114185891808,
    ),
    (
        "1/0001",
        120,
        &[52, 68],
        517.107869835449,
        [511.5212873850145, 385.05844968953664],
        [360.5319152199386, 485.63700851054665],
        [332.38496189089267, 358.5578298972035],
        -0.019078121189962584,
    ),
    (
        "1/0002",
        120,
        &[55, 65],
        963.5290538512642,
        [514.6232784256895, 383.04509816016935],
        [780.8589897750194, 670.353234124812],
        [570.1591550831378, 299.15643367101785],
        0.007079431871780022,
    ),
    (
        "2/0000",
        196,
        &[43, 46, 107],
        571.9210394896908,
        [516.8557775238901, 393.01501678684104],
        [543.3340484287028, 419.1870072713069],
        [154.5598625972998, 668.5685253810525],
        0.002841384345506915,
    ),
    (
        "2/0001",
        216,
        &[21, 119, 76],
        983.6376457777931,
        [519.6815229524125, 389.4403586164309],
        [461.8943802273296, 111.51375999247867],
        [316.44055942334944, 490.0935317208012],
        -0.014073718024133638,
    ),
    (
        "2/0002",
        168,
        &[36, 89, 43],
        779.1139498432294,
        [511.4886232747334, 389.1773797123849],
        [369.2641768374287, 299.773735969622],
        [713.3603956669084, 453.717673451424],
        -0.014519964497053886,
    ),
    (
        "3/0000",
        241,
        &[44, 45, 42, 110],
        620.2312154336162,
        [522.7985588235479, 392.78923859447224],
        [879.4998879892053, 145.95263991255823],
        [667.7385162316466, 440.3054982788203],
        0.004042513168834639,
    ),
    (
        "3/0001",
        314,
        &[51, 83, 116, 64],
        1308.9649447321285,
        [518.2470602979989, 380.06273226136494],
        [880.9686066194762, 539.4240881342487],
        [739.3310354803587, 673.7624137911713],
        -0.013225078773285031,
    ),
    (
        "3/0002",
        291,
        &[59, 80, 99, 53],
        894.503051289597,
        [512.5602577858741, 384.0386746314869],
        [368.04990324394106, 544.2976555027587],
        [706.1087237491324, 235.936668748606],
        -0.008215623406833,
    ),
    (
        "4/0000",
        317,
        &[58, 68, 48, 92, 51],
        1323.2733068620937,
        [509.6867278497283, 382.4146896929064],
        [801.4299436427945, 550.4157502004134],
        [368.26201914035755, 545.8586036551487],
        0.008902014021666078,
    ),
    (
        "4/0001",
        379,
        &[57, 79, 64, 94, 85],
        812.6696215707152,
        [507.97194533161, 383.95813419662164],
        [517.2560800196813, 281.72635612812485],
        [345.4901988318024, 142.06427079968716],
        -0.004629570214679671,
    ),
    (
        "4/0002",
        370,
        &[33, 82, 107, 97, 51],
        768.3779570841438,
        [513.0696991913943, 392.63505640094803],
        [450.4763156160692, 327.7523024563519],
        [275.45877476271994, 395.63006653792047],
        -0.008411322095775406,
    ),
];

#[test]
fn good_fixtures_load_with_the_values_numpy_reads() {
    let data = HopeF::open(common::hopef_fixture("good")).unwrap();
    assert_eq!(data.categories().unwrap(), vec![1, 2, 3, 4]);
    let refs = data.select(&[], &Selection::All).unwrap();
    assert_eq!(refs.len(), 12);
    for (r, &(name, n, counts, focal, pp, first1, last2, f_last_21)) in
        refs.iter().zip(TABLE.iter())
    {
        assert_eq!(r.name(), name);
        let scene = data.load(r, LoadOptions::default()).unwrap();
        assert_eq!(scene.name, name);
        assert_eq!(scene.len(), n, "{name}");
        let labels = scene.labels.as_ref().unwrap();
        for (j, &count) in counts.iter().enumerate() {
            assert_eq!(
                labels.iter().filter(|&&l| l == j as i32).count(),
                count,
                "{name} label {j}"
            );
        }
        assert_eq!(scene.num_motions(), r.category as usize);
        assert_eq!(scene.gt_fundamentals.len(), r.category as usize);
        assert_eq!(scene.true_focal, Some(focal), "{name}");
        assert_eq!(scene.principal_point, pp, "{name}");
        assert_eq!(scene.points1[0], first1, "{name}");
        assert_eq!(scene.points2[n - 1], last2, "{name}");
        assert_eq!(
            scene.gt_fundamentals.last().unwrap()[(2, 1)],
            f_last_21,
            "{name}: F is read row-major"
        );
        assert_eq!(scene.image_size, DEFAULT_IMAGE_SIZE);
        assert!(scene.images.is_none());
    }
}

#[test]
fn ground_truth_f_fits_the_inliers_and_not_the_outliers() {
    // The fixtures add Gaussian noise sigma = 0.5 px to inliers: the true F
    // must explain them (x2' F x1 = 0 with F[j-1] for label j).
    let data = HopeF::open(common::hopef_fixture("good")).unwrap();
    for r in data.select(&[], &Selection::All).unwrap() {
        let scene = data.load(&r, LoadOptions::default()).unwrap();
        let labels = scene.labels.as_ref().unwrap();
        let (mut inlier, mut within, mut outlier_far, mut outliers) = (0, 0, 0, 0);
        for ((&p1, &p2), &label) in scene.points1.iter().zip(&scene.points2).zip(labels) {
            if label > 0 {
                let d = sampson_distance(&scene.gt_fundamentals[label as usize - 1], p1, p2);
                inlier += 1;
                within += usize::from(d < 2.5);
            } else {
                outliers += 1;
                let nearest = scene
                    .gt_fundamentals
                    .iter()
                    .map(|f| sampson_distance(f, p1, p2))
                    .fold(f64::INFINITY, f64::min);
                outlier_far += usize::from(nearest > 2.5);
            }
        }
        assert_eq!(
            within, inlier,
            "{}: every inlier within 5 sigma",
            scene.name
        );
        assert!(
            outlier_far * 10 >= outliers * 8,
            "{}: {outlier_far}/{outliers} outliers far",
            scene.name
        );
    }
}

#[test]
fn selection_by_category_and_index_range() {
    let data = HopeF::open(common::hopef_fixture("good")).unwrap();
    let names = |cats: &[u32], sel: Selection| -> Vec<String> {
        data.select(cats, &sel)
            .unwrap()
            .iter()
            .map(|r| r.name())
            .collect()
    };
    assert_eq!(
        names(&[2, 4], Selection::Indices(1..=2)),
        ["2/0001", "2/0002", "4/0001", "4/0002"]
    );
    assert_eq!(names(&[3], Selection::All), ["3/0000", "3/0001", "3/0002"]);
    assert!(names(&[], Selection::Split(Split::Test)).is_empty());
    assert_eq!(names(&[1], Selection::Split(Split::Train)).len(), 3);
    assert!(names(&[7], Selection::All).is_empty());
    assert_eq!(data.find("2/0001").unwrap().name(), "2/0001");
    assert_eq!(data.find("2/1").unwrap().name(), "2/0001");
    for bad in ["2/0007", "9/0001", "x", "2-0001"] {
        assert!(
            matches!(data.find(bad), Err(DatasetError::UnknownScene { .. })),
            "{bad}"
        );
    }
}

#[test]
fn splits_select_the_right_folders() {
    let root = tempfile::tempdir().unwrap();
    let indices = [0u32, 1, 799, 800, 899, 900, 950, 999];
    for k in [1u32, 3] {
        for i in indices {
            std::fs::create_dir_all(root.path().join(k.to_string()).join(format!("{i:04}")))
                .unwrap();
        }
    }
    // Noise that must be ignored: non-numeric folders and a file with a numeric name.
    std::fs::create_dir_all(root.path().join("1/notes")).unwrap();
    std::fs::create_dir_all(root.path().join("extra")).unwrap();
    std::fs::write(root.path().join("3/0901"), b"not a folder").unwrap();

    let data = HopeF::open(root.path()).unwrap();
    assert_eq!(data.categories().unwrap(), vec![1, 3]);
    let pick = |split| -> Vec<(u32, u32)> {
        data.select(&[], &Selection::Split(split))
            .unwrap()
            .iter()
            .map(|r| (r.category, r.index))
            .collect()
    };
    assert_eq!(
        pick(Split::Train),
        [(1, 0), (1, 1), (1, 799), (3, 0), (3, 1), (3, 799)]
    );
    assert_eq!(pick(Split::Val), [(1, 800), (1, 899), (3, 800), (3, 899)]);
    assert_eq!(
        pick(Split::Test),
        [(1, 900), (1, 950), (1, 999), (3, 900), (3, 950), (3, 999)]
    );
    assert_eq!(Split::Train.indices(), 0..=799);
    assert_eq!(Split::Val.indices(), 800..=899);
    assert_eq!("test".parse::<Split>(), Ok(Split::Test));
    assert_eq!("Validation".parse::<Split>(), Ok(Split::Val));
    assert!("dev".parse::<Split>().is_err());
}

#[test]
fn every_bad_fixture_names_the_file_and_the_problem() {
    let cases = [
        ("missing_labels", "missing array `labels`"),
        (
            "length_mismatch",
            "array `labels`: length 178 does not match points1 (181 points)",
        ),
        (
            "nan_points",
            "array `points1`: row 5 has a non-finite coordinate",
        ),
        ("truncated", "not a readable .npz archive: zip archive:"),
    ];
    for (case, problem) in cases {
        let dir = common::hopef_fixture("bad").join(case).join("1/0000");
        let err = load_scene(&dir).unwrap_err();
        let msg = err.to_string();
        let file = dir.join(FEATURES_FILE);
        assert!(
            msg.starts_with(&format!("{}: {problem}", file.display())),
            "{case}: {msg}"
        );
    }
}

/// Copies a good fixture scene into a temporary folder `<tmp>/2/0001`.
fn copy_fixture() -> (tempfile::TempDir, std::path::PathBuf) {
    let src = common::hopef_fixture("good").join("2/0001");
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("2/0001");
    std::fs::create_dir_all(&dir).unwrap();
    for f in [FEATURES_FILE, CAMERA_FILE] {
        std::fs::copy(src.join(f), dir.join(f)).unwrap();
    }
    (tmp, dir)
}

#[test]
fn renders_give_images_and_image_size() {
    let (_tmp, dir) = copy_fixture();
    let img0 = image::RgbImage::from_fn(800, 600, |x, y| image::Rgb([x as u8, y as u8, 7]));
    let img1 = image::RgbImage::from_fn(800, 600, |x, y| image::Rgb([y as u8, x as u8, 9]));
    img0.save(dir.join("render0.png")).unwrap();
    img1.save(dir.join("render1.png")).unwrap();
    let scene = load_scene(&dir).unwrap();
    assert_eq!(scene.name, "2/0001");
    assert_eq!(scene.image_size, (800, 600));
    assert_eq!(scene.images, Some((img0, img1)));
    let light = load_scene_with(&dir, LoadOptions { images: false }).unwrap();
    assert_eq!(light.image_size, (800, 600));
    assert!(light.images.is_none());

    // A corrupt render names the PNG.
    std::fs::write(dir.join("render1.png"), b"not a png").unwrap();
    let msg = load_scene(&dir).unwrap_err().to_string();
    assert!(
        msg.starts_with(&format!("{}: image:", dir.join("render1.png").display())),
        "{msg}"
    );
}

#[test]
fn camera_problems_name_the_camera_file() {
    let (_tmp, dir) = copy_fixture();
    std::fs::write(dir.join(CAMERA_FILE), b"PK\x03\x04 broken").unwrap();
    let msg = load_scene(&dir).unwrap_err().to_string();
    assert!(
        msg.starts_with(&format!(
            "{}: not a readable .npz archive",
            dir.join(CAMERA_FILE).display()
        )),
        "{msg}"
    );
    std::fs::remove_file(dir.join(CAMERA_FILE)).unwrap();
    let msg = load_scene(&dir).unwrap_err().to_string();
    assert!(
        msg.starts_with(&dir.join(CAMERA_FILE).display().to_string()),
        "{msg}"
    );
}

#[test]
fn missing_dataset_directory_says_where_to_get_it() {
    let msg = HopeF::open(Path::new("/nonexistent/hopef"))
        .unwrap_err()
        .to_string();
    assert!(
        msg.starts_with("HOPE-F not found at /nonexistent/hopef"),
        "{msg}"
    );
    assert!(msg.contains("datasets/README.md"), "{msg}");
}
