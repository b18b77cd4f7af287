//! The readers of untrusted input, under property-based fuzzing: `.npy` fields
//! ([`npy::parse_field`]), scene files ([`scene::parse_scene`]) and validation definitions
//! ([`builtin::check`]).
//!
//! On any input a reader either returns an error or a value that satisfies every range it
//! promises; it never panics. Valid random fields round-trip exactly. Case counts are kept
//! modest so that the file runs in a few seconds.

use std::path::Path;

use proptest::prelude::*;

use persson_check::engine::grid::{MAX_N, MIN_N};
use persson_check::engine::scene::{parse_scene, Scene};
use persson_check::io::npy::{self, Field};
use persson_check::validation::check;
use persson_check::validation::source::DEFINITIONS;
use persson_check::validation::Source;

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: 256,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

// ---------------------------------------------------------------------------------------
// .npy fields
// ---------------------------------------------------------------------------------------

/// What an accepted field must satisfy.
fn assert_sound(field: &Field) {
    assert!((MIN_N..=MAX_N).contains(&field.n), "n = {}", field.n);
    assert_eq!(field.values.len(), field.n * field.n);
    assert!(field.values.iter().all(|v| v.is_finite()));
}

/// The bytes of `values` (n x n) as written by the crate.
fn written(n: usize, values: &[f64]) -> Vec<u8> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("f.npy");
    npy::write_field(&path, n, values).unwrap();
    std::fs::read(&path).unwrap()
}

/// A version-1 `.npy` file from a header dict's text and raw data.
fn with_header(dict: &str, data: &[u8]) -> Vec<u8> {
    let mut header = dict.to_string();
    let used = 10 + header.len() + 1;
    header.push_str(&" ".repeat((64 - used % 64) % 64));
    header.push('\n');
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend((header.len() as u16).to_le_bytes());
    bytes.extend(header.as_bytes());
    bytes.extend(data);
    bytes
}

/// Finite float64 values of every kind (normal, subnormal, zero, both signs).
fn finite() -> impl Strategy<Value = f64> {
    prop::num::f64::POSITIVE
        | prop::num::f64::NEGATIVE
        | prop::num::f64::NORMAL
        | prop::num::f64::SUBNORMAL
        | prop::num::f64::ZERO
}

/// A square field of finite values, `n` in `[MIN_N, 12]`.
fn square_field() -> impl Strategy<Value = (usize, Vec<f64>)> {
    (MIN_N..=12usize).prop_flat_map(|n| (Just(n), prop::collection::vec(finite(), n * n)))
}

/// A dimension as it might appear in a header: small, zero, huge, or in hex.
fn dimension() -> impl Strategy<Value = String> {
    prop_oneof![
        (0u64..16).prop_map(|d| d.to_string()),
        Just("32769".to_string()),
        Just("4294967296".to_string()),
        Just("0x100000000".to_string()),
        Just("18446744073709551615".to_string()),
        Just("18446744073709551616".to_string()),
        Just("-4".to_string()),
    ]
}

/// The text of a header dict with a random dtype, order and shape.
fn header_dict() -> impl Strategy<Value = String> {
    let descr = prop::sample::select(vec![
        "'<f8'",
        "'>f8'",
        "'=f8'",
        "'|f8'",
        "'<f4'",
        "'<i8'",
        "'<c16'",
        "'|O'",
        "'<U3'",
        "'xyz'",
        "[('a', '<f8')]",
        "[('a', '<f8', (4294967296, 4294967296))]",
        "3",
    ]);
    let order = prop::sample::select(vec!["False", "True", "0", "'no'"]);
    let shape = prop::collection::vec(dimension(), 0..4).prop_map(|dims| match dims.len() {
        1 => format!("({},)", dims[0]),
        _ => format!("({})", dims.join(", ")),
    });
    (descr, order, shape).prop_map(|(descr, order, shape)| {
        format!("{{'descr': {descr}, 'fortran_order': {order}, 'shape': {shape}, }}")
    })
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn npy_arbitrary_bytes(bytes in prop::collection::vec(any::<u8>(), 0..600)) {
        if let Ok(field) = npy::parse_field(&bytes, MIN_N..=MAX_N) {
            assert_sound(&field);
        }
    }

    #[test]
    fn npy_arbitrary_bytes_after_a_valid_preamble(
        tail in prop::collection::vec(any::<u8>(), 0..600),
        version in 1u8..=3,
    ) {
        let mut bytes = b"\x93NUMPY".to_vec();
        bytes.extend([version, 0]);
        bytes.extend(tail);
        if let Ok(field) = npy::parse_field(&bytes, MIN_N..=MAX_N) {
            assert_sound(&field);
        }
    }

    #[test]
    fn npy_valid_fields_round_trip_exactly((n, values) in square_field()) {
        let field = npy::parse_field(&written(n, &values), MIN_N..=MAX_N).unwrap();
        prop_assert_eq!(field.n, n);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        prop_assert_eq!(bits(&field.values), bits(&values));
    }

    #[test]
    fn npy_fortran_order_is_transposed((n, values) in square_field()) {
        let data: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        let dict = format!("{{'descr': '<f8', 'fortran_order': True, 'shape': ({n}, {n}), }}");
        let field = npy::parse_field(&with_header(&dict, &data), MIN_N..=MAX_N).unwrap();
        for i in 0..n {
            for j in 0..n {
                prop_assert_eq!(field.values[i * n + j].to_bits(), values[j * n + i].to_bits());
            }
        }
    }

    #[test]
    fn npy_mutated_valid_files(
        (n, values) in square_field(),
        edits in prop::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 0..6),
        cut in any::<prop::sample::Index>(),
        truncate in any::<bool>(),
    ) {
        let mut bytes = written(n, &values);
        for (at, byte) in edits {
            let k = at.index(bytes.len());
            bytes[k] = byte;
        }
        if truncate {
            bytes.truncate(cut.index(bytes.len()));
        }
        if let Ok(field) = npy::parse_field(&bytes, MIN_N..=MAX_N) {
            assert_sound(&field);
        }
    }

    #[test]
    fn npy_random_headers(
        dict in header_dict(),
        data in prop::collection::vec(any::<u8>(), 0..1200),
    ) {
        match npy::parse_field(&with_header(&dict, &data), MIN_N..=MAX_N) {
            Ok(field) => {
                assert_sound(&field);
                let shape = format!("({}, {})", field.n, field.n);
                prop_assert!(dict.contains(&shape), "{} accepted as {}", dict, shape);
            }
            Err(message) => prop_assert!(!message.is_empty() && !message.contains('\n')),
        }
    }
}

// ---------------------------------------------------------------------------------------
// Scene files
// ---------------------------------------------------------------------------------------

const SCENE: &str = "\
[surface]
n = 32
hurst = 0.8
lambda_l = 16
lambda_s = 4
seed = 1
lambda_r = 24
amplitudes = \"random_phase\"
rms_gradient = 1.0

[solve]
zeta = 2
p0 = 0.1
solver = \"cg\"
tol = 1e-8
e_star = 1.0
";

/// The ranges every accepted scene satisfies, restated independently of the reader.
fn assert_in_range(scene: &Scene) {
    let s = &scene.surface;
    assert!((MIN_N..=MAX_N).contains(&s.n), "{scene:?}");
    assert!(s.hurst > 0.0 && s.hurst < 1.0, "{scene:?}");
    assert!(s.lambda_s >= 2.0, "{scene:?}");
    assert!(
        s.lambda_l > s.lambda_s && s.lambda_l <= s.n as f64,
        "{scene:?}"
    );
    if let Some(r) = s.lambda_r {
        assert!(r > s.lambda_l && r <= s.n as f64, "{scene:?}");
    }
    assert!(
        s.rms_gradient.is_finite() && s.rms_gradient > 0.0,
        "{scene:?}"
    );
    let v = &scene.solve;
    let zeta_max = s.lambda_l / s.lambda_s;
    if let Some(z) = v.zeta {
        assert!(z >= 1.0 && z <= zeta_max * (1.0 + 1e-12), "{scene:?}");
    }
    if let Some(p0) = v.p0 {
        assert!(p0.is_finite() && p0 > 0.0, "{scene:?}");
    }
    if let Some(a) = v.contact_area {
        assert!(a > 0.0 && a < 1.0, "{scene:?}");
    }
    assert!(v.p0.is_none() || v.contact_area.is_none(), "{scene:?}");
    if let Some(tol) = v.tol {
        assert!((1e-14..1.0).contains(&tol), "{scene:?}");
    }
    if let Some(e) = v.e_star {
        assert!(e.is_finite() && e > 0.0, "{scene:?}");
    }
    scene.validate().unwrap();
}

/// Parses `text`; an accepted scene must be in range, an error must name the file.
fn check_scene(text: &str) {
    match parse_scene(text, Path::new("fuzz.toml")) {
        Ok(scene) => assert_in_range(&scene),
        Err(e) => {
            let message = e.to_string();
            assert!(message.starts_with("fuzz.toml: "), "{message}");
            assert!(!message.contains('\n'), "{message}");
        }
    }
}

/// A TOML value for a numeric key: in range, out of range, of another type, or absurd.
fn toml_number() -> impl Strategy<Value = String> {
    prop_oneof![
        (-2.0..80.0f64).prop_map(|v| format!("{v}")),
        (-3i64..80).prop_map(|v| v.to_string()),
        prop::sample::select(vec![
            "0",
            "-0.0",
            "1",
            "2",
            "4",
            "16",
            "32",
            "0.5",
            "0.999999",
            "1e-15",
            "1e-14",
            "1e300",
            "-1e300",
            "nan",
            "inf",
            "-inf",
            "4294967296",
            "18446744073709551615",
            "\"4\"",
            "true",
            "[4]",
            "{ a = 1 }",
        ])
        .prop_map(String::from),
    ]
}

/// The valid scene with some keys' values replaced, some keys removed, and possibly an
/// unknown key added.
fn varied_scene() -> impl Strategy<Value = String> {
    let keys = [
        "n",
        "hurst",
        "lambda_l",
        "lambda_s",
        "seed",
        "lambda_r",
        "rms_gradient",
        "zeta",
        "p0",
        "tol",
        "e_star",
    ];
    (
        prop::collection::vec(prop::option::weighted(0.4, toml_number()), keys.len()),
        prop::collection::vec(prop::bool::weighted(0.1), keys.len()),
        prop::option::weighted(0.2, toml_number()),
        prop::option::weighted(0.1, Just("bogus = 1".to_string())),
    )
        .prop_map(move |(values, removed, area, extra)| {
            let mut lines = Vec::new();
            for line in SCENE.lines() {
                let key = line.split(" = ").next().unwrap_or("");
                match keys.iter().position(|k| *k == key) {
                    Some(k) if removed[k] => {}
                    Some(k) => match &values[k] {
                        Some(v) => lines.push(format!("{key} = {v}")),
                        None => lines.push(line.to_string()),
                    },
                    None => lines.push(line.to_string()),
                }
            }
            if let Some(a) = area {
                lines.push(format!("contact_area = {a}"));
            }
            if let Some(x) = extra {
                lines.insert(1, x);
            }
            lines.join("\n") + "\n"
        })
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn scene_arbitrary_text(text in any::<String>()) {
        check_scene(&text);
    }

    #[test]
    fn scene_toml_like_text(text in "[\\[\\]a-z_=\"0-9.\\- \n]{0,200}") {
        check_scene(&text);
    }

    #[test]
    fn scene_varied_values(text in varied_scene()) {
        check_scene(&text);
    }

    #[test]
    fn scene_mutated_text(
        at in any::<prop::sample::Index>(),
        len in 0usize..12,
        insert in "[\\[\\]a-z_=\"0-9.\\-# \n]{0,8}",
    ) {
        let chars: Vec<char> = SCENE.chars().collect();
        let start = at.index(chars.len());
        let end = (start + len).min(chars.len());
        let text: String = chars[..start]
            .iter()
            .chain(insert.chars().collect::<Vec<_>>().iter())
            .chain(chars[end..].iter())
            .collect();
        check_scene(&text);
    }
}

#[test]
fn the_valid_scene_is_accepted() {
    let scene = parse_scene(SCENE, Path::new("fuzz.toml")).unwrap();
    assert_in_range(&scene);
}

// ---------------------------------------------------------------------------------------
// Validation definitions
// ---------------------------------------------------------------------------------------

/// The numeric literals of `text`: (byte offset, length) of each value after ` = ` or
/// inside a list.
fn numbers(text: &str) -> Vec<(usize, usize)> {
    let bytes = text.as_bytes();
    let mut out = Vec::new();
    let mut k = 0;
    while k < bytes.len() {
        let starts = (bytes[k].is_ascii_digit() || bytes[k] == b'-')
            && k > 0
            && matches!(bytes[k - 1], b' ' | b'[');
        if starts {
            let len = bytes[k..]
                .iter()
                .take_while(|b| b.is_ascii_alphanumeric() || matches!(b, b'.' | b'-' | b'+'))
                .count();
            out.push((k, len));
            k += len;
        } else {
            k += 1;
        }
    }
    out
}

#[test]
fn shipped_definitions_pass_the_check() {
    for (name, text) in DEFINITIONS {
        let source = Source {
            path: format!("builtin:{name}").into(),
            text: text.to_string(),
        };
        check(&source).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn definition_with_one_number_replaced(
        which in any::<prop::sample::Index>(),
        at in any::<prop::sample::Index>(),
        value in prop::sample::select(vec![
            "0", "-1", "0.5", "1", "2", "3", "1e-300", "1e300", "nan", "inf", "-inf", "100000",
            "[]", "\"x\"",
        ]),
    ) {
        let (name, text) = DEFINITIONS[which.index(DEFINITIONS.len())];
        let spots = numbers(text);
        let (start, len) = spots[at.index(spots.len())];
        let text = format!("{}{value}{}", &text[..start], &text[start + len..]);
        let source = Source { path: format!("builtin:{name}").into(), text };
        if let Err(e) = check(&source) {
            let message = e.to_string();
            prop_assert!(message.starts_with(&format!("builtin:{name}: ")), "{}", message);
        }
    }
}
