"""One reduced validation from Python, with its plan and its scorecard."""

import json

import pytest

import persson_check
from conftest import ROOT


@pytest.fixture(scope="module")
def d_onset(tmp_path_factory):
    out = tmp_path_factory.mktemp("validate")
    return out, persson_check.validate(["d_onset"], out=str(out))


def test_reduced_d_onset_against_the_paper(d_onset):
    out, outcomes = d_onset
    assert len(outcomes) == 1
    o = outcomes[0]
    assert o["name"] == "d_onset"
    # The headline verdict is the paper's (assumption (d) violated): `reproduced` compares the
    # headline alone. The paper's statements are judged apart: at the reduced scale the peak
    # ratio's interval still reaches its alternative (the floor built into the measure).
    assert o["verdict"] == "violated"
    assert o["paper_verdict"] == "violated"
    assert o["reproduced"] is True
    peak = next(c for c in o["claims"] if c["key"] == "peaks_above_resolution")
    assert peak["result"] == "not_established"
    # The default solvers: GFMD for the headline, CG for the one cross-check.
    assert o["solver"] == "gfmd"
    assert [c["solver"] for c in o["cross_checks"]] == ["cg"]
    assert all(c["agrees"] is True for c in o["cross_checks"])
    # The same record as the file written beside it.
    assert o == json.loads((out / "d_onset.json").read_text())


def test_plan_lists_the_jobs():
    plan = persson_check.plan("d_onset", shards=2)
    assert plan["shards"] == 2
    assert len(plan["jobs"]) > 0
    assert {row["validation"] for row in plan["jobs"]} == {"d_onset"}
    assert len(plan["share_costs"]) == 2


def test_report_writes_the_scorecard(d_onset, tmp_path):
    out, _ = d_onset
    card = tmp_path / "scorecard.md"
    summary = persson_check.report(source=str(out), out=str(card), golden=str(ROOT / "golden"))
    assert summary["validations"] == ["d_onset"]
    assert card.read_text().count("d_onset") >= 1


def test_merge_needs_the_shares_results(tmp_path):
    with pytest.raises(ValueError):
        persson_check.merge("d_onset", out=str(tmp_path))
    # A partial merge leaves out only optional parts of a scene; d_onset has none.
    with pytest.raises(ValueError, match="have no result"):
        persson_check.merge("d_onset", out=str(tmp_path), partial=True)


def test_paths_may_be_pathlib_paths(d_onset, tmp_path):
    out, _ = d_onset
    assert isinstance(out, type(tmp_path))
    summary = persson_check.report(source=out, out=tmp_path / "card.md", golden=ROOT / "golden")
    assert summary["path"] == str(tmp_path / "card.md")
    plan = persson_check.plan("d_onset", out=out)
    assert {row["validation"] for row in plan["jobs"]} == {"d_onset"}
