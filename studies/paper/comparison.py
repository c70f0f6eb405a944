"""Every number and every qualitative claim of Xu et al. (arXiv:0904.0135) set against mpmshock's
runs: the rows of comparison.csv.

    from paper.comparison import comparison_rows, write_comparison_csv
    rows = comparison_rows("DIR/runs")            # list of dicts, in the paper's figure order
    write_comparison_csv(rows, "DIR/comparison.csv")

Runs. runs_dir/<case>/ is an mpmshock run directory of studies/paper/scenes/<case>.scene with the default
(energy) temperature model; runs_dir/<case>-paperT/ is the same case with `temperature_model =
paper`, or, where that directory is absent, <case>/ itself read with its paper_temperature columns
(a run made with `paper_temperature = on` reports both models). Cases: base (delta 1.03, r 50 um, 1000 m/s; Fig. 1-8), void_r25, void_r100 (Fig. 7-8),
delta1.4 (r 10 um; Fig. 9-13), delta1.4_v500, delta1.4_v1500, delta1.4_v2000 (Fig. 12), delta1.01,
delta1.02, delta1.1, delta1.7 (Fig. 13). A run that is missing gives its rows with `mpmshock` empty
and the note 'not run'; a measurement a run cannot give (too short, no snapshot at that time) gives
'not measured' and the reason.

Rows. `figure, quantity, paper, mpmshock, unit, note`: the paper's value or claim, ours (a number to
4 significant digits, or a measured statement such as 'yes: slope -0.12 g/cm3/us'), in the paper's
units (g/cm3, GPa, K, m/s, ns, um; mean squares of velocity gradients in 1/ns^2), and whether the two
agree and why not (the temperature model, the numerical error that docs/accuracy.md estimates at
the run's resolution, a quick run's coarser cells, the paper's own inconsistency). Temperatures
come in two rows: '(energy T)' from the default model, T = T_H(V) + (E - E_H(V))/c_v, which
includes the compaction (PdV) heating of collapsing voids, and '(paper T)' from the paper's
T = T_H(V) + plastic work/c_v, which leaves that heating out.

Code. paper_measures.py reads the runs and measures them (CaseRun, Campaign, first_maximum, ...);
paper_rows.py holds what every row shares (row, measured_row, study_row, the words and the
reasons); paper_rows_base.py makes the rows of Fig. 1-6 (the base case), paper_rows_studies.py
those of Fig. 7-13; this module puts them in the paper's order and writes the csv.

Definitions shared by the rows (each measurement function's docstring gives its own):
- Times are in ns from the impact; a region's series is its regions.csv column (means and standard
  deviations over its points), converted to the paper's units.
- The shock-free end t_stop of a run is its end time, or, if earlier, the estimated time at which
  the release from the top free surface reaches the top of the bottom region (release_time).
- The late ('steady') window is the last 300 ns before t_stop.
- The initial stage of a bottom region ends at the first maximum of its mean density
  (first_maximum); 'after the initial stage' is [that time, t_stop].
"""

import csv

from .measures import Campaign
from .rows_base import (fig1_rows, fig2_dip_rows, fig2_rise_rows, fig2_steady_rows, fig2_top_rows,
                              fig2_velocity_rows, fig3_rows, fig4_rows, fig5_rows, fig6_rows,
                              first_maximum_time_rows, first_maximum_value_rows, theory_base_rows)
from .rows_studies import fig7_rows, fig8_rows, fig9_rows, fig10_rows, fig11_rows, fig12_rows, fig13_rows

COLUMNS = ("figure", "quantity", "paper", "mpmshock", "unit", "note")


# --- the table ----------------------------------------------------------------------------------------

FIGURES = (fig1_rows, first_maximum_value_rows, first_maximum_time_rows, theory_base_rows, fig2_rise_rows,
           fig2_dip_rows, fig2_steady_rows, fig2_velocity_rows, fig2_top_rows, fig3_rows, fig4_rows, fig5_rows,
           fig6_rows, fig7_rows, fig8_rows, fig9_rows, fig10_rows, fig11_rows, fig12_rows, fig13_rows)


def comparison_rows(runs_dir, quick=False):
    """Every row of comparison.csv, in the paper's figure order (dicts with the keys of COLUMNS).
    `quick` marks the runs as the reduced ones of `reproduce-paper --quick` in the notes."""
    campaign = Campaign(runs_dir, quick)
    rows = []
    for figure_rows in FIGURES:
        rows += figure_rows(campaign)
    return rows


def write_comparison_csv(rows, path):
    """comparison.csv: the header figure,quantity,paper,mpmshock,unit,note and one line per row."""
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=COLUMNS, lineterminator="\n")
        writer.writeheader()
        for entry in rows:
            writer.writerow({key: entry.get(key, "") for key in COLUMNS})
