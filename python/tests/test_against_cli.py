"""Results equal to the command line's on the same inputs."""

import json

import numpy as np
import pytest

import persson_check
from conftest import save


@pytest.mark.parametrize(
    "n, hurst, lambda_l, lambda_s, seed, zeta",
    [
        (64, 0.8, 32.0, 4.0, 1, None),
        (128, 0.3, 128.0, 2.0, 12345678901234, None),
        (96, 0.8, 48.0, 4.0, 7, 5.0),
        (512, 0.8, 256.0, 4.0, 1, None),
    ],
)
def test_surface_is_the_cli_realization_bit_for_bit(cli, tmp_path, n, hurst, lambda_l, lambda_s, seed, zeta):
    out = tmp_path / "h.npy"
    args = ["surface", "--n", n, "--hurst", hurst, "--lambda-l", lambda_l,
            "--lambda-s", lambda_s, "--seed", seed, "--out", out]
    if zeta is not None:
        args += ["--zeta", zeta]
    cli(*args)
    ours = persson_check.surface(n, hurst, lambda_l, lambda_s, seed, zeta=zeta)
    theirs = np.load(out)
    assert ours.shape == (n, n) and ours.dtype == np.float64
    assert ours.tobytes() == theirs.tobytes()


def _cli_solve(cli, tmp_path, h, *flags):
    heights = save(tmp_path / "h.npy", h)
    out = tmp_path / "solve"
    cli("solve", "--heights", heights, *flags, "--out", out)
    summary = json.loads((out / "summary.json").read_text())
    return summary, np.load(out / "pressure.npy"), np.load(out / "gap.npy")


@pytest.mark.parametrize("n, solver", [(128, "cg"), (512, "cg"), (64, "gfmd")])
def test_solve_gives_the_cli_area_and_pressure(cli, tmp_path, n, solver):
    h = persson_check.surface(n, 0.8, n / 2, 4.0, 1)
    summary, pressure, gap = _cli_solve(
        cli, tmp_path, h, "--p0", 0.1, "--tol", 1e-8, "--solver", solver
    )
    s = persson_check.solve(h, p0=0.1, tol=1e-8, solver=solver)
    assert abs(s.contact_area - summary["contact_area"]) <= 1e-12
    assert np.max(np.abs(s.pressure - pressure)) <= 1e-12
    assert np.max(np.abs(s.gap - gap)) <= 1e-10
    assert s.iterations == summary["iterations"]
    ours = s.summary()
    for key in ("p0", "elastic_energy", "mean_gap", "residual", "zeta", "rms_gradient"):
        assert ours[key] == pytest.approx(summary[key], rel=1e-10, abs=1e-14), key
    assert ours["termination"] == summary["termination"] == "converged"
    assert set(summary) - {"source"} <= set(ours)


def test_summary_has_the_keys_of_summary_json_in_order(cli, tmp_path):
    h = persson_check.surface(64, 0.8, 32.0, 4.0, 1)
    summary, _, _ = _cli_solve(cli, tmp_path, h, "--p0", 0.1)
    ours = persson_check.solve(h, p0=0.1).summary()
    assert list(ours) == list(summary)
    assert list(ours["residual_components"]) == list(summary["residual_components"])
    assert summary["source"].endswith("h.npy")
    assert ours["source"] == "array"


def test_solve_at_a_contact_area_matches_the_cli(cli, tmp_path):
    h = persson_check.surface(64, 0.8, 32.0, 4.0, 5)
    summary, pressure, _ = _cli_solve(cli, tmp_path, h, "--contact-area", 0.2)
    s = persson_check.solve(h, contact_area=0.2)
    assert s.p0 == pytest.approx(summary["p0"], rel=1e-12)
    assert abs(s.contact_area - summary["contact_area"]) <= 1e-12
    assert np.max(np.abs(s.pressure - pressure)) <= 1e-12
    assert s.load_solves == summary["load_solves"]


def test_lambda_l_and_zeta_as_on_the_command_line(cli, tmp_path):
    h = persson_check.surface(64, 0.8, 32.0, 4.0, 2)
    summary, pressure, _ = _cli_solve(
        cli, tmp_path, h, "--p0", 0.05, "--file-lambda-l", 32, "--zeta", 3.0
    )
    s = persson_check.solve(h, p0=0.05, lambda_l=32.0, zeta=3.0)
    assert s.zeta == summary["zeta"] == 3.0
    assert abs(s.contact_area - summary["contact_area"]) <= 1e-12
    assert np.max(np.abs(s.pressure - pressure)) <= 1e-12
