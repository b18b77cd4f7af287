//! `.npy` height fields (`solve --heights`).

use super::*;

/// A version-1 `.npy` file with header fields `descr` and `shape` (Python literals) and
/// raw `data`.
fn npy(descr: &str, shape: &str, data: &[u8]) -> Vec<u8> {
    let mut header = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
    let used = 10 + header.len() + 1;
    header.push_str(&" ".repeat((64 - used % 64) % 64));
    header.push('\n');
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend((header.len() as u16).to_le_bytes());
    bytes.extend(header.as_bytes());
    bytes.extend(data);
    bytes
}

/// Little-endian float64 bytes.
fn f64s(values: &[f64]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// A smooth periodic 8 x 8 field.
fn field8() -> Vec<f64> {
    let tau = std::f64::consts::TAU;
    (0..64)
        .map(|k| ((k / 8) as f64 * tau / 8.0).sin() + ((k % 8) as f64 * tau / 8.0).cos())
        .collect()
}

/// A heights file holding `bytes` is rejected by `solve --heights`, naming the file and
/// `words`.
fn bad_heights(bytes: &[u8], words: &[&str]) {
    let dir = tempdir();
    std::fs::write(dir.path().join("h.npy"), bytes).unwrap();
    let words: Vec<&str> = words.iter().copied().chain(["h.npy"]).collect();
    rejected(
        dir.path(),
        &[
            "solve",
            "--heights",
            "h.npy",
            "--p0",
            "0.1",
            "--out",
            "solved",
        ],
        &words,
    );
}

#[test]
fn heights_valid_file_is_accepted() {
    let dir = tempdir();
    std::fs::write(
        dir.path().join("h.npy"),
        npy("<f8", "(8, 8)", &f64s(&field8())),
    )
    .unwrap();
    let (code, stderr) = run(
        dir.path(),
        &[
            "solve",
            "--heights",
            "h.npy",
            "--p0",
            "0.1",
            "--out",
            "solved",
        ],
    );
    assert_eq!(code, Some(0), "{stderr}");
}

#[test]
fn heights_truncated_data() {
    let bytes = npy("<f8", "(8, 8)", &f64s(&field8()));
    bad_heights(
        &bytes[..bytes.len() - 9],
        &["truncated", "64 float64 values"],
    );
}

#[test]
fn heights_truncated_header() {
    let bytes = npy("<f8", "(8, 8)", &f64s(&field8()));
    bad_heights(&bytes[..30], &["not a valid .npy", "truncated"]);
}

#[test]
fn heights_empty_file() {
    bad_heights(b"", &["not a valid .npy"]);
}

#[test]
fn heights_not_npy() {
    bad_heights(b"1.0 2.0\n3.0 4.0\n", &["not a valid .npy"]);
}

#[test]
fn heights_trailing_bytes() {
    let mut data = f64s(&field8());
    data.extend(f64s(&[1.0, 2.0]));
    bad_heights(&npy("<f8", "(8, 8)", &data), &["16 bytes follow", "8 x 8"]);
}

#[test]
fn heights_float32() {
    let data: Vec<u8> = field8()
        .iter()
        .flat_map(|&v| (v as f32).to_le_bytes())
        .collect();
    bad_heights(&npy("<f4", "(8, 8)", &data), &["dtype", "<f4", "float64"]);
}

#[test]
fn heights_int64() {
    let data: Vec<u8> = (0..64i64).flat_map(|v| v.to_le_bytes()).collect();
    bad_heights(&npy("<i8", "(8, 8)", &data), &["dtype", "<i8", "float64"]);
}

#[test]
fn heights_complex128() {
    bad_heights(
        &npy("<c16", "(8, 8)", &[0; 1024]),
        &["dtype", "<c16", "float64"],
    );
}

#[test]
fn heights_one_dimensional() {
    bad_heights(
        &npy("<f8", "(64,)", &f64s(&field8())),
        &["1 dimensions", "expected 2 (N, N)"],
    );
}

#[test]
fn heights_three_dimensional() {
    bad_heights(
        &npy("<f8", "(4, 4, 4)", &f64s(&field8())),
        &["3 dimensions", "expected 2 (N, N)"],
    );
}

#[test]
fn heights_scalar() {
    bad_heights(
        &npy("<f8", "()", &f64s(&[1.0])),
        &["0 dimensions", "expected 2 (N, N)"],
    );
}

#[test]
fn heights_non_square() {
    bad_heights(
        &npy("<f8", "(8, 4)", &f64s(&field8()[..32])),
        &["not square", "[8, 4]", "(N, N)"],
    );
}

#[test]
fn heights_empty_array() {
    bad_heights(&npy("<f8", "(0, 0)", &[]), &["empty"]);
}

#[test]
fn heights_grid_too_small() {
    bad_heights(
        &npy("<f8", "(2, 2)", &f64s(&[0.0, 1.0, 2.0, 3.0])),
        &["N = 2", "[4, 32768]"],
    );
}

#[test]
fn heights_shape_overflowing_u64() {
    // The dimensions' product overflows: rejected, not a panic.
    bad_heights(
        &npy("<f8", "(0x100000000, 0x100000000, 2)", &[0; 64]),
        &["3 dimensions"],
    );
}

#[test]
fn heights_shape_larger_than_data() {
    bad_heights(
        &npy("<f8", "(40000, 40000)", &f64s(&field8())),
        &["N = 40000", "[4, 32768]"],
    );
    // Within range but far more than the file holds: read as far as the data goes.
    bad_heights(
        &npy("<f8", "(20000, 20000)", &f64s(&field8())),
        &["truncated", "400000000 float64 values"],
    );
    bad_heights(
        &npy("<f8", "(16, 16)", &f64s(&field8())),
        &["truncated", "256 float64 values"],
    );
}

#[test]
fn heights_nan() {
    let mut values = field8();
    values[10] = f64::NAN;
    bad_heights(
        &npy("<f8", "(8, 8)", &f64s(&values)),
        &["row 1, column 2", "NaN", "finite"],
    );
}

#[test]
fn heights_infinite() {
    let mut values = field8();
    values[63] = f64::INFINITY;
    bad_heights(
        &npy("<f8", "(8, 8)", &f64s(&values)),
        &["row 7, column 7", "inf", "finite"],
    );
    values[63] = f64::NEG_INFINITY;
    bad_heights(
        &npy("<f8", "(8, 8)", &f64s(&values)),
        &["row 7, column 7", "-inf", "finite"],
    );
}

#[test]
fn heights_flat_with_a_target_contact_area() {
    // A flat surface is in full contact at any load: no contact area in (0, 1) is reachable.
    let dir = tempdir();
    std::fs::write(
        dir.path().join("h.npy"),
        npy("<f8", "(8, 8)", &f64s(&[0.5; 64])),
    )
    .unwrap();
    rejected(
        dir.path(),
        &[
            "solve",
            "--heights",
            "h.npy",
            "--contact-area",
            "0.3",
            "--out",
            "solved",
        ],
        &["contact_area = 0.3", "flat", "--p0"],
    );
}

#[test]
fn heights_file_missing() {
    let dir = tempdir();
    rejected(
        dir.path(),
        &[
            "solve",
            "--heights",
            "h.npy",
            "--p0",
            "0.1",
            "--out",
            "solved",
        ],
        &["h.npy", "No such file"],
    );
}

#[test]
fn heights_file_lambda_l_out_of_range() {
    for value in ["64", "0", "-1"] {
        let dir = tempdir();
        std::fs::write(
            dir.path().join("h.npy"),
            npy("<f8", "(8, 8)", &f64s(&field8())),
        )
        .unwrap();
        let args = [
            "solve",
            "--heights",
            "h.npy",
            "--file-lambda-l",
            value,
            "--p0",
            "0.1",
            "--out",
            "solved",
        ];
        let stderr = rejected(dir.path(), &args, &["--file-lambda-l"]);
        assert!(
            stderr.contains("L = 8") || stderr.contains("> 0"),
            "{stderr}"
        );
    }
}
