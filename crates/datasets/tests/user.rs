//! User match files: CSV and `matches.txt`, image size from the caller or a
//! sidecar TOML, errors naming the file and line.

use datasets::user::{load_csv, load_matches_txt, read_sidecar, sidecar_path};
use datasets::DatasetError;
use std::path::{Path, PathBuf};

fn rows(n: usize) -> Vec<[f64; 4]> {
    (0..n)
        .map(|i| [i as f64 + 0.5, 2.0 * i as f64, 100.0 - i as f64, 3.25])
        .collect()
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn csv_columns_in_any_order_with_labels() {
    let dir = tempfile::tempdir().unwrap();
    let mut text = String::from("label, Y2, x2, y1, X1\n");
    for (i, r) in rows(10).iter().enumerate() {
        text += &format!("{}, {}, {}, {}, {}\n", i % 3, r[3], r[2], r[1], r[0]);
    }
    let path = write(dir.path(), "pair.csv", &text);
    let scene = load_csv(&path, Some((320, 240))).unwrap();
    assert_eq!(scene.name, "pair");
    assert_eq!(scene.len(), 10);
    for (i, r) in rows(10).iter().enumerate() {
        assert_eq!(scene.points1[i], [r[0], r[1]]);
        assert_eq!(scene.points2[i], [r[2], r[3]]);
    }
    assert_eq!(scene.labels, Some((0..10).map(|i| i % 3).collect()));
    assert_eq!(scene.num_motions(), 2);
    assert_eq!(scene.image_size, (320, 240));
    assert_eq!(scene.principal_point, [159.5, 119.5]);
    assert_eq!(scene.true_focal, None);
}

#[test]
fn sidecar_supplies_size_name_focal_and_principal_point() {
    let dir = tempfile::tempdir().unwrap();
    let mut text = String::from("x1,y1,x2,y2\n");
    for r in rows(9) {
        text += &format!("{},{},{},{}\n", r[0], r[1], r[2], r[3]);
    }
    let path = write(dir.path(), "desk.csv", &text);
    write(
        dir.path(),
        "desk.toml",
        "width = 640\nheight = 480\nname = \"my desk\"\nfocal = 700.0\nprincipal_point = [320.0, 241.0]\n",
    );
    assert_eq!(sidecar_path(&path), dir.path().join("desk.toml"));
    let scene = load_csv(&path, None).unwrap();
    assert_eq!(scene.name, "my desk");
    assert_eq!(scene.image_size, (640, 480));
    assert_eq!(scene.true_focal, Some(700.0));
    assert_eq!(scene.principal_point, [320.0, 241.0]);
    assert_eq!(scene.labels, None);
    // The caller's image size wins over the sidecar's.
    assert_eq!(
        load_csv(&path, Some((800, 600))).unwrap().image_size,
        (800, 600)
    );

    write(
        dir.path(),
        "desk.toml",
        "width = 640\nheight = 480\ncolour = 3\n",
    );
    let err = read_sidecar(&dir.path().join("desk.toml")).unwrap_err();
    assert!(
        err.to_string().contains("desk.toml") && err.to_string().contains("colour"),
        "{err}"
    );
}

#[test]
fn missing_image_size_names_the_sidecar_to_write() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "a.csv", "x1,y1,x2,y2\n1,2,3,4\n");
    let msg = load_csv(&path, None).unwrap_err().to_string();
    assert!(
        msg.contains(&dir.path().join("a.toml").display().to_string()),
        "{msg}"
    );
}

#[test]
fn csv_errors_name_file_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let good_rows: String = rows(8)
        .iter()
        .map(|r| format!("{},{},{},{}\n", r[0], r[1], r[2], r[3]))
        .collect();
    let cases = [
        ("x1,y1,x2\n1,2,3\n", "missing column `y2`".to_string()),
        (
            &*format!("x1,y1,x2,y2\n{good_rows}1,2,three,4\n"),
            "line 10: column `x2`: \"three\" is not a number".to_string(),
        ),
        (
            &*format!("x1,y1,x2,y2\n{good_rows}1,2,3\n"),
            "line 10".to_string(),
        ),
        (
            "x1,y1,x2,y2,label\n1,2,3,4,1\n1,2,3,4,1.5\n",
            "line 3: column `label`: \"1.5\" is not an integer".to_string(),
        ),
        (
            "x1,y1,x2,y2\n1,2,3,4\n",
            "field `points1`: 1 correspondences, at least 8 needed".to_string(),
        ),
        (
            &*format!("x1,y1,x2,y2\n{good_rows}1,NaN,3,4\n"),
            "field `points1` at index 8: non-finite coordinate".to_string(),
        ),
    ];
    for (text, expected) in cases {
        let path = write(dir.path(), "bad.csv", text);
        let msg = load_csv(&path, Some((10, 10))).unwrap_err().to_string();
        assert!(msg.starts_with(&path.display().to_string()), "{msg}");
        assert!(msg.contains(&expected), "expected {expected:?} in {msg}");
    }
    // A negative label is refused where it is read: -1 and -2 are not
    // spellings of "unknown".
    for bad in ["-1", "-2", ""] {
        let labels: String = (0..8)
            .map(|i| format!("1,2,3,4,{}\n", if i == 6 { bad } else { "1" }))
            .collect();
        let path = write(
            dir.path(),
            "neg.csv",
            &format!("x1,y1,x2,y2,label\n{labels}"),
        );
        let err = load_csv(&path, Some((10, 10))).unwrap_err();
        assert!(
            matches!(&err, DatasetError::Parse { line: Some(8), .. }),
            "{err}"
        );
        let msg = err.to_string();
        assert!(
            msg.contains("column `label`") && msg.contains("or `unknown`"),
            "{msg}"
        );
    }
}

#[test]
fn csv_unknown_columns_are_errors_naming_them() {
    let dir = tempfile::tempdir().unwrap();
    let body: String = rows(8)
        .iter()
        .map(|r| format!("{},{},{},{},1\n", r[0], r[1], r[2], r[3]))
        .collect();
    let cases = [
        ("x1,y1,x2,y2,lable", "unknown column `lable`"),
        ("x1,y1,x2,y2,score", "unknown column `score`"),
        ("x1,y1,x2,y2,X1", "column `X1` appears twice"),
    ];
    for (header, expected) in cases {
        let path = write(dir.path(), "typo.csv", &format!("{header}\n{body}"));
        let msg = load_csv(&path, Some((10, 10))).unwrap_err().to_string();
        assert_eq!(
            msg,
            format!(
                "{}: line 1: {expected}: the columns are x1, y1, x2, y2 and optionally label",
                path.display()
            )
        );
    }
}

#[test]
fn unknown_labels_are_read_as_unknown_label() {
    let dir = tempfile::tempdir().unwrap();
    let words = [
        "1", "unknown", "0", "2", "Unknown", "1", "UNKNOWN", "2", "0",
    ];
    let mut csv = String::from("x1,y1,x2,y2,label\n");
    let mut txt = String::new();
    for (r, word) in rows(9).iter().zip(words) {
        csv += &format!("{},{},{},{},{word}\n", r[0], r[1], r[2], r[3]);
        txt += &format!("{} {} {} {} {word}\n", r[0], r[1], r[2], r[3]);
    }
    let u = datasets::UNKNOWN_LABEL;
    let expected = vec![1, u, 0, 2, u, 1, u, 2, 0];
    for scene in [
        load_csv(write(dir.path(), "u.csv", &csv), Some((10, 10))).unwrap(),
        load_matches_txt(write(dir.path(), "u.txt", &txt), Some((10, 10))).unwrap(),
    ] {
        assert_eq!(scene.labels.as_ref(), Some(&expected));
        assert_eq!(scene.num_unknown(), 3);
        assert_eq!(scene.num_outliers(), 2);
        assert_eq!(scene.num_motions(), 2);
    }
}

/// One row of the table in datasets/real-sift/README.md: scene, matches,
/// known, unknown, per-label counts.
type ReadmeRow = (String, usize, usize, usize, Vec<(i32, usize)>);

fn real_sift_readme(dir: &Path) -> Vec<ReadmeRow> {
    let text = std::fs::read_to_string(dir.join("README.md")).unwrap();
    // The first table: from its `| scene |` header to the first blank line.
    text.lines()
        .skip_while(|l| !l.starts_with("| scene |"))
        .take_while(|l| !l.is_empty())
        .filter(|l| l.starts_with("| ") && !l.starts_with("| scene") && !l.starts_with("| total"))
        .map(|l| {
            let cells: Vec<&str> = l.trim_matches('|').split('|').map(str::trim).collect();
            let per_label = cells[4]
                .split(", ")
                .map(|kv| {
                    let (k, v) = kv.split_once(": ").unwrap();
                    (k.parse().unwrap(), v.parse().unwrap())
                })
                .collect();
            let n = |i: usize| cells[i].parse::<usize>().unwrap();
            (cells[0].to_string(), n(1), n(2), n(3), per_label)
        })
        .collect()
}

/// The committed SIFT benchmark loads, and the loader counts what the
/// script that wrote it printed into its README: matches, known, unknown
/// and every label.
#[test]
fn real_sift_files_load_with_the_readme_counts() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../datasets/real-sift");
    let table = real_sift_readme(&dir);
    assert_eq!(table.len(), 19);
    for (name, matches, known, unknown, per_label) in table {
        let scene = load_csv(dir.join(format!("{name}.csv")), None).unwrap();
        assert_eq!(scene.name, name);
        assert_eq!(scene.image_size, (640, 480));
        assert_eq!(
            (scene.len(), scene.num_unknown()),
            (matches, unknown),
            "{name}"
        );
        let labels = scene.labels.unwrap();
        let counted: Vec<(i32, usize)> = per_label
            .iter()
            .map(|&(k, _)| (k, labels.iter().filter(|&&l| l == k).count()))
            .collect();
        assert_eq!(counted, per_label, "{name}");
        assert_eq!(
            per_label.iter().map(|c| c.1).sum::<usize>(),
            known,
            "{name}"
        );
    }
}

#[test]
fn matches_txt_with_labels_comments_and_blank_lines() {
    let dir = tempfile::tempdir().unwrap();
    let mut text = String::from("# x1 y1 x2 y2 label\n\n");
    for (i, r) in rows(8).iter().enumerate() {
        text += &format!("  {}\t{} {}   {} {}\n", r[0], r[1], r[2], r[3], i % 2);
    }
    let path = write(dir.path(), "matches.txt", &text);
    let scene = load_matches_txt(&path, Some((200, 100))).unwrap();
    assert_eq!(scene.name, "matches");
    assert_eq!(scene.len(), 8);
    assert_eq!(scene.points2[3], [97.0, 3.25]);
    assert_eq!(scene.labels, Some(vec![0, 1, 0, 1, 0, 1, 0, 1]));
    assert_eq!(scene.num_outliers(), 4);

    let unlabelled: String = rows(8)
        .iter()
        .map(|r| format!("{} {} {} {}\n", r[0], r[1], r[2], r[3]))
        .collect();
    let path = write(dir.path(), "plain.txt", &unlabelled);
    assert_eq!(
        load_matches_txt(&path, Some((200, 100))).unwrap().labels,
        None
    );
}

#[test]
fn matches_txt_errors_name_file_and_line() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            "1 2 3 4 1\n1 2 3 4\n",
            "line 2: 4 columns, earlier lines have 5",
        ),
        (
            "1 2 3\n",
            "line 1: 3 columns, expected `x1 y1 x2 y2 [label]`",
        ),
        (
            "# c\n1 2 x 4 0\n",
            "line 2: column 3: \"x\" is not a number",
        ),
        (
            "1 2 3 4 one\n",
            "line 1: column 5: \"one\" is not an integer label: labels are 0 (outlier), 1, 2, … (motion) or `unknown`",
        ),
        (
            "1 2 3 4 -1\n",
            "line 1: column 5: -1 is negative: labels are 0 (outlier), 1, 2, … (motion) or `unknown`",
        ),
    ];
    for (text, expected) in cases {
        let path = write(dir.path(), "m.txt", text);
        let msg = load_matches_txt(&path, Some((10, 10)))
            .unwrap_err()
            .to_string();
        assert_eq!(msg, format!("{}: {expected}", path.display()));
    }
    let msg = load_matches_txt("/nonexistent/m.txt", Some((1, 1)))
        .unwrap_err()
        .to_string();
    assert!(msg.starts_with("/nonexistent/m.txt: "), "{msg}");
}
