//! `sctl focal` end to end: the PoseLib fixture as input, and bad input.

mod support;
use support::{number as parse, one_line_error, sctl, PoseLibFocals};

use std::io::Write;

#[test]
fn focal_reads_the_poselib_fixture_and_agrees_with_it() {
    let fixture = PoseLibFocals::read();
    let path = &fixture.path;
    let out = sctl()
        .args(["focal", "--input"])
        .arg(path)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8(out.stdout).unwrap();
    let mut lines = stdout.lines();
    assert_eq!(
        lines.next(),
        Some("row,bougnoux_f1,bougnoux_f2,iter_f1,iter_f2,iterations,iter_status")
    );
    let ours: Vec<Vec<String>> = lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();

    let reference = &fixture.rows;
    assert_eq!(ours.len(), reference.len());

    let (mut feasible, mut agree) = (0, 0);
    for (i, (row, refrow)) in ours.iter().zip(reference).enumerate() {
        assert_eq!(row.len(), 7, "row {i}: {row:?}");
        assert_eq!(row[0], i.to_string());
        // Bougnoux: the same focal lengths, the same missing ones.
        for (k, name) in [(1, "bougnoux_f1"), (2, "bougnoux_f2")] {
            match (parse(&row[k]), fixture.value(refrow, name)) {
                (Some(a), Some(b)) => {
                    assert!((a - b).abs() <= 1e-8 * b, "row {i} {name}: {a} vs {b}")
                }
                (None, None) => {}
                (a, b) => panic!("row {i} {name}: ours {a:?}, PoseLib {b:?}"),
            }
        }
        match row[6].as_str() {
            "ok" => {
                assert!(parse(&row[3]).is_some() && parse(&row[4]).is_some());
                assert!(row[5].parse::<usize>().is_ok());
            }
            "failed" => assert!(row[3].is_empty() && row[4].is_empty() && row[5].is_empty()),
            other => panic!("row {i}: status {other}"),
        }
        if fixture.text(refrow, "poselib_status") == "feasible" {
            feasible += 1;
            let want = [
                fixture.value(refrow, "iter_f1").unwrap(),
                fixture.value(refrow, "iter_f2").unwrap(),
            ];
            if let (Some(a), Some(b)) = (parse(&row[3]), parse(&row[4])) {
                if (a.abs() - want[0].abs()).abs() <= 0.01 * want[0].abs()
                    && (b.abs() - want[1].abs()).abs() <= 0.01 * want[1].abs()
                {
                    agree += 1;
                }
            }
        }
    }
    assert!(feasible >= 50);
    assert!(agree as f64 >= 0.9 * feasible as f64, "{agree}/{feasible}");
}

#[test]
fn focal_uses_the_documented_defaults() {
    // F = K^-T [t]x R K^-1 (normalised) with K = diag(1000, 1000, 1),
    // R = Rxyz(0.1, -0.2, 0.05), t = (0.4, -0.2, 1): the default prior
    // f_prior = 1000 satisfies the constraints, so the solver stops at k = 1
    // with f1 = f2 = 1000, and Bougnoux recovers 1000 as well.
    let mut file = tempfile::NamedTempFile::new().unwrap();
    writeln!(file, "F00,F01,F02,F10,F11,F12,F20,F21,F22").unwrap();
    writeln!(
        file,
        "-1.0776190350497522e-06,-1.2296600249114414e-05,-0.001037886004734488,\
         1.0924456070369674e-05,-1.320057027540976e-06,-0.00707557288071216,\
         0.002615938828093836,0.0046546286941375695,-0.999960174248637"
    )
    .unwrap();
    let out = sctl()
        .args(["focal", "--input"])
        .arg(file.path())
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8(out.stdout).unwrap();
    let row: Vec<&str> = stdout.lines().nth(1).unwrap().split(',').collect();
    assert_eq!(row[0], "0");
    for (k, cell) in row.iter().enumerate().take(5).skip(1) {
        let v: f64 = cell.parse().unwrap();
        assert!((v - 1000.0).abs() < 1e-4, "column {k}: {v}");
    }
    assert_eq!(&row[5..], ["1", "ok"]);
}

/// `sctl focal` on a file holding `content`: its one-line error, checked to
/// name the file and to contain every one of `needles`.
fn run_bad(content: &str, needles: &[&str]) -> String {
    let mut file = tempfile::NamedTempFile::new().unwrap();
    file.write_all(content.as_bytes()).unwrap();
    let output = sctl()
        .args(["focal", "--input"])
        .arg(file.path())
        .output()
        .unwrap();
    let name = file.path().display().to_string();
    let mut all = vec![name.as_str()];
    all.extend_from_slice(needles);
    one_line_error(&output, &all)
}

#[test]
fn focal_reports_a_missing_column() {
    run_bad(
        "F00,F01,F02,F10,F11,F20,F21,F22\n1,2,3,4,5,6,7,8\n",
        &["missing column F12"],
    );
}

#[test]
fn focal_reports_a_non_numeric_cell() {
    let header = "F00,F01,F02,F10,F11,F12,F20,F21,F22,f_prior\n";
    let good = "0,-5e-7,0.002,5e-7,0,-0.001,-0.002,0.001,0,1000\n";
    let bad = "0,abc,0.002,5e-7,0,-0.001,-0.002,0.001,0,1000\n";
    run_bad(
        &format!("{header}{good}{bad}"),
        &["row 1 (line 3), column F01", "'abc' is not a number"],
    );
}

#[test]
fn focal_reports_nan_and_bad_parameters() {
    let header = "F00,F01,F02,F10,F11,F12,F20,F21,F22,f_prior,max_iters\n";
    run_bad(
        &format!("{header}0,-5e-7,0.002,5e-7,NaN,-0.001,-0.002,0.001,0,1000,50\n"),
        &["row 0 (line 2), column F11: 'NaN' is not a finite number"],
    );
    run_bad(
        &format!("{header}0,-5e-7,0.002,5e-7,0,-0.001,-0.002,0.001,0,-3,50\n"),
        &["column f_prior: -3 must be > 0"],
    );
    run_bad(
        &format!("{header}0,-5e-7,0.002,5e-7,0,-0.001,-0.002,0.001,0,1000,2.5\n"),
        &["column max_iters: '2.5' is not a non-negative integer"],
    );
}
