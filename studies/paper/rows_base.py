"""The rows of Fig. 1-6 of Xu et al.: the base case (delta 1.03, r 50 um, 1000 m/s): the front at 250
ns, B800's means (first maxima, rise, dip, steady values, velocities), the top free surface, jets,
standard deviations and mean squared velocity gradients; the theory rows at delta 1.03.
"""

import numpy as np

from mpmshock_post.errors import PostError
from mpmshock_post.hugoniot import hugoniot_temperature_table, porous_shock
from .measures import (BOTTOM, BOTTOM_REGIONS, DISSIPATION_COLUMNS, PAPER_T_SUFFIX, SQUARED_RATE_UNIT,
                             TEMPERATURE_MODELS, TOP_REGIONS, NotMeasured, _display_quantity, column_heights,
                             deepest_dip, exponential_decay, in_window, late_dissipation, oscillation,
                             rise_end, smooth3, trend, value_at, window_mean)
from .rows import (ENERGY_T_REASON, FRAME_TEXT, LAYOUT_REASON, PAPER_432_REASON, PAPER_T_LEAST, fmt,
                         measured_row, number_verdict, ratio, row, signed, temperature_reason, yes_no)

DIP_WINDOW_END = 700.0           # ns: Fig. 2's dip near 450 ns is looked for before this
PAPER_DOWNSTREAM_BOUNDARY = 810.0   # um: the paper's 'downstream boundary' of B800 at 250 ns


# --- Fig. 1: t = 250 ns -------------------------------------------------------------------------------

def shocked_front(snapshot, pressure_threshold):
    """Target points (body 1) whose pressure is at least `pressure_threshold` (Pa): their x and y."""
    target = snapshot["body"] == 1
    shocked = target & (snapshot["pressure"] >= pressure_threshold)
    if not shocked.any():
        raise NotMeasured(f"no shocked target point at {snapshot.time * 1e9:.0f} ns")
    position = snapshot["position"][shocked]
    return position[:, 0], position[:, 1]


def fig1_rows(c):
    """250 ns. The front, from the snapshot: the highest target point whose pressure reaches half the
    full-compaction porous Hugoniot pressure. No stable shock: the shocked material is far from a
    uniform state, read from B800 (wholly shocked by then) as pressure std / mean above 5 % (a solid
    plate's plateau is uniform to about 1 %: docs/accuracy.md)."""

    def front(run):
        snapshot = run.snapshot_near(250.0)
        _, y = shocked_front(snapshot, 0.5 * run.hugoniot_state.pressure)
        front_um, top_um = y.max() * 1e6, run.region_top() * 1e6
        past = front_um > PAPER_DOWNSTREAM_BOUNDARY
        return (f"{yes_no(past)}: front at {fmt(front_um)} um",
                f"{'agree' if past else 'differ'}: the front is {'past' if front_um > top_um else 'short of'} B800's "
                f"top at {top_um:.0f} um (the paper's 810 um is not B800's top, 100 + 800 um: an inconsistency of "
                f"its text); theory: the porous front is at {250.0 * run.hugoniot_state.front_speed * 1e-3:.0f} um; "
                f"{run.resolution}")

    def unsteady(run):
        t, std = run.series(BOTTOM, "pressure_std")
        _, mean = run.series(BOTTOM, "pressure_mean")
        spread = ratio(value_at(t, std, 250.0), value_at(t, mean, 250.0))
        return (f"{yes_no(spread > 0.05)}: B800 pressure std/mean {spread:.3g} at 250 ns",
                f"{'agree' if spread > 0.05 else 'differ'}: rarefactions off the voids keep the shocked material "
                f"from a uniform state (a solid plate's plateau is uniform to ~1 %); {run.resolution}")

    return [
        measured_row(c, "Fig 1", "shock front passed the B800 downstream boundary at 250 ns", "yes (> 810)", "um",
                     ["base"], front),
        measured_row(c, "Fig 1", "no stable shock wave: the shocked material is not uniform at 250 ns", "yes", "",
                     ["base"], unsteady),
    ]


# --- Fig. 2: means in the base case -------------------------------------------------------------------

def first_maximum_value_rows(c):
    """The first maximum (first_maximum) of B800's mean density, pressure and temperature (both
    models), against the paper's 3.14 g/cm3, 16.7 GPa, 432 K; agreement within the numerical error
    docs/accuracy.md gives at the run's resolution (at least 0.5 %, 3 %, 10 K)."""
    entries = [("density", "density_mean", "base", 3.14, "g/cm3", lambda run: max(run.accuracy.density, 0.005), True),
               ("pressure", "pressure_mean", "base", 16.7, "GPa", lambda run: max(run.accuracy.pressure, 0.03), True)]
    entries += [(f"temperature ({model})", "temperature_mean", c.temperature_case("base", model), 432.0, "K",
                 lambda run: max(run.accuracy.temperature, 10.0), False) for model in TEMPERATURE_MODELS]
    rows = []
    for name, column, case, paper_value, unit, tolerance, relative in entries:
        def measure(run, column=column, name=name, paper_value=paper_value, unit=unit, tolerance=tolerance,
                    relative=relative):
            t, y = run.series(BOTTOM, column)
            t_max, value = run.first_maximum(BOTTOM, column)
            verdict = number_verdict(value, paper_value, tolerance(run), unit, relative)
            if verdict.startswith("agree"):
                reason = ""
            elif name.startswith("temperature"):
                model = name[name.index("(") + 1:-1]
                reason = f": {temperature_reason(model)}; {PAPER_432_REASON}"
            else:
                reason = ": the first maximum is a transient overshoot, sensitive to resolution and void layout"
            return fmt(value), (f"{verdict}{reason}; at {t_max:.0f} ns; at 250 ns: "
                                f"{fmt(value_at(t, y, 250.0))}; {run.accuracy.text}; {run.resolution}")
        rows.append(measured_row(c, "Fig 2", f"B800 first maximum of mean {name}", fmt(paper_value), unit, [case],
                                 measure))
    return rows


def first_maximum_time_rows(c):
    """The time of each first maximum, against the paper's 250 ns ('about': 10 %)."""
    entries = [("density", "density_mean", "base"), ("pressure", "pressure_mean", "base")]
    entries += [(f"temperature ({model})", "temperature_mean", c.temperature_case("base", model))
                for model in TEMPERATURE_MODELS]
    rows = []
    for name, column, case in entries:
        def measure(run, column=column):
            t_max, _ = run.first_maximum(BOTTOM, column)
            verdict = number_verdict(t_max, 250.0, 0.1, "ns")
            reason = "" if verdict.startswith("agree") else (
                f": theory puts the porous front's exit from B800 at {run.front_exit_time():.0f} ns; the paper "
                f"ascribes its later maximum to the dispersion of the shock")
            return fmt(t_max), (f"{verdict}{reason}; first local maximum of the 3-sample smoothed 10 ns series "
                                f"reaching 90 % of the rise; {run.resolution}")
        rows.append(measured_row(c, "Fig 2", f"B800 time of the first maximum of mean {name}", "250", "ns", [case],
                                 measure))
    return rows


def theory_base_rows(c):
    """The solid's T_H at the paper's 3.14 g/cm3, and the full-compaction porous Hugoniot at delta 1.03,
    1000 m/s (hugoniot.porous_shock) against the paper's first maximum and our B800 late window."""
    try:
        material = c.material
    except PostError as e:
        return [row("Fig 2", "theory: T_H of the solid at 3.14 g/cm3", "432", "K", "", f"not computed: {e}")]
    table = hugoniot_temperature_table(material)
    t_h = table.hugoniot_temperature(material.density / 3140.0)
    rows = [row("Fig 2", "theory: T_H of the solid at the paper's 3.14 g/cm3 (the least T of the paper's model there)",
                "432", "K", fmt(t_h), f"differ ({signed(t_h - 432.0, 3, 'K')}): {PAPER_432_REASON}")]
    state = porous_shock(1000.0, 1.03, material)
    t_h_compacted = table.hugoniot_temperature(state.J)

    def ours(case, column):
        run = c.get(case)
        if run is None:
            return f"ours: not run: {c.why(case)}"
        try:
            late = run.late_mean(BOTTOM, column)
        except NotMeasured as e:
            return f"not measured: {e}"
        # A window mean, not a steady state: the slope says how far the state still drifts there.
        return (f"our B800 {column} {fmt(late.mean)} over {late.t0:.0f}-{late.t1:.0f} ns (its mean; drifting "
                f"{late.slope:+.3g} per us there; {run.resolution})")

    rows += [
        row("Fig 2", "theory: full-compaction porous Hugoniot density (delta 1.03, 1000 m/s)", "3.14", "g/cm3",
            fmt(state.density * 1e-3), f"{number_verdict(state.density * 1e-3, 3.14, 0.005, '')}: the paper's "
            f"number is its transient first maximum, the nearest it gives; {ours('base', 'macro_density')}"),
        row("Fig 2", "theory: full-compaction porous Hugoniot pressure (delta 1.03, 1000 m/s)", "16.7", "GPa",
            fmt(state.pressure * 1e-9), f"{number_verdict(state.pressure * 1e-9, 16.7, 0.03, '')}: the paper's "
            f"first maximum overshoots the later state; {ours('base', 'macro_normal_stress')}"),
        row("Fig 2", "theory: full-compaction porous Hugoniot temperature (energy T) (delta 1.03, 1000 m/s)", "432",
            "K", fmt(state.temperature), f"differ: T_H(V) + (E - E_H)/c_v with the full compaction energy jump; "
            f"{ENERGY_T_REASON}; {ours('base', 'temperature_mean')}"),
        row("Fig 2", f"theory: {PAPER_T_LEAST} (delta 1.03, 1000 m/s)", "432", "K",
            fmt(t_h_compacted), f"{number_verdict(t_h_compacted, 432.0, 10.0, 'K', relative=False)}: the paper's "
            f"model adds plastic work to this, so it cannot be below; {PAPER_432_REASON}; "
            f"{ours(c.temperature_case('base', 'paper T'), 'temperature_mean')}"),
    ]
    return rows


def fig2_rise_rows(c):
    """Near-linear rise of B800's means to about 150 ns (rise_end)."""
    rows = []
    columns = (("density", "density_mean", "base"),
               ("pressure", "pressure_mean", "base"),
               *((f"temperature ({m})", "temperature_mean", c.temperature_case("base", m)) for m in TEMPERATURE_MODELS))
    for name, column, case in columns:
        def measure(run, column=column):
            t, y = run.series(BOTTOM, column)
            t_max, _ = run.first_maximum(BOTTOM, column)
            t_rise, r2 = rise_end(t, y, t_max)
            return (fmt(t_rise), f"{number_verdict(t_rise, 150.0, 0.15, 'ns')}; R^2 of a line over 0-{t_rise:.0f} ns "
                    f"{r2:.3f}; the rise ends when the smoothed rate falls below half its 0-100 ns rate; theory: the "
                    f"porous front leaves B800 at {run.front_exit_time():.0f} ns; "
                    f"{run.resolution}")
        rows.append(measured_row(c, "Fig 2", f"B800 mean {name} rises nearly linearly up to", "150", "ns", [case],
                                 measure))
    return rows


def fig2_dip_rows(c):
    """The dip (concave) near 450 ns: the deepest local minimum (deepest_dip) of the smoothed B800
    mean density between its first maximum and DIP_WINDOW_END (700 ns); the recovery: the largest smoothed value in the
    200 ns after the dip, as a share of the drop from the largest smoothed value in the 100 ns before
    it; the temperature's gain: its largest smoothed value in the 200 ns after the dip minus that in
    the 100 ns before."""

    def dip_of(run, column):
        return deepest_dip(*run.series(BOTTOM, column), run.initial_stage_end(), min(DIP_WINDOW_END, run.t_stop))

    def dip(run):
        t_dip, _ = dip_of(run, "density_mean")
        t_pdip, _ = dip_of(run, "pressure_mean")
        return (fmt(t_dip), f"{number_verdict(t_dip, 450.0, 0.1, 'ns')}; pressure's dip at {t_pdip:.0f} ns; the dips "
                f"come from rarefactions off the voids above B800, whose layout is random ({LAYOUT_REASON}); "
                f"{run.resolution}")

    def recovery(run):
        t, rho = run.series(BOTTOM, "density_mean")
        t_dip, low = dip_of(run, "density_mean")
        s = smooth3(rho)
        before = in_window(t, s, t_dip - 100.0, t_dip)[1].max()
        after_t, after = in_window(t, s, t_dip, min(t_dip + 200.0, run.t_stop))
        share = ratio(after.max() - low, before - low)
        recovered = share >= 0.9
        return (f"{yes_no(recovered)}: density regains {100 * share:.0f} % of its {fmt(before - low, 3)} g/cm3 drop "
                f"by {after_t[np.argmax(after)]:.0f} ns",
                f"{'agree' if recovered else 'differ'}: recovered means at least 90 % of the drop regained; "
                f"{run.resolution}")

    def temperature_gain(run):
        t_dip, _ = dip_of(run, "density_mean")
        tt, temperature = run.series(BOTTOM, "temperature_mean")
        s = smooth3(temperature)
        gain = (in_window(tt, s, t_dip, min(t_dip + 200.0, run.t_stop))[1].max()
                - in_window(tt, s, t_dip - 100.0, t_dip)[1].max())
        return (f"{yes_no(gain > 0)}: {signed(gain, 3, 'K')} after the dip",
                f"{'agree' if gain > 0 else 'differ'}: largest smoothed T in the 200 ns after the density dip minus "
                f"that in the 100 ns before; {run.resolution}")

    rows = [measured_row(c, "Fig 2", "time of the dip (concave) in B800 density and pressure", "450", "ns", ["base"],
                         dip),
            measured_row(c, "Fig 2", "B800 density recovers to its steady value after the dip", "yes", "g/cm3",
                         ["base"], recovery)]
    for model in TEMPERATURE_MODELS:
        rows.append(measured_row(c, "Fig 2", f"B800 temperature higher after the dip ({model})", "yes", "K",
                                 [c.temperature_case("base", model)], temperature_gain))
    return rows


def fig2_steady_rows(c):
    """After 650 ns in B800 (trend over [650 ns, t_stop]): density and pressure nearly constant, weak
    fluctuations (rms about the line, as a share of the mean), temperature still rising slowly;
    smaller domains show more detailed wave structure (B100 against B800 fluctuation)."""

    def constant(run):
        rho = trend(*run.series(BOTTOM, "density_mean"), 650.0, run.t_stop)
        p = trend(*run.series(BOTTOM, "pressure_mean"), 650.0, run.t_stop)
        rho_rate, p_rate = ratio(rho.slope, rho.mean), ratio(p.slope, p.mean)
        flat = abs(rho_rate) < 0.02 and abs(p_rate) < 0.1
        return (f"{yes_no(flat)}: density {signed(rho.slope, 3)} g/cm3/us ({signed(100 * rho_rate, 2)} %/us), "
                f"pressure {signed(p.slope, 3)} GPa/us ({signed(100 * p_rate, 2)} %/us)",
                f"{'agree' if flat else 'differ'}: least-squares slopes over {rho.t0:.0f}-{rho.t1:.0f} ns; nearly "
                f"constant read as under 2 %/us (density) and 10 %/us (pressure); {run.resolution}")

    def fluctuations(run):
        rho = trend(*run.series(BOTTOM, "density_mean"), 650.0, run.t_stop)
        p = trend(*run.series(BOTTOM, "pressure_mean"), 650.0, run.t_stop)
        rho_share, p_share = ratio(rho.fluctuation, rho.mean), ratio(p.fluctuation, p.mean)
        weak = rho_share < 0.01 and p_share < 0.05
        return (f"{yes_no(weak)}: rms {100 * rho_share:.2g} % (density), {100 * p_share:.2g} % (pressure)",
                f"{'agree' if weak else 'differ'}: rms about the least-squares line over {rho.t0:.0f}-{rho.t1:.0f} ns; "
                f"weak read as under 1 % and 5 %; {run.resolution}")

    def slowly_rising(run):
        temperature = trend(*run.series(BOTTOM, "temperature_mean"), 650.0, run.t_stop)
        rising = temperature.slope > 0
        return (f"{yes_no(rising)}: {signed(temperature.slope, 3, 'K/us')}",
                f"{'agree' if rising else 'differ'}: least-squares slope over {temperature.t0:.0f}-"
                f"{temperature.t1:.0f} ns; {run.resolution}")

    def smaller_domain_detail(run):
        small = oscillation(*run.series("B100", "density_mean"), 650.0, run.t_stop)
        large = oscillation(*run.series(BOTTOM, "density_mean"), 650.0, run.t_stop)
        return (f"{yes_no(small > large)}: density oscillation {fmt(small, 2)} (B100) vs {fmt(large, 2)} g/cm3 (B800)",
                f"{'agree' if small > large else 'differ'}: rms about the 5-sample running mean over 650-"
                f"{run.t_stop:.0f} ns; {run.resolution}")

    rows = [measured_row(c, "Fig 2", "B800 density and pressure nearly constant after 650 ns", "yes",
                         "g/cm3/us, GPa/us", ["base"], constant),
            measured_row(c, "Fig 2", "weak fluctuations of B800 density and pressure after 650 ns", "yes", "%",
                         ["base"], fluctuations)]
    for model in TEMPERATURE_MODELS:
        rows.append(measured_row(c, "Fig 2", f"B800 temperature still increasing slowly after 650 ns ({model})", "yes",
                                 "K/us", [c.temperature_case("base", model)], slowly_rising))
    rows.append(measured_row(c, "Fig 2", "smaller domains show more detailed wave structure (B100 vs B800)", "yes",
                             "g/cm3", ["base"], smaller_domain_detail))
    return rows


def fig2_velocity_rows(c):
    """B800's mean velocities after the initial stage ([initial_stage_end, t_stop]): u_y about 0
    (its mean and rms); u_x first rising, then oscillating near 0 (the largest |u_x| before the end of
    the initial stage + 100 ns against the rms after)."""

    def u_y(run):
        t, u = run.series(BOTTOM, "velocity_y_mean")
        tw, uw = in_window(t, u, run.initial_stage_end(), run.t_stop)
        mean, rms = float(uw.mean()), float(np.sqrt(np.mean(uw ** 2)))
        about_zero = abs(mean) < 0.05 * run.velocity and rms < 0.1 * run.velocity
        return (fmt(mean, 3), f"{'agree' if about_zero else 'differ'}: mean over {tw[0]:.0f}-{tw[-1]:.0f} ns, rms "
                f"{rms:.3g} m/s ({100 * rms / run.velocity:.2g} % of v); the symmetric impact leaves the shocked "
                f"material at rest; {run.resolution}")

    def u_x(run):
        t, u = run.series(BOTTOM, "velocity_x_mean")
        t_early = run.initial_stage_end() + 100.0
        _, early = in_window(t, u, t[0], t_early)
        _, late = in_window(t, u, t_early, run.t_stop)
        peak, late_rms = float(np.max(np.abs(early))), float(np.sqrt(np.mean(late ** 2)))
        rises = peak > 3.0 * late_rms and peak > 1.0
        return (f"{yes_no(rises)}: largest |u_x| {fmt(peak, 2)} m/s before {t_early:.0f} ns, "
                f"rms {fmt(late_rms, 2)} m/s after",
                f"{'agree' if rises else 'differ'}: a rise means a first |u_x| above 1 m/s and 3 times the later "
                f"rms; x momentum of the periodic column is conserved, so a full-width mean u_x stays near "
                f"0 by construction (the paper's first rise may be a layout or boundary effect); {run.resolution}")

    return [measured_row(c, "Fig 2", "B800 mean u_y after the initial stage", "0", "m/s", ["base"], u_y),
            measured_row(c, "Fig 2", "B800 mean u_x first increases, then oscillates near 0", "yes", "m/s", ["base"],
                         u_x)]


def fig2_top_rows(c):
    """The top of the target: the shock's arrival (CaseRun.top_arrival), the free-surface velocity
    (mean u_y of the same probe or region over [arrival + 100 ns, arrival + 200 ns]); after the
    release, the T800 and T400 means over the run's last 100 ns (which must start at least 200 ns after
    the arrival): density and pressure against their initial values, temperature rise above the
    initial temperature and its slope over the last 200 ns; the T100 density's oscillation
    (oscillation) from arrival + 200 ns against T400's and T800's."""

    def arrival(run):
        t_a, source, _, _ = run.top_arrival
        return (fmt(t_a), f"{number_verdict(t_a, 800.0, 0.05, 'ns')}: first upward crossing of u_y = 0 by "
                f"{source}; {run.resolution}")

    def surface_velocity(run):
        t_a, source, t, u = run.top_arrival
        if run.t_end < t_a + 200.0:
            raise NotMeasured(f"the run ends at {run.t_end:.0f} ns, before arrival + 200 ns")
        mean = window_mean(t, u, t_a + 100.0, t_a + 200.0)
        _, later = in_window(t, u, t_a + 100.0, run.t_end)
        verdict = number_verdict(mean, 877.0, 0.05, "")
        return (fmt(mean), f"{verdict}: mean u_y of {source} over {t_a + 100:.0f}-{t_a + 200:.0f} ns, {FRAME_TEXT}; "
                f"from {t_a + 100:.0f} ns to the end ({run.t_end:.0f} ns) it averages {later.mean():.0f} and ranges "
                f"{later.min():.0f}-{later.max():.0f} m/s; a near-solid free surface reaches about +v here; "
                f"{run.resolution}")

    def released(run):
        t_a = run.top_arrival[0]
        t0 = run.t_end - 100.0
        if t0 < t_a + 200.0:
            raise NotMeasured(f"the run ends at {run.t_end:.0f} ns, too soon after the arrival at {t_a:.0f} ns")
        return t0, run.t_end

    def density_after(region):
        def measure(run):
            t0, t1 = released(run)
            t, rho = run.series(region, "density_mean")
            tm, macro = run.series(region, "macro_density")
            value, macro_value = window_mean(t, rho, t0, t1), window_mean(tm, macro, t0, t1)
            above = macro_value > macro[0]
            return (f"{fmt(value)} (initial {fmt(rho[0])}); band {fmt(macro_value)} (initial {fmt(macro[0])})",
                    f"{'agree' if above else 'differ'} for the band density (mass over area, voids counted), the "
                    f"porous sample's density: {signed(100 * (macro_value / macro[0] - 1), 2)} %; the points' own "
                    f"density is {signed(100 * (value / rho[0] - 1), 2)} % from the solid's (hot, released material "
                    f"expands); means over {t0:.0f}-{t1:.0f} ns; {run.resolution}")
        return measure

    def pressure_after(region):
        def measure(run):
            t0, t1 = released(run)
            value = window_mean(*run.series(region, "pressure_mean"), t0, t1)
            return (fmt(value, 3), f"{'agree' if value > 0 else 'differ'} (slightly above the initial 0 GPa means "
                    f"> 0): mean over {t0:.0f}-{t1:.0f} ns; {run.resolution}")
        return measure

    def temperature_left(region, model):
        def measure(run):
            t0, t1 = released(run)
            t, temperature = run.series(region, "temperature_mean")
            rise = window_mean(t, temperature, t0, t1) - temperature[0]
            verdict = number_verdict(rise, 60.0, max(run.accuracy.temperature, 10.0), "K", relative=False)
            reason = "" if verdict.startswith("agree") else f": {temperature_reason(model)}"
            return fmt(rise), f"{verdict}{reason}; mean over {t0:.0f}-{t1:.0f} ns minus the initial; {run.resolution}"
        return measure

    def still_rising(model):
        def measure(run):
            _, t1 = released(run)
            slopes = {region: trend(*run.series(region, "temperature_mean"), t1 - 200.0, t1).slope
                      for region in ("T800", "T400")}
            rising = all(slope > 0 for slope in slopes.values())
            return (f"{yes_no(rising)}: " + ", ".join(f"{signed(s, 3, 'K/us')} ({r})" for r, s in slopes.items()),
                    f"{'agree' if rising else 'differ'}: least-squares slopes over the last 200 ns; {run.resolution}")
        return measure

    def t100_oscillations(run):
        t0 = run.top_arrival[0] + 200.0
        amplitude = {region: oscillation(*run.series(region, "density_mean"), t0, run.t_end) for region in TOP_REGIONS}
        evident = amplitude["T100"] > max(amplitude["T400"], amplitude["T800"])
        listed = ", ".join(f"{fmt(v, 2)} ({r})" for r, v in amplitude.items())
        return (f"{yes_no(evident)}: density oscillation {listed} g/cm3",
                f"{'agree' if evident else 'differ'}: rms about the 5-sample running mean over {t0:.0f}-"
                f"{run.t_end:.0f} ns (arrival + 200 ns on, once the release has crossed T800; the paper "
                f"names 900 ns, its arrival + 100 ns); evident means larger than in T400 and T800; {run.resolution}")

    rows = [measured_row(c, "Fig 2", "shock arrives at the top free surface", "800", "ns", ["base"], arrival),
            measured_row(c, "Fig 2", "top free surface moves up during unloading (simulation frame)", "877", "m/s",
                         ["base"], surface_velocity)]
    for region in ("T800", "T400"):
        rows.append(measured_row(c, "Fig 2", f"{region} density after release", "slightly above initial", "g/cm3",
                                 ["base"], density_after(region)))
    for region in ("T800", "T400"):
        rows.append(measured_row(c, "Fig 2", f"{region} pressure after release", "slightly above initial", "GPa",
                                 ["base"], pressure_after(region)))
    for model in TEMPERATURE_MODELS:
        for region in ("T800", "T400"):
            rows.append(measured_row(c, "Fig 2", f"{region} temperature left above the initial after release ({model})",
                                     "60", "K", [c.temperature_case("base", model)], temperature_left(region, model)))
    for model in TEMPERATURE_MODELS:
        rows.append(measured_row(c, "Fig 2", f"T800, T400 temperature still increasing after release ({model})", "yes",
                                 "K/us", [c.temperature_case("base", model)], still_rising(model)))
    rows.append(measured_row(c, "Fig 2", "evident oscillations in T100 density after 900 ns", "yes", "g/cm3", ["base"],
                             t100_oscillations))
    return rows


# --- Fig. 3: t = 1150 ns ------------------------------------------------------------------------------

def fig3_rows(c):
    """Jetting at the upper free surface at 1150 ns, from the snapshot: the highest target point in
    each x bin two cells wide; jets = the highest of those above their median (the surface), in um;
    'jetting' when that exceeds 2 cells."""

    def jets(run):
        snapshot = run.snapshot_near(1150.0)
        target = snapshot["body"] == 1
        position = snapshot["position"][target]
        h = float(run.scene["cell_size"])
        tops = column_heights(position[:, 0], position[:, 1], float(run.scene["width"]), 2.0 * h)
        height = (tops.max() - np.median(tops)) * 1e6
        return (f"{yes_no(height > 2e6 * h)}: highest jet {fmt(height, 3)} um above the median surface",
                f"{'agree' if height > 2e6 * h else 'differ'}: from the snapshot at {snapshot.time * 1e9:.0f} ns; jets "
                f"come from voids near the surface, {LAYOUT_REASON}; {run.resolution}")

    return [measured_row(c, "Fig 3", "jetting at the upper free surface at 1150 ns", "yes", "um", ["base"], jets)]


# --- Fig. 4: standard deviations ----------------------------------------------------------------------

STD_QUANTITIES = (("density", "density_std"), ("pressure", "pressure_std"), ("temperature", "temperature_std"),
                  ("u_x", "velocity_x_std"), ("u_y", "velocity_y_std"))


def decay_text(decay, unit):
    return (f"peak {fmt(decay.peak, 3)} {unit} at {decay.t_peak:.0f} ns, tau {fmt(decay.tau, 3)} ns, "
            f"R^2 {decay.r2:.3f}, steady {fmt(decay.steady, 3)} {unit}")


def decay_measure(region, column, unit):
    """exponential_decay of a region's column up to t_stop, as a row's (mpmshock, note); 'nearly
    exponential' read as R^2 >= 0.9."""
    def measure(run):
        decay = exponential_decay(*run.series(region, column), run.t_stop)
        good = decay.r2 >= 0.9
        return (f"{yes_no(good)}: {decay_text(decay, unit)}",
                f"{'agree' if good else 'differ'}: least-squares fit c + a exp(-(t - t_peak)/tau) from the peak to "
                f"{run.t_stop:.0f} ns; nearly exponential read as R^2 >= 0.9; {run.resolution}")
    return measure


def fig4_rows(c):
    """B800's standard deviations: rise, then nearly exponential decay (exponential_decay); std of
    u_y above that of u_x (time means over [std peak of u_y, t_stop] in B800, B400, B100); larger
    domains larger std in the transient (the peak of each std in B800, B400, B100)."""
    rows = []
    for name, column in STD_QUANTITIES:
        unit = _display_quantity(column).unit
        cases = ([c.temperature_case("base", m) for m in TEMPERATURE_MODELS] if name == "temperature" else ["base"])
        for case in cases:
            label = name + (f" ({'paper T' if case.endswith(PAPER_T_SUFFIX) else 'energy T'})"
                            if name == "temperature" else "")
            rows.append(measured_row(c, "Fig 4", f"B800 std of {label} rises fast, then decays nearly exponentially",
                                     "yes", unit, [case], decay_measure(BOTTOM, column, unit)))

    def uy_over_ux(run):
        parts, larger = [], True
        for region in BOTTOM_REGIONS:
            t, uy = in_window(*run.series(region, "velocity_y_std"), 0.0, run.t_stop)
            t_peak = t[int(np.argmax(smooth3(uy)))]
            y_mean = window_mean(t, uy, t_peak, run.t_stop)
            x_mean = window_mean(*run.series(region, "velocity_x_std"), t_peak, run.t_stop)
            larger &= y_mean > x_mean
            parts.append(f"{region} {fmt(y_mean, 3)} vs {fmt(x_mean, 3)}")
        return (f"{yes_no(larger)}: " + ", ".join(parts) + " m/s",
                f"{'agree' if larger else 'differ'}: time means of std u_y and std u_x from std u_y's peak to "
                f"{run.t_stop:.0f} ns; {run.resolution}")

    def larger_domains(run):
        verdicts, parts = [], []
        for name, column in STD_QUANTITIES:
            peaks = [float(np.max(smooth3(in_window(*run.series(r, column), 0.0, run.t_stop)[1])))
                     for r in BOTTOM_REGIONS]
            ordered = peaks[0] >= peaks[1] >= peaks[2]
            verdicts.append(ordered)
            parts.append(f"{name} {'/'.join(fmt(p, 3) for p in peaks)}")
        return (f"{yes_no(all(verdicts))} for {sum(verdicts)} of {len(verdicts)}: peak std B800/B400/B100 "
                + "; ".join(parts), f"{'agree' if all(verdicts) else 'partly' if any(verdicts) else 'differ'}: peaks "
                f"of the 3-sample smoothed std up to {run.t_stop:.0f} ns (units g/cm3, GPa, K, m/s); {run.resolution}")

    rows.append(measured_row(c, "Fig 4", "std of u_y larger than std of u_x", "yes", "m/s", ["base"], uy_over_ux))
    rows.append(measured_row(c, "Fig 4", "larger measured domains give larger std in the transient", "yes", "",
                             ["base"], larger_domains))
    return rows


# --- Fig. 5: mean squared rotation, divergence, strain rate --------------------------------------------

def fig5_rows(c):
    """B800's <Rot^2>, <Div^2>, <D:D>: nearly exponential decay to steady values (exponential_decay);
    steady = the late-window mean; 'close' read as a ratio within 0.67-1.5, 'a little larger' as a
    ratio between 1 and 2."""
    rows = [measured_row(c, "Fig 5", f"B800 mean squared {name} decays nearly exponentially to a steady value", "yes",
                         SQUARED_RATE_UNIT, ["base"], decay_measure(BOTTOM, column, SQUARED_RATE_UNIT))
            for name, column in DISSIPATION_COLUMNS]

    def strain_close_to_rotation(run):
        late = late_dissipation(run)
        strain_over_rotation = ratio(late["strain rate"], late["rotation"])
        close = 1 / 1.5 <= strain_over_rotation <= 1.5
        return (f"{yes_no(close)}: <D:D>/<Rot^2> = {strain_over_rotation:.3g} ({fmt(late['strain rate'], 3)} vs "
                f"{fmt(late['rotation'], 3)} 1/ns^2)", f"{'agree' if close else 'differ'}: late-window means "
                f"{run.late_window[0]:.0f}-{run.late_window[1]:.0f} ns; the strain rate is D:D (regions.csv), the "
                f"paper does not give its norm: with the equivalent rate (2/3) D:D the ratio is "
                f"{2.0 / 3.0 * strain_over_rotation:.3g}; {run.resolution}")

    def divergence_a_little_larger(run):
        late = late_dissipation(run)
        divergence_over_rotation = ratio(late["divergence"], late["rotation"])
        little = 1.0 < divergence_over_rotation <= 2.0
        return (f"{yes_no(little)}: <Div^2>/<Rot^2> = {divergence_over_rotation:.3g}, <Div^2>/<D:D> = "
                f"{ratio(late['divergence'], late['strain rate']):.3g}",
                f"{'agree' if little else 'differ'}: late-window means; a little larger read as 1-2 times the "
                f"rotation; {run.resolution}")

    rows += [measured_row(c, "Fig 5", "steady mean squared strain rate close to that of rotation", "yes",
                          SQUARED_RATE_UNIT, ["base"], strain_close_to_rotation),
             measured_row(c, "Fig 5", "steady mean squared divergence a little larger", "yes", SQUARED_RATE_UNIT,
                          ["base"], divergence_a_little_larger)]
    return rows


def fig6_rows(c):
    """Fig. 6 names a void of the paper's own layout; nothing in ours corresponds to it."""
    return [row("Fig 6", "a void near (510 um, 280 um) at 750 ns", "yes", "um", "n/a",
                f"not comparable: {LAYOUT_REASON}; the field plot at 750 ns shows our own voids")]
