#!/usr/bin/env python3
"""The table of the paper's numbers for reviewers: every number the paper (Dapp, Prodanov &
Müser 2014) states about the tested assumptions, beside the full-scale and the reduced
result of this project and whether each reproduces it.

    scripts/paper_table.py --full results/full --reduced results/reduced [--write README.md]

Reads the outcomes (<name>.json) of the two runs; prints the Markdown table, or with
--write replaces the table between the markers `<!-- paper-table -->` and
`<!-- /paper-table -->` of that file. A number whose validation has not run at that scale
shows "not run yet".

How a row is judged ("reproduces"):
  near  - within 10% of the paper's value or within three standard errors of it;
  check - the validation's own check of that part of the paper's finding passed;
  found - the validation reproduced the paper's finding (its verdict, range and checks).
"""
import argparse
import json
import math
import pathlib
import re
import sys

# (statement, paper's value as the paper gives it, the paper's number or None,
#  validation, where the measurement is, rule, check key for rule "check")
ROWS = [
    ("(a) D_n / D_P at high pressure, p >= p0/a_r", "~1", 1.0,
     "a_diffusion", "detail:d_ratio_high", "check", "high_pressure_ratio_near_one"),
    ("(a) D_n / D_P at low pressure, p < p0/a_r / 2", "larger than 1", None,
     "a_diffusion", "headline", "found", None),
    ("(b) contact-averaged drift mu_c (p0/a_r per unit zeta)", "< 0", None,
     "b_drift", "headline", "check", "mu_c_negative"),
    ("(c) flux into contact, zeta 128 -> 129.5 (% of A0)", "0.675%", 0.00675,
     "c_flux", "detail:flux_in", "near", None),
    ("(c) flux out of contact, same step (% of A0)", "0.597%", 0.00597,
     "c_flux", "detail:flux_out", "near", None),
    ("(c) net over mean one-way flux, same step", "~0.12", 0.12264,
     "c_flux", "detail:net_over_gross", "near", None),
    ("(c) non-contact entering contact, zeta 63 -> 63.3 (H = 0.5, a_r = 0.01; % of the non-contact)", "~1%", 0.01,
     "c_flux", "sensitivity:transition:zero_bin", "near", None),
    ("(c) re-entry share at a_r = 0.14 (H = 0.8)", "~62%", 0.62,
     "c_reentry", "detail:share_ar0.14", "near", None),
    ("(c) re-entry share at a_r = 0.014", "~100%", 1.0,
     "c_reentry", "detail:share_ar0.014", "near", None),
    ("(c) re-entry share at a_r = 0.88", "~8%", 0.08,
     "c_reentry", "detail:share_ar0.88", "near", None),
    ("(d) E_norm below resolution, partial contact", "> 0", None,
     "d_onset", "headline", "found", None),
    ("(e) asymptote K1 exp(-K2 x): K1 (H = 0.8)", "0.9", 0.9,
     "e_frozen", "detail:k1", "near", None),
    ("(e) asymptote K1 exp(-K2 x): K2 (H = 0.8)", "1.0", 1.0,
     "e_frozen", "detail:k2", "near", None),
    ("total energy: E_exa / E_c, corrected theory, intermediate load", "~0.9 (about 10% too high)", 0.91,
     "total_energy", "headline", "found", None),
    ("total energy: E_exa / E_c below a_r = 0.05 (a_r = 0.01): the correction fails", "fails", None,
     "total_energy", "detail:corrected_ar0.01", "check", "correction_fails_at_low_load"),
    ("contact area: kappa = a_r / p~0 at low load", "~2 (2 c1 = 2.15)", 2.15,
     "contact_area", "headline", "near", None),
    ("contact area: eq. (contactArea), largest deviation for a_r in [0.01, 0.9] (% of a_r)", "within ~10%", 0.1,
     "contact_area", "detail:law_deviation", "check", "law_within_tolerance"),
]


def load(folder):
    out = {}
    if folder and folder.is_dir():
        for p in folder.glob("*.json"):
            try:
                o = json.loads(p.read_text())
            except json.JSONDecodeError:
                continue
            if isinstance(o, dict) and "name" in o and "verdict" in o:
                out[o["name"]] = o
    return out


def estimate(o, where):
    """(value, std_error) of the measurement at `where`, or None."""
    kind, _, rest = where.partition(":")
    if kind == "headline":
        return o.get("value"), o.get("std_error")
    if kind == "detail":
        for d in o.get("details", []):
            if d["key"] == rest:
                v = d.get("value") or {}
                return v.get("value"), v.get("std_error")
        return None
    if kind == "sensitivity":
        parameter, field = rest.split(":")
        for r in o.get("sensitivity", []):
            if r["parameter"] == parameter and r.get(field):
                return r[field]["value"], r[field].get("std_error")
        return None
    raise ValueError(where)


def number(x):
    return isinstance(x, (int, float)) and math.isfinite(x)


def text(e, percent):
    value, err = e
    if not number(value):
        return "n/a"
    scale, unit = (100.0, "%") if percent else (1.0, "")
    digits = 3 if abs(value * scale) < 10 else 2
    s = f"{value * scale:.{digits}g}{unit}"
    if number(err):
        s += f" ± {err * scale:.2g}{unit}"
    return s


def judged(o, row, e):
    _, paper_text, paper, _, _, rule, check = row
    if rule == "found":
        return {True: "yes", False: "no", None: "undecided"}[o.get("reproduced")]
    if rule == "check":
        for c in o.get("checks", []):
            if c["key"] == check:
                if c.get("decided") is False:
                    return "undecided"
                return "yes" if c["passed"] else "no"
        return "n/a"
    value, err = e
    if not number(value):
        return "n/a"
    dev = abs(value - paper)
    if dev <= 0.1 * abs(paper) or (number(err) and dev <= 3 * err):
        return "yes"
    return "no"


def cell(outcomes, row):
    o = outcomes.get(row[3])
    if o is None:
        return "not run yet", "—"
    e = estimate(o, row[4])
    if e is None:
        return "not measured", "—"
    percent = row[1].endswith("%") or "% " in row[0] or "(% of" in row[0]
    return text(e, percent), judged(o, row, e)


def table(full, reduced):
    lines = [
        "| the paper's number | paper | full scale | reproduces | reduced | reproduces |",
        "|---|---|---|---|---|---|",
    ]
    for row in ROWS:
        f, fj = cell(full, row)
        r, rj = cell(reduced, row)
        lines.append(f"| {row[0]} | {row[1]} | {f} | {fj} | {r} | {rj} |")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--full", type=pathlib.Path, default=pathlib.Path("results/full"))
    ap.add_argument("--reduced", type=pathlib.Path, default=pathlib.Path("results/reduced"))
    ap.add_argument("--write", type=pathlib.Path, help="a Markdown file with the markers")
    args = ap.parse_args()
    md = table(load(args.full), load(args.reduced))
    if not args.write:
        sys.stdout.write(md)
        return
    doc = args.write.read_text()
    pattern = re.compile(r"(<!-- paper-table -->\n).*?(<!-- /paper-table -->)", re.S)
    if not pattern.search(doc):
        sys.exit(f"paper_table: no <!-- paper-table --> markers in {args.write}")
    args.write.write_text(pattern.sub(lambda m: m.group(1) + md + m.group(2), doc))
    print(f"paper_table: wrote the table into {args.write}")


if __name__ == "__main__":
    main()
