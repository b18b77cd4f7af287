"""Bad input raises ValueError or TypeError with the command line's message."""

import numpy as np
import pytest

import persson_check
from conftest import cli_error, save


def _cli_solve_error(cli, tmp_path, h, *flags):
    path = save(tmp_path / "h.npy", h)
    result = cli("solve", "--heights", path, *flags, "--out", tmp_path / "out", check=False)
    message = cli_error(result)
    prefix = f"{path}: "
    return message[len(prefix):] if message.startswith(prefix) else message


def test_nan_height(cli, tmp_path, rough):
    h = rough.copy()
    h[5, 9] = np.nan
    with pytest.raises(ValueError) as e:
        persson_check.solve(h, p0=0.1)
    assert str(e.value) == "entry at row 5, column 9 is NaN (fields must be finite)"
    assert str(e.value) == _cli_solve_error(cli, tmp_path, h, "--p0", 0.1)


def test_infinite_height_in_theory_and_sweep(rough):
    h = rough.copy()
    h[0, 1] = -np.inf
    for call in (lambda: persson_check.theory(h, 0.1), lambda: persson_check.sweep(h, p0=0.1)):
        with pytest.raises(ValueError, match="row 0, column 1 is -inf"):
            call()


def test_non_square_array(cli, tmp_path):
    h = np.zeros((32, 48))
    with pytest.raises(ValueError) as e:
        persson_check.solve(h, p0=0.1)
    assert str(e.value) == "array is not square (shape [32, 48]), expected (N, N)"
    assert str(e.value) == _cli_solve_error(cli, tmp_path, h, "--p0", 0.1)


def test_wrong_rank():
    with pytest.raises(ValueError, match=r"array has 1 dimensions \(shape \[64\]\)"):
        persson_check.solve(np.zeros(64), p0=0.1)


@pytest.mark.parametrize(
    "kwargs, flags",
    [
        ({"p0": -0.1}, ["--p0", -0.1]),
        ({"p0": 0.0}, ["--p0", 0.0]),
        ({"contact_area": 1.5}, ["--contact-area", 1.5]),
        ({"p0": 0.1, "tol": 1e-20}, ["--p0", 0.1, "--tol", 1e-20]),
        ({"p0": 0.1, "zeta": 0.5}, ["--p0", 0.1, "--zeta", 0.5]),
        ({"p0": 0.1, "zeta": 100.0}, ["--p0", 0.1, "--zeta", 100.0]),
        ({"p0": 0.1, "lambda_l": 1000.0}, ["--p0", 0.1, "--file-lambda-l", 1000.0]),
    ],
)
def test_bad_load_and_settings(cli, tmp_path, rough, kwargs, flags):
    with pytest.raises(ValueError) as e:
        persson_check.solve(rough, **kwargs)
    theirs = _cli_solve_error(cli, tmp_path, rough, *flags)
    # The command line names the flag (--p0, --file-lambda-l), Python the keyword.
    for flag, keyword in (("--file-lambda-l", "lambda_l"), ("--contact-area", "contact_area"),
                          ("--p0", "p0"), ("--tol", "tol"), ("--zeta", "zeta")):
        theirs = theirs.replace(flag, keyword)
    assert str(e.value) == theirs


def test_load_must_be_one_of_two(rough):
    with pytest.raises(ValueError, match="invalid load = missing"):
        persson_check.solve(rough)
    with pytest.raises(ValueError, match="invalid load = both p0 and contact_area"):
        persson_check.solve(rough, p0=0.1, contact_area=0.2)


@pytest.mark.parametrize(
    "args, flag, keyword",
    [
        ((64, 1.5, 32.0, 4.0, 1), "--hurst", "hurst"),
        ((64, 0.8, 128.0, 4.0, 1), "--lambda-l", "lambda_l"),
        ((64, 0.8, 32.0, 1.0, 1), "--lambda-s", "lambda_s"),
        ((3, 0.8, 2.0, 2.0, 1), "--n", "n"),
    ],
)
def test_bad_surface_parameters(cli, tmp_path, args, flag, keyword):
    with pytest.raises(ValueError) as e:
        persson_check.surface(*args)
    n, hurst, lambda_l, lambda_s, seed = args
    result = cli("surface", "--n", n, "--hurst", hurst, "--lambda-l", lambda_l,
                 "--lambda-s", lambda_s, "--seed", seed, "--out", tmp_path / "h.npy", check=False)
    assert str(e.value) == cli_error(result).replace(flag, keyword)


def test_type_errors(rough):
    with pytest.raises(TypeError, match="expected real numbers"):
        persson_check.solve(rough.astype(complex), p0=0.1)
    with pytest.raises(TypeError):
        persson_check.solve(rough, p0="a lot")
    with pytest.raises(TypeError):
        persson_check.surface(64, 0.8, 32.0, 4.0, "seed")
    with pytest.raises(ValueError, match="invalid seed = -1"):
        persson_check.surface(64, 0.8, 32.0, 4.0, -1)
    with pytest.raises(ValueError, match='invalid solver = "fem"'):
        persson_check.solve(rough, p0=0.1, solver="fem")


def test_unconverged_solve_is_an_error_not_a_result(rough):
    with pytest.raises(persson_check.SolveError, match="did not converge"):
        persson_check.solve(rough, p0=0.1, solver="gfmd", max_iter=3)
    assert issubclass(persson_check.SolveError, RuntimeError)


def test_unknown_validation(tmp_path):
    with pytest.raises(ValueError):
        persson_check.validate("no_such_validation", out=str(tmp_path))
    with pytest.raises(ValueError):
        persson_check.report(source=str(tmp_path / "missing"), out=str(tmp_path / "s.md"))
