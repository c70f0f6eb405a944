"""What every row of comparison.csv shares: numbers and words, the row builders (a missing run gives
'not run', a measurement the run cannot give 'not measured') and the reasons the notes give.
"""

import numpy as np

from mpmshock_post.errors import PostError
from .measures import NotMeasured



# --- numbers and words ------------------------------------------------------------------------------

def fmt(value, digits=4):
    """A number to `digits` significant digits ('' for None or NaN)."""
    if value is None or not np.isfinite(value):
        return ""
    return f"{value:.{digits}g}"


def signed(value, digits=3, unit=""):
    """'+1.23 unit' / '-1.23 unit'."""
    return f"{value:+.{digits}g}" + (f" {unit}" if unit else "")


def ratio(numerator, denominator):
    """numerator / denominator; NotMeasured when the denominator is not a positive number."""
    if not denominator > 0:
        raise NotMeasured(f"a ratio to {denominator:g}")
    return numerator / denominator


def yes_no(flag):
    return "yes" if flag else "no"


def number_verdict(ours, paper, tolerance, unit, relative=True):
    """'agree' when |ours - paper| <= tolerance (a share of the paper's value if `relative`, else in
    `unit`), else 'differ'; with the signed difference."""
    difference = ours - paper
    if relative:
        share = difference / paper
        within = abs(share) <= tolerance
        text = f"{signed(100 * share, 2)} % from the paper; tolerance {100 * tolerance:.2g} %"
    else:
        within = abs(difference) <= tolerance
        text = f"{signed(difference, 3, unit)} from the paper; tolerance {tolerance:.3g} {unit}"
    return ("agree" if within else "differ") + f" ({text})"


# --- rows ----------------------------------------------------------------------------------------------

def row(figure, quantity_name, paper, unit, mpmshock="", note=""):
    return {"figure": figure, "quantity": quantity_name, "paper": paper, "mpmshock": mpmshock, "unit": unit,
            "note": note}


def measured_row(campaign, figure, quantity_name, paper, unit, cases, measure):
    """A row from `measure(*runs) -> (mpmshock, note)` on the runs of `cases`. A missing run gives
    mpmshock '' and the note 'not run: CASE'; NotMeasured (or a PostError reading the run) gives ''
    and 'not measured: why'."""
    runs = [campaign.get(case) for case in cases]
    missing = [case for case, run in zip(cases, runs) if run is None]
    if missing:
        return row(figure, quantity_name, paper, unit, "", "not run: " + ", ".join(map(campaign.why, missing)))
    try:
        mpmshock, note = measure(*runs)
    except (NotMeasured, PostError) as e:
        return row(figure, quantity_name, paper, unit, "", f"not measured ({runs[0].resolution}): {e}")
    return row(figure, quantity_name, paper, unit, mpmshock, note)


def study_row(campaign, figure, quantity_name, paper, unit, cases, measure):
    """A row over a series of cases (void size, speed, porosity): `measure(runs) -> (mpmshock, note)`
    with the runs present, in the order of `cases`; fewer than two present gives 'not run'."""
    present = {case: campaign.get(case) for case in cases if campaign.get(case) is not None}
    missing = [case for case in cases if case not in present]
    not_run = "not run: " + ", ".join(map(campaign.why, missing))
    if len(present) < 2:
        return row(figure, quantity_name, paper, unit, "", not_run)
    try:
        mpmshock, note = measure(present)
    except (NotMeasured, PostError) as e:
        return row(figure, quantity_name, paper, unit, "", f"not measured: {e}")
    if missing:
        note += f" ({not_run})"
    return row(figure, quantity_name, paper, unit, mpmshock, note)


# --- reasons ------------------------------------------------------------------------------------------

ENERGY_T_REASON = ("the energy temperature includes the compaction (PdV) heating of collapsing voids, which the "
                   "paper's T_H(V) + plastic work/c_v leaves out: compare the (paper T) row")
PAPER_432_REASON = ("the paper's 432 K lies below the solid's T_H at its own 3.14 g/cm3 (462.7 K: the theory row), "
                    "which its temperature model cannot give for material compressed that far: an inconsistency "
                    "in the paper")
PAPER_T_LEAST = "T_H at the full-compaction density (paper T without plastic work: its least value)"
LAYOUT_REASON = "our void layout (random, seed) is not the paper's"
FRAME_TEXT = ("in the simulation frame of the paper's symmetric set-up (impact plane at rest, target at -v "
              "before the shock); a target-at-rest experiment would read v more")


def temperature_reason(model):
    """Why a temperature of `model` may differ from the paper's."""
    if model == "energy T":
        return ENERGY_T_REASON
    return ("the paper's own temperature model, so the rest is numerics (coarse cells understate temperatures: "
            "docs/accuracy.md) and the void layout")
