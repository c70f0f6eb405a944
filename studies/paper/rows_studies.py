"""The rows of Fig. 7-13 of Xu et al.: void size (Fig. 7-8), delta 1.4 (Fig. 9-11, with the theory
rows at delta 1.4), shock strength (Fig. 12) and porosity (Fig. 13).
"""

import math

import numpy as np

from mpmshock_post.errors import PostError
from mpmshock_post.hugoniot import hugoniot_temperature_table, porous_shock
from .measures import (BOTTOM, DISSIPATION_COLUMNS, LATE_WINDOW, PAPER_T_SUFFIX, SQUARED_RATE_UNIT,
                             TEMPERATURE_MODELS, NotMeasured, in_window, late_dissipation,
                             slopes_after_initial_stage, smooth3, window_mean)
from .rows import PAPER_T_LEAST, fmt, measured_row, ratio, row, signed, study_row, yes_no



# --- Fig. 7 and 8: void size ---------------------------------------------------------------------------

VOID_CASES = ("void_r25", "base", "void_r100")


def void_resolution_text(runs):
    """How the void-size runs are resolved, and what that does to the comparison between them."""
    ratios = [run.cells_per_radius for run in runs.values()]
    listed = ", ".join(f"r/{r:.2g}" for r in ratios)
    if max(ratios) / min(ratios) < 1.01:
        return (f"the cells scale with r (h = {listed}), so each void is resolved alike, but the cells differ in "
                f"size: finer cells resolve steeper velocity gradients (larger mean squares) and overstate density "
                f"and pressure less (docs/accuracy.md)")
    return (f"the radii are resolved differently (h = {listed}): better-resolved voids heat more and give larger "
            f"mean squared gradients (docs/accuracy.md), which mixes resolution into the void-size effect")


def band_sampling_text(runs, with_temperature=False):
    """How one layout per radius samples B800: its own initial porosity in each run (few large voids
    fill a band unevenly) and the full-compaction Hugoniot there; with_temperature: how far each
    run's late mean temperature (energy model) lies from that Hugoniot's. Empty where a run has no
    t = 0 sample."""
    try:
        states = [run.band_hugoniot(BOTTOM) for run in runs.values()]
    except NotMeasured:
        return ""
    radii = "/".join(radius_label(run) for run in runs.values())
    text = (f"B800's own porosity at t = 0 (its band density) is delta "
            + "/".join(f"{state.porosity:.4f}" for state in states) + f" at {radii} (body: "
            + "/".join(f"{run.porosity:.4g}" for run in runs.values()) + "): the layout, not the radius, sets how "
            "porous the measured band is, and the full-compaction Hugoniot at those porosities gives "
            + "/".join(f"{state.density * 1e-3:.4g}" for state in states) + " g/cm3, "
            + "/".join(f"{state.pressure * 1e-9:.4g}" for state in states) + " GPa, "
            + "/".join(f"{state.temperature:.0f}" for state in states) + " K (energy T)")
    if with_temperature:
        late = [run.late_mean(BOTTOM, "temperature_mean").mean for run in runs.values()]
        text += "; our temperatures minus those: " + "/".join(
            signed(ours - state.temperature, 2, "K") for ours, state in zip(late, states))
    return text


def radius_label(run):
    return f"r {float(run.scene['void_radius']) * 1e6:.3g} um"


def fig7_rows(c):
    """Late-window B800 means for each void radius: temperature rising with r; density, pressure and
    u_y with no evident difference, i.e. a spread between the radii (max - min) no larger than twice
    the largest within-run fluctuation (rms about the window's line)."""
    rows = []
    for model in TEMPERATURE_MODELS:
        energy_model = model == TEMPERATURE_MODELS[0]  # the Hugoniot's temperature is the energy model's

        def hotter(runs, energy_model=energy_model):
            late = {case: run.late_mean(BOTTOM, "temperature_mean") for case, run in runs.items()}
            values = [late[case].mean for case in runs]
            increasing = all(b > a for a, b in zip(values, values[1:]))
            return ("{}: ".format(yes_no(increasing)) + ", ".join(
                f"{fmt(late[case].mean)} K ({radius_label(run)})" for case, run in runs.items()),
                f"{'agree' if increasing else 'differ'}: B800 late-window means (last {LATE_WINDOW:.0f} ns before each "
                f"run's t_stop); {void_resolution_text(runs)}; "
                + (f"{sampling}; " if (sampling := band_sampling_text(runs, energy_model)) else "")
                + "; ".join(run.resolution for run in runs.values()))
        rows.append(study_row(c, "Fig 7", f"larger voids give a higher mean temperature ({model})", "yes", "K",
                              [c.temperature_case(case, model) for case in VOID_CASES], hotter))

    def no_difference(runs):
        parts, alike = [], True
        for name, column in (("density", "density_mean"), ("pressure", "pressure_mean"), ("u_y", "velocity_y_mean")):
            late = [run.late_mean(BOTTOM, column) for run in runs.values()]
            spread = max(x.mean for x in late) - min(x.mean for x in late)
            noise = max(x.fluctuation for x in late)
            alike &= spread <= 2.0 * noise
            parts.append(f"{name} spread {fmt(spread, 2)} (fluctuation {fmt(noise, 2)})")
        return (f"{yes_no(alike)}: " + ", ".join(parts),
                f"{'agree' if alike else 'differ'}: B800 late-window means over the radii "
                f"{', '.join(radius_label(r) for r in runs.values())}; no evident difference read as a spread within "
                f"twice the largest fluctuation; units g/cm3, GPa, m/s; {void_resolution_text(runs)}"
                + (f"; {sampling}" if (sampling := band_sampling_text(runs)) else ""))

    rows.append(study_row(c, "Fig 7", "no evident difference in steady density, pressure and velocity", "yes",
                          "g/cm3, GPa, m/s", list(VOID_CASES), no_difference))
    return rows


def fig8_rows(c):
    """Void size and B800's <Rot^2>, <Div^2>: the transient (peak of the smoothed series) differs
    between the radii, the steady values (late-window means) do not: 'differ' read as a max/min ratio
    above 1.5."""

    def ratios(runs, value):
        parts, largest = [], 1.0
        for name, column in DISSIPATION_COLUMNS[:2]:
            values = [value(run, column) for run in runs.values()]
            spread = ratio(max(values), min(values))
            largest = max(largest, spread)
            parts.append(f"{name} " + "/".join(fmt(v, 3) for v in values) + f" (max/min {spread:.3g})")
        return parts, largest

    def peak(run, column):
        return float(np.max(smooth3(in_window(*run.series(BOTTOM, column), 0.0, run.t_stop)[1])))

    def steady(run, column):
        return run.late_mean(BOTTOM, column).mean

    def transient(runs):
        parts, largest = ratios(runs, peak)
        return (f"{yes_no(largest > 1.5)}: peaks " + "; ".join(parts) + " 1/ns^2 at "
                + "/".join(radius_label(r) for r in runs.values()),
                f"{'agree' if largest > 1.5 else 'differ'}: peak of the 3-sample smoothed series; differ read as "
                f"max/min > 1.5; {void_resolution_text(runs)}")

    def steady_alike(runs):
        parts, largest = ratios(runs, steady)
        return (f"{yes_no(largest <= 1.5)}: late means " + "; ".join(parts) + " 1/ns^2",
                f"{'agree' if largest <= 1.5 else 'differ'}: late-window means; alike read as max/min <= 1.5; "
                f"{void_resolution_text(runs)}")

    return [study_row(c, "Fig 8", "void size changes the transient of mean squared rotation and divergence", "yes",
                      SQUARED_RATE_UNIT, list(VOID_CASES), transient),
            study_row(c, "Fig 8", "void size does not change their steady values", "yes", SQUARED_RATE_UNIT,
                      list(VOID_CASES), steady_alike)]


# --- Fig. 9 and 10: delta 1.4 --------------------------------------------------------------------------

def fig9_rows(c):
    """delta 1.4, B800 after the initial stage (CaseRun.after_initial_stage): density and pressure
    falling; the temperature rising faster than at delta 1.03 (the same definition on base);
    the full-compaction porous Hugoniot as theory."""

    def falling(column, unit):
        def measure(run):
            fit = run.after_initial_stage(BOTTOM, column)
            down = fit.slope < 0
            verdict = ("differ" if not down else "agree" if fit.distinguishable_from_zero
                       else "agree in sign only (the slope lies within 2 standard errors of zero)")
            return (f"{yes_no(down)}: {slope_text(fit)} {unit}/us (R^2 {fit.r2:.2f})",
                    f"{verdict}: least-squares slope (+- standard error, residuals' autocorrelation allowed for) over "
                    f"{fit.t0:.0f}-{fit.t1:.0f} ns (first maximum of the density to t_stop); {run.accuracy.text}; "
                    f"{run.resolution}")
        return measure

    rows = [measured_row(c, "Fig 9", "delta 1.4: B800 density decreases after the initial stage", "yes", "g/cm3/us",
                         ["delta1.4"], falling("density_mean", "g/cm3")),
            measured_row(c, "Fig 9", "delta 1.4: B800 pressure decreases after the initial stage", "yes", "GPa/us",
                         ["delta1.4"], falling("pressure_mean", "GPa"))]
    for model in TEMPERATURE_MODELS:
        def faster(high, low):
            fast = high.after_initial_stage(BOTTOM, "temperature_mean")
            slow = low.after_initial_stage(BOTTOM, "temperature_mean")
            return (f"{yes_no(fast.slope > slow.slope)}: {slope_text(fast)} K/us vs "
                    f"{slope_text(slow)} K/us at delta 1.03",
                    f"{'agree' if fast.slope > slow.slope else 'differ'}: slopes (+- standard error, residuals' "
                    f"autocorrelation allowed for) over {fast.t0:.0f}-{fast.t1:.0f} ns (delta 1.4) and "
                    f"{slow.t0:.0f}-{slow.t1:.0f} ns (delta 1.03); {separation_text([fast, slow])}; "
                    f"{high.resolution}; {low.resolution}")
        rows.append(measured_row(c, "Fig 9", f"temperature rises faster at delta 1.4 than at 1.03 ({model})", "yes",
                                 "K/us", [c.temperature_case("delta1.4", model), c.temperature_case("base", model)],
                                 faster))
    return rows + theory_delta14_rows(c)


# The shock each case of Fig. 9, 12 and 13 drives (studies/paper/scenes/CASE.scene; test_paper_comparison checks
# the scenes): (impact velocity in m/s, porosity delta).
CASE_SHOCKS = {"delta1.4": (1000.0, 1.4), "delta1.4_v500": (500.0, 1.4), "delta1.4_v1500": (1500.0, 1.4),
               "delta1.4_v2000": (2000.0, 1.4), "delta1.01": (1000.0, 1.01), "delta1.02": (1000.0, 1.02),
               "delta1.1": (1000.0, 1.1), "delta1.7": (1000.0, 1.7)}


def theory_delta14_rows(c):
    """The full-compaction porous Hugoniot at delta 1.4, 1000 m/s against our B800 late-window means,
    with T_H at its density (the paper model's least temperature)."""
    return theory_case_rows(c, "Fig 9", "delta1.4", paper_least=True)


def theory_case_rows(c, figure, case, paper_least=False):
    """The full-compaction porous Hugoniot of `case`'s shock (CASE_SHOCKS) against our B800
    late-window means (macro_density, macro_normal_stress, temperature_mean of the energy model;
    with paper_least, T_H at the Hugoniot density against the paper model's temperature)."""
    velocity, porosity = CASE_SHOCKS[case]
    label = f"(delta {porosity:g}, {velocity:.0f} m/s)"
    try:
        material = c.material
    except PostError as e:
        return [row(figure, f"theory: full-compaction porous Hugoniot {label}", "", "", "", f"not computed: {e}")]
    state = porous_shock(velocity, porosity, material)
    entries = [("full-compaction porous Hugoniot density", "macro_density", state.density * 1e-3, "g/cm3", case),
               ("full-compaction porous Hugoniot pressure", "macro_normal_stress", state.pressure * 1e-9, "GPa", case),
               ("full-compaction porous Hugoniot temperature (energy T)", "temperature_mean", state.temperature, "K",
                case)]
    if paper_least:
        t_h = hugoniot_temperature_table(material).hugoniot_temperature(state.J)
        entries.append((PAPER_T_LEAST, "temperature_mean", t_h, "K", case + PAPER_T_SUFFIX))
    rows = []
    for name, column, theory, unit, run_name in entries:
        run = c.get(run_name)
        if run is None:
            note = f"theory (hugoniot.porous_shock); ours: not run: {c.why(run_name)}"
        else:
            try:
                late = run.late_mean(BOTTOM, column)
                note = (f"theory (hugoniot.porous_shock); ours: B800 {column} {fmt(late.mean)} over {late.t0:.0f}-"
                        f"{late.t1:.0f} ns ({signed(100 * (late.mean / theory - 1), 2)} %); {run.accuracy.text}; "
                        f"{run.resolution}")
            except NotMeasured as e:
                note = f"theory (hugoniot.porous_shock); ours not measured: {e}"
        rows.append(row(figure, f"theory: {name} {label}", "", unit, fmt(theory), note))
    return rows


def fig10_rows(c):
    """delta 1.4, B800: in the transient (t <= initial_stage_end) the time means of <Rot^2>, <Div^2>,
    <D:D>, rotation the largest; later (late window) the three similar, read as max/min <= 1.5."""

    def transient(run):
        t_end = run.initial_stage_end()
        means = {name: window_mean(*run.series(BOTTOM, column), 0.0, t_end) for name, column in DISSIPATION_COLUMNS}
        largest = max(means, key=means.get)
        return (f"{yes_no(largest == 'rotation')}: " + ", ".join(f"{n} {fmt(v, 3)}" for n, v in means.items())
                + " 1/ns^2", f"{'agree' if largest == 'rotation' else 'differ'}: time means over 0-{t_end:.0f} ns "
                f"(to the first maximum of the density); {run.resolution}")

    def similar(run):
        late = late_dissipation(run)
        spread = ratio(max(late.values()), min(late.values()))
        return (f"{yes_no(spread <= 1.5)}: " + ", ".join(f"{n} {fmt(v, 3)}" for n, v in late.items())
                + f" 1/ns^2 (max/min {spread:.3g})", f"{'agree' if spread <= 1.5 else 'differ'}: late-window means "
                f"{run.late_window[0]:.0f}-{run.late_window[1]:.0f} ns; similar read as max/min <= 1.5; "
                f"{run.resolution}")

    return [measured_row(c, "Fig 10", "delta 1.4: rotation the largest contribution in the transient", "yes",
                         SQUARED_RATE_UNIT, ["delta1.4"], transient),
            measured_row(c, "Fig 10", "delta 1.4: later the three contributions nearly the same", "yes",
                         SQUARED_RATE_UNIT, ["delta1.4"], similar)]


# --- Fig. 11: distributions ---------------------------------------------------------------------------

NON_GAUSSIAN_SKEWNESS = 0.5
NON_GAUSSIAN_KURTOSIS = 1.0


def fig11_rows(c):
    """delta 1.4, B800 at 1200/1250/1300 ns: a distribution is non-Gaussian when |skewness| > 0.5 or
    |excess kurtosis| > 1 at every time (clearly visible against the Gaussian of the same mean and
    deviation); it varies with time when its mean moves by more than 0.1 std or its std, skewness or
    kurtosis changes by more than 10 %, 0.2 or 0.2 between the times."""
    rows = []

    def non_gaussian(name):
        def measure(run):
            table, which = run.distributions
            entries = table[name]
            far = all(abs(s) > NON_GAUSSIAN_SKEWNESS or abs(k) > NON_GAUSSIAN_KURTOSIS for _, _, _, s, k in entries)
            return (f"{yes_no(far)}: skewness " + "/".join(f"{s:.2f}" for *_, s, _ in entries) + ", excess kurtosis "
                    + "/".join(f"{k:.2f}" for *_, k in entries), f"{'agree' if far else 'differ'}: B800 at {which}; "
                    f"non-Gaussian read as |S| > {NON_GAUSSIAN_SKEWNESS} or |K| > {NON_GAUSSIAN_KURTOSIS}; "
                    f"{run.resolution}")
        return measure

    for name in ("density", "pressure", "temperature", "velocity_x", "velocity_y"):
        cases = ([(m, c.temperature_case("delta1.4", m)) for m in TEMPERATURE_MODELS] if name == "temperature"
                 else [(None, "delta1.4")])
        for model, case in cases:
            label = name.replace("velocity_", "u_") + (f" ({model})" if model else "")
            rows.append(measured_row(c, "Fig 11", f"delta 1.4: distribution of {label} non-Gaussian", "yes", "",
                                     [case], non_gaussian(name)))

    def varies(run):
        table, which = run.distributions
        moving = []
        for name, entries in table.items():
            means, stds, skews, kurts = (np.array(col) for col in list(zip(*entries))[1:])
            if (np.ptp(means) > 0.1 * stds.mean() or np.ptp(stds) > 0.1 * stds.mean() or np.ptp(skews) > 0.2
                    or np.ptp(kurts) > 0.2):
                moving.append(name.replace("velocity_", "u_"))
        return (f"{yes_no(bool(moving))}: " + (", ".join(moving) if moving else "none") + " change",
                f"{'agree' if moving else 'differ'}: B800 at {which}; a change is a mean moving by 0.1 std or std by "
                f"10 %, skewness or kurtosis by 0.2; {run.resolution}")

    rows.append(measured_row(c, "Fig 11", "delta 1.4: the distributions vary with time", "yes", "", ["delta1.4"],
                             varies))
    return rows


# --- Fig. 12 and 13: shock strength and porosity ------------------------------------------------------

SPEED_CASES = ("delta1.4_v500", "delta1.4", "delta1.4_v1500", "delta1.4_v2000")
SMALL_POROSITY_CASES = ("delta1.01", "delta1.02", "delta1.1")   # Fig. 13's 'very small' porosities
LARGE_POROSITY_CASES = ("delta1.4", "delta1.7")


def fig12_rows(c):
    """delta 1.4 at 500, 1000, 1500, 2000 m/s: the slopes after the initial stage of B800's density
    (falling faster) and temperature (rising faster) as the shock strengthens, i.e. the density slope
    decreasing and the temperature slope increasing with v."""

    def trend_with_speed(column, unit, sign):
        def measure(runs):
            fits = slopes_after_initial_stage(runs, column)
            values = [sign * fits[case].slope for case in runs]
            grows = all(b > a for a, b in zip(values, values[1:]))
            return (f"{yes_no(grows)}: " + ", ".join(f"{slope_text(fits[case])} at {run.velocity:.0f} m/s"
                                                      for case, run in runs.items()) + f" {unit}/us",
                    f"{'agree' if grows else 'differ'}: B800 least-squares slopes (+- standard error, residuals' "
                    f"autocorrelation allowed for) from the first maximum of the density to t_stop; "
                    + separation_text([fits[case] for case in runs]) + "; "
                    + "; ".join(run.resolution for run in runs.values()))
        return measure

    rows = [study_row(c, "Fig 12", "delta 1.4: density decreases faster with a stronger shock", "yes", "g/cm3/us",
                      list(SPEED_CASES), trend_with_speed("density_mean", "g/cm3", -1.0))]
    for model in TEMPERATURE_MODELS:
        rows.append(study_row(c, "Fig 12", f"delta 1.4: temperature increases faster with a stronger shock ({model})",
                              "yes", "K/us", [c.temperature_case(case, model) for case in SPEED_CASES],
                              trend_with_speed("temperature_mean", "K", 1.0)))
    for case in SPEED_CASES:
        if case != "delta1.4":  # its theory rows are Fig. 9's
            rows += theory_case_rows(c, "Fig 12", case)
    return rows


def slope_text(fit):
    """A Trend's slope with its standard error, e.g. '-0.0084 +- 0.0012'."""
    return f"{signed(fit.slope, 3)} +- {fmt(fit.slope_se, 2)}"


def separation_text(fits):
    """How many neighbouring slopes of a study (in its order) differ by more than twice their combined
    standard error, sqrt(se_a^2 + se_b^2), and by how many the first and the last differ: whether its
    ordering is beyond the noise."""
    def apart(a, b):
        error = math.hypot(a.slope_se, b.slope_se)
        return abs(b.slope - a.slope) / error if error > 0 else math.inf

    if len(fits) < 2:
        return "one slope alone"
    if len(fits) == 2:
        return f"the two slopes differ by {apart(*fits):.1f} combined standard errors"
    pairs = list(zip(fits, fits[1:]))
    return (f"{sum(apart(a, b) > 2.0 for a, b in pairs)} of {len(pairs)} neighbouring slopes differ by more than 2 "
            f"combined standard errors, the first and the last by {apart(fits[0], fits[-1]):.1f}")


def fig13_rows(c):
    """1000 m/s, delta 1.01 ... 1.7: B800 density slopes after the initial stage
    (CaseRun.after_initial_stage). At small porosity (1.01, 1.02, 1.1) the decrease rate grows with
    delta: the slopes fall with delta. At large porosity (1.4, 1.7) the behaviour is 'more complex'
    when the slopes over all porosities stop falling with delta, or a straight line fits the large
    porosities worse (mean R^2) than the small ones."""

    def small(runs):
        fits = slopes_after_initial_stage(runs, "density_mean")
        values = [fits[case].slope for case in runs]
        grows = all(b < a for a, b in zip(values, values[1:]))
        flat = [f"{run.porosity:g}" for case, run in runs.items() if not fits[case].distinguishable_from_zero]
        separation = separation_text([fits[case] for case in runs])
        return (f"{yes_no(grows)}: " + ", ".join(f"{slope_text(fits[case])} at delta {run.porosity:g}"
                                                 for case, run in runs.items()) + " g/cm3/us",
                f"{'agree' if grows else 'differ'}: B800 slopes (+- standard error, residuals' autocorrelation "
                f"allowed for) from the first maximum of the density to t_stop; "
                + (f"within 2 standard errors of zero (no measurable trend) at delta {', '.join(flat)}; "
                   if flat else "every slope beyond 2 standard errors of zero; ")
                + separation + "; " + "; ".join(run.resolution for run in runs.values()))

    def large(runs):
        fits = slopes_after_initial_stage(runs, "density_mean")
        small_r2 = [fits[case].r2 for case in runs if case in SMALL_POROSITY_CASES]
        large_r2 = [fits[case].r2 for case in runs if case in LARGE_POROSITY_CASES]
        if not small_r2 or not large_r2:
            raise NotMeasured("needs a small- and a large-porosity run")
        slopes = [fits[case].slope for case in runs]
        monotone = all(b < a for a, b in zip(slopes, slopes[1:]))
        complex_ = not monotone or np.mean(large_r2) < np.mean(small_r2)
        return (f"{yes_no(complex_)}: " + ", ".join(f"{slope_text(fits[case])} (R^2 {fits[case].r2:.2f}) at delta "
                                                    f"{run.porosity:g}" for case, run in runs.items()) + " g/cm3/us",
                f"{'agree' if complex_ else 'differ'}: more complex read as slopes that stop falling with delta or a "
                f"worse straight-line fit at large porosity; slopes fall monotonically with delta: {yes_no(monotone)}; "
                f"mean R^2 {np.mean(large_r2):.2f} (large) vs {np.mean(small_r2):.2f} (small); "
                + "; ".join(run.resolution for run in runs.values()))

    rows = [study_row(c, "Fig 13", "small porosity: density decrease rate grows with porosity", "yes", "g/cm3/us",
                      list(SMALL_POROSITY_CASES), small),
            study_row(c, "Fig 13", "large porosity: density shows more complex behaviour", "yes", "g/cm3/us",
                      list(SMALL_POROSITY_CASES + LARGE_POROSITY_CASES), large)]
    for case in SMALL_POROSITY_CASES + LARGE_POROSITY_CASES:
        if case != "delta1.4":
            rows += theory_case_rows(c, "Fig 13", case)
    return rows
