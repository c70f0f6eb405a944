"""The sections of docs/accuracy.md, one per part of the accuracy study: each computes its tables and
findings from the series' Outcomes, draws its figures and fills its prose from accuracy.md.in.

Part of the study in studies/accuracy/ of the checkout, run as `studies/accuracy/accuracy-study`;
report.py assembles the document. Table headers and cell labels are here, sentences in the template.
"""

import math

import numpy as np

from mpmshock_post import converge
from mpmshock_post.errors import PostError
from mpmshock_post.reader import Run

from .figures import (SOLID_PLOTTED, figure_answer, figure_porous, figure_sensitivity, figure_solid_cost,
                      figure_solid_h)
from .formats import (RELATIVE, cells_text, error_text, h_text, md_table, order_or_dash, order_text, unit_of,
                      unit_value)
from .measure import (LARGE_RUN, QUANTITIES, band_deviator, exact_order, measure_single, needed_resolution,
                      nice_cell, plateau, study_rate)
from .plan import MAIN_SHAPE, NS, PAPER_SCENE, REGION, SHAPES, UM


def _window_text(series):
    t0, t1 = series.window
    return f"{t0 / NS:g}-{t1 / NS:g}"


def _resolved(o):
    """The resolved scene (scene.txt) of an Outcome's first run: what the simulator ran, automatic
    keys (cfl, av_linear) included."""
    return Run(o.run_dirs[0][0]).scene


def _values_of(outcomes, key):
    """The values of one resolved key over these Outcomes' runs, as text ('0.6', or '0.2 and 0.6')."""
    return " and ".join(dict.fromkeys(f"{_resolved(o)[key]:g}" for o in outcomes))


def _cfls(outcomes):
    """Each shape's cfl as run ('bspline2_domain 0.6, bilinear 0.3'), the main shape first."""
    shapes = sorted({o.series.info["shape"] for o in outcomes}, key=SHAPES.index)
    return ", ".join(f"{shape} {_values_of([o for o in outcomes if o.series.info['shape'] == shape], 'cfl')}"
                     for shape in shapes)


def _layouts(report, series):
    n = series.seeds
    return report.text("layouts", count=n, plural="s" if n > 1 else "",
                       seeds=", ".join(str(1 + s) for s in range(n)))


# --- part 1: solid plates -------------------------------------------------------------------------

def _shape_key(o):
    order = {shape: k for k, shape in enumerate(SHAPES)}   # the main shape first
    return (o.series.info.get("velocity", 0), order.get(o.series.info.get("shape"), 9), o.series.info.get("ppc", 0))


def solid_section(report, outcomes):
    """Section 1: the errors against the exact Rankine-Hugoniot state, their orders, the cost, a
    fourth level and strength."""
    text = report.text
    standard = sorted((o for o in outcomes if o.series.info["plasticity"] == "off" and not o.series.info.get("fine")),
                      key=_shape_key)
    fine = [o for o in outcomes if o.series.info.get("fine")]
    plastic = [o for o in outcomes if o.series.info["plasticity"] == "on"]
    plan = report.plan
    speeds = []
    for v in sorted({o.series.info["velocity"] for o in standard}):
        o = next(o for o in standard if o.series.info["velocity"] == v)
        ex = o.series.info["exact"]
        speeds.append(f"| {v:g} m/s | {ex.density:.5g} | {ex.pressure * 1e-9:.4g} | {ex.temperature:.4g} | "
                      f"{o.series.scene['end_time']} | {_window_text(o.series)} ns | "
                      f"{o.series.info['t_release'] / NS:.0f} ns |")
    chunks = [text("solid", width=h_text(plan.solid_width), height_mm=f"{plan.solid_height * 1e3:g}",
                   columns=f"{plan.solid_width / standard[0].h[0]:g} cells at {h_text(standard[0].h[0])}",
                   band=standard[0].series.scene["region." + REGION], cells=cells_text(standard[0].h),
                   speeds="\n".join(speeds), cfls=_cfls(standard),
                   av_linear=_values_of(standard, "av_linear"))]
    for q in SOLID_PLOTTED:
        chunks.append(text("solid.errors", quantity=q, table=_solid_errors(q, standard)))
    chunks.append(text("solid.orders", figure_h=report.figure("solid_h", figure_solid_h, standard + fine),
                       figure_cost=report.figure("solid_cost", figure_solid_cost, standard + fine)))
    at = [o for o in standard + fine if o.series.info["velocity"] == 1000.0]
    if at:
        chunks.append(text("solid.cost", table=_solid_cost(at)))
    for o in fine:
        chunks.append(text("solid.fine", shape=o.series.info["shape"], table=_fourth_level(o)))
    for o in plastic:
        off = next(x for x in standard if all(x.series.info[key] == o.series.info[key]
                                              for key in ("velocity", "shape", "ppc")))
        chunks.append(_strength(report, o, off))
    _shape_findings(report, standard)
    report.sections.append(chunks)
    report.window_cases += [(f"solid {o.series.info['velocity']:g} m/s", o) for o in outcomes
                            if o.series.info["shape"] == MAIN_SHAPE and o.series.info["ppc"] == 2
                            and o.series.info["plasticity"] == "off" and not o.series.info.get("fine")]


def _solid_errors(q, standard):
    """The table of one quantity's errors against the exact state, per speed, shape and ppc."""
    header = ["speed", "shape", "ppc", *(f"error {h_text(h)}" for h in standard[0].h),
              "order vs exact (finest pair)", "tool's observed order", "tool's estimate (finest)",
              "estimate / true error", "extrapolated error"]
    rows = []
    for o in standard:
        ex = o.series.exact[q]
        res = o.results[q]
        errors = [v - ex for v in res.values]
        est = res.estimate.errors[-1]
        ratio = est / abs(errors[-1]) if errors[-1] else math.inf
        rows.append([f"{o.series.info['velocity']:g}", o.series.info["shape"], o.series.info["ppc"],
                     *(error_text(q, e, ex) for e in errors), order_or_dash(exact_order(errors, o.h)),
                     order_text(res.estimate), error_text(q, est, ex, signed=False), f"{ratio:.2g}",
                     error_text(q, res.estimate.extrapolated - ex, ex)])
    return md_table(header, rows)


def _solid_cost(at):
    """Points, steps and rates of the 1000 m/s runs (the fourth level's finest only)."""
    rows = []
    for o in at:
        for k, h in enumerate(o.h):
            if o.series.info.get("fine") and k < len(o.h) - 1:
                continue
            s = o.summaries[k][0]
            rows.append([o.series.info["shape"], o.series.info["ppc"], h_text(h), s["material_points"], s["steps"],
                         f"{s['material_points'] * s['steps']:.3g}", f"{s['wall_seconds']:.2f}",
                         f"{s['point_steps_per_second']:.3g}", f"{s['threads']} ({s['steps_with_fewer_threads']} "
                         f"steps on fewer)", f"{abs(s['energy_error']):.1e}"])
    return md_table(["shape", "ppc", "cell", "points", "steps", "point-steps", "wall (s)", "point-steps/s", "threads",
                     "energy error"], rows)


def _fourth_level(o):
    """The orders of the three coarser and the three finer of four levels."""
    rows = []
    for q in SOLID_PLOTTED:
        ex = o.series.exact[q]
        res = o.results[q]
        errors = [v - ex for v in res.values]
        coarse = converge.richardson(res.values[:3], o.h[:3])
        rows.append([q, *(error_text(q, e, ex) for e in errors), order_or_dash(exact_order(errors[:3], o.h[:3])),
                     order_or_dash(exact_order(errors, o.h)), order_text(coarse), order_text(res.estimate),
                     f"{res.estimate.errors[-1] / abs(errors[-1]):.2g}" if errors[-1] else "-"])
    return md_table(["quantity", *(f"error {h_text(h)}" for h in o.h), "order vs exact 20/10/5",
                     "order vs exact 10/5/2.5", "tool's order 20/10/5", "tool's order 10/5/2.5",
                     "tool's estimate / true (2.5 um)"], rows)


def _strength(report, o, off):
    """The plasticity-on series against the same series without strength; adds its finding."""
    material = Run(o.run_dirs[-1][0]).scene   # the run's resolved scene: its strength parameters
    sy0, Et, E = material["yield_stress"], material["tangent_modulus"], material["youngs_modulus"]
    Ep = E * Et / (E - Et)
    J = o.series.info["exact"].J
    y_hard = sy0 + Ep * (2.0 / 3.0) * abs(math.log(J))
    rows, deviators = [], []
    for k, h in enumerate(o.h):
        d_sigma = o.results["macro_normal_stress"].values[k] - off.results["macro_normal_stress"].values[k]
        d_p = o.results["pressure_mean"].values[k] - off.results["pressure_mean"].values[k]
        d_t = o.results["temperature_mean"].values[k] - off.results["temperature_mean"].values[k]
        d_rho = o.results["density_mean"].values[k] - off.results["density_mean"].values[k]
        dev = band_deviator(o.run_dirs[k][0])
        deviators.append(dev)
        rows.append([h_text(h), f"{o.results['macro_normal_stress'].values[k] * 1e-9:.4f}",
                     f"{off.results['macro_normal_stress'].values[k] * 1e-9:.4f}", f"{d_sigma * 1e-6:+.0f}",
                     f"{d_p * 1e-6:+.0f}", f"{(d_sigma - d_p) * 1e-6:+.0f}", f"{d_rho:+.2f}", f"{d_t:+.2f}",
                     f"{-dev['s_yy'] * 1e-6:.0f}", f"{dev['von_mises'] * 1e-6:.0f}", f"{dev['plastic_strain']:.3f}"])
    finest = deviators[-1]
    yields = {"yield": f"{sy0 * 1e-6:.0f}", "two_thirds_yield": f"{2 / 3 * sy0 * 1e-6:.0f}",
              "two_thirds_hardened": f"{2 / 3 * y_hard * 1e-6:.0f}",
              "uniaxial_strain": f"{2 / 3 * abs(math.log(J)):.3f}", "von_mises": f"{finest['von_mises'] * 1e-6:.0f}",
              "plastic_strain": f"{finest['plastic_strain']:.3f}"}   # the numbers the strength prose names
    where = "below_yield" if finest["von_mises"] < 0.9 * sy0 else "at_yield"
    verdict = report.text(f"solid.plastic.{where}", s_yy=f"{-finest['s_yy'] * 1e-6:.0f}", **yields)
    av_linear = _values_of([o], "av_linear")
    report.find("solid.plastic", shape=o.series.info["shape"], av_linear=av_linear, h=h_text(o.h[-1]),
                excess=f"{(rows and float(rows[-1][5])):+.0f}", where=report.text(f"finding.solid.plastic.{where}"),
                **yields)
    res = o.results["macro_normal_stress"]
    table = md_table(["cell", "sigma_n on (GPa)", "sigma_n off (GPa)", "sigma_n on-off (MPa)",
                      "P on-off (MPa)", "(sigma_n - P) on-off (MPa)", "rho on-off (kg/m3)", "T on-off (K)",
                      "-s_yy at the end (MPa)", "von Mises stress at the end (MPa)", "plastic strain"], rows)
    return report.text("solid.plastic", shape=o.series.info["shape"], av_linear=av_linear,
                       plastic_modulus=f"{Ep * 1e-6:.0f}", table=table, verdict=verdict,
                       limit=f"{res.estimate.extrapolated * 1e-9:.4f}", order=order_text(res.estimate),
                       hydrodynamic=f"{o.series.exact['macro_normal_stress'] * 1e-9:.4f}", **yields)


def _shape_findings(report, standard):
    """Per shape at 2 points per cell: the largest error at the finest cell and the orders."""
    for shape in SHAPES:
        group = [o for o in standard if o.series.info["shape"] == shape and o.series.info["ppc"] == 2]
        if not group:
            continue
        parts = []
        for q in ("pressure_mean", "macro_normal_stress", "density_mean", "temperature_mean"):
            errors = [o.results[q].values[-1] - o.series.exact[q] for o in group]
            worst = max(range(len(group)), key=lambda i: abs(errors[i]))
            orders = [exact_order([v - o.series.exact[q] for v in o.results[q].values], o.h) for o in group]
            parts.append(report.text("finding.solid.shape.quantity", quantity=q,
                                     error=error_text(q, errors[worst], group[worst].series.exact[q]),
                                     orders="/".join("-" if p is None else f"{p:.1f}" for p in orders)))
        report.find("solid.shape", shape=shape, h=h_text(group[0].h[-1]), h_coarser=h_text(group[0].h[-2]),
                    speeds="/".join(f"{o.series.info['velocity']:g}" for o in group), errors="; ".join(parts))


# --- part 2: porous bodies ------------------------------------------------------------------------

def porous_section(report, outcomes):
    """Section 2: each porosity's convergence, the resolution it needs, its residual porosity and
    the comparisons (the main shape without volumetric smoothing, the other shape functions)."""
    text, plan = report.text, report.plan
    r = plan.void_radius
    main = sorted((o for o in outcomes if not o.series.info["comparison"]), key=lambda o: o.series.info["delta"])
    shapes = [o for o in outcomes if o.series.info["comparison"]]   # in the plan's order
    o0 = main[0]
    wider = "".join(" " + text("porous.wider", wide=h_text(w), delta=f"{d:g}", width=h_text(plan.porous_width))
                    for d, w in plan.porous_width_for.items() if d in plan.porous_deltas)
    deltas = []
    for o in main + shapes:
        ex = o.series.info["exact"]
        voids = [s["voids"] / 2 for s in o.summaries[-1]]
        deltas.append(f"| {o.series.info['delta']:g}{'' if o in main else ', ' + o.series.info['label']} | "
                      f"{np.mean(voids):.0f} | {ex.density:.5g} | {ex.pressure * 1e-9:.4g} | {ex.temperature:.4g} | "
                      f"{ex.shock_speed:.0f} | {o.series.scene['end_time']} | {_window_text(o.series)} ns | "
                      f"{o.series.seeds} |")
    chunks = [text("porous", r=h_text(r), cells=cells_text(o0.h), ratios=", ".join(f"1/{r / h:g}" for h in o0.h),
                   width=h_text(plan.porous_width), wider=wider, height=h_text(plan.porous_height),
                   deltas="\n".join(deltas), main_shape=MAIN_SHAPE, cfl=_values_of(main, "cfl"),
                   av_linear=_values_of(main, "av_linear"))]
    for o in main:
        chunks.append(text("porous.delta", delta=f"{o.series.info['delta']:g}", layouts=_layouts(report, o.series),
                           table=_porous_convergence(o, r)))
    chunks.append(text("porous.units"))
    need, table = _porous_need(main, r)
    chunks.append(text("porous.need", table=table))
    chunks.append(text("porous.residual", table=_residual_porosity(main)))
    if shapes:
        chunks.append(_porous_shapes(report, main, shapes, r))
    chunks.append(text("porous.figure", figure=report.figure("porous", figure_porous, main + shapes, r)))
    for o in main:
        d = o.series.info["delta"]
        q = "macro_normal_stress"
        res = o.results[q]
        needs = ", ".join(f"{t} %: " + (f"h/r = 1/{r / need[(d, q, t)][0]:.2g}" if need[(d, q, t)][0] else "-") +
                          ("" if need[(d, q, t)][1] == "measured" else " (extrapolated)") for t in (1, 3, 10))
        ex = o.series.exact[q]
        rho = o.results["macro_density"]
        report.find("porous", delta=f"{d:g}", r=h_text(r), seeds=o.series.seeds, needs=needs,
                    limit=f"{res.estimate.extrapolated * 1e-9:.3g}", order=order_text(res.estimate),
                    from_full=error_text(q, res.estimate.extrapolated - ex, ex), exact=f"{ex * 1e-9:.3g}",
                    fine=f"{r / o.h[-1]:g}",
                    density_from_full=error_text("macro_density", rho.values[-1] - o.series.exact["macro_density"],
                                                 o.series.exact["macro_density"]),
                    points_from_full=error_text("density_mean", o.results["density_mean"].values[-1]
                                                - o.series.exact["density_mean"], o.series.exact["density_mean"]))
    report.sections.append(chunks)
    report.window_cases += [(f"delta {o.series.info['delta']:g}", o) for o in main]


def _porous_convergence(o, r):
    """One porosity's seed means per level, limit, order, errors and full-compaction difference."""
    rows = []
    for q in QUANTITIES:
        res = o.results[q]
        ex = o.series.exact.get(q)
        limit = res.estimate.extrapolated
        rows.append([q, *(f"{unit_value(q, v)} ± {unit_value(q, se, 2)}" for v, se in
                          zip(res.values, res.standard_errors)),
                     unit_value(q, limit), order_text(res.estimate),
                     error_text(q, res.estimate.errors[-1], limit, signed=False),
                     error_text(q, res.standard_errors[-1], limit, signed=False),
                     "-" if ex is None else unit_value(q, ex),
                     "-" if ex is None else error_text(q, limit - ex, ex)])
    return md_table(["quantity (units)", *(f"h/r = 1/{r / h:g}" for h in o.h), "limit", "order",
                     "disc. error (finest)", "SE (finest)", "full compaction", "limit - full compaction"], rows)


def _porous_need(main, r):
    """({(delta, quantity, target %): (h, how)}, the table of the h/r each target needs)."""
    header = ["delta", *(f"{q} {t:g} %" for q in ("macro_normal_stress", "pressure_mean") for t in (1, 3, 10))]
    rows, need = [], {}
    for o in main:
        row = [f"{o.series.info['delta']:g}"]
        for q in ("macro_normal_stress", "pressure_mean"):
            for t in (1, 3, 10):
                h, err, how = needed_resolution(o.results[q], o.h, t / 100.0, True)
                need[(o.series.info["delta"], q, t)] = (h, how)
                row.append("-" if h is None else (f"h/r = 1/{r / h:.2g} ({h_text(h)})" +
                                                  ("" if how == "measured" else f", {how}")))
        rows.append(row)
    return need, md_table(header, rows)


def _residual_porosity(main):
    """The points' density against the band's at the finest cell."""
    rows = []
    for o in main:
        k = len(o.h) - 1
        rho_pts, rho_macro = o.results["density_mean"].values[k], o.results["macro_density"].values[k]
        ex = o.series.info["exact"]
        rows.append([f"{o.series.info['delta']:g}", h_text(o.h[k]), f"{rho_pts:.5g}", f"{rho_macro:.5g}",
                     f"{ex.density:.5g}", f"{100 * (rho_pts / rho_macro - 1):+.2f} %",
                     f"{100 * (rho_macro / ex.density - 1):+.2f} %", f"{100 * (rho_pts / ex.density - 1):+.2f} %"])
    return md_table(["delta", "cell", "density_mean", "macro_density", "full compaction",
                     "density_mean / macro_density - 1 (open voids)", "macro_density vs full compaction",
                     "density_mean vs full compaction"], rows)


def _porous_shapes(report, main, shapes, r):
    """The comparisons (the main shape without volumetric smoothing, bspline2, gimp, bilinear) at one
    porosity against the main shape's limit; adds their findings."""
    delta = shapes[0].series.info["delta"]
    base = next(o for o in main if o.series.info["delta"] == delta)
    rows = []
    for o in [base] + shapes:
        for q in ("macro_normal_stress", "pressure_mean", "macro_density", "density_mean", "temperature_mean"):
            res = o.results[q]
            ref = base.results[q].estimate.extrapolated
            dist = [abs(v - ref) for v in res.values]
            trend = (f"moves away from the {MAIN_SHAPE} limit with refinement" if dist[-1] > dist[-2] > dist[0] or
                     dist[-1] > dist[0] * 1.5 else "")
            se = error_text(q, res.standard_errors[-1], ref, signed=False) if o.series.seeds > 1 else "-"
            rows.append([o.series.info["label"], o.series.seeds, q,
                         *(unit_value(q, v) for v in res.values), unit_value(q, res.estimate.extrapolated),
                         order_text(res.estimate), error_text(q, res.values[-1] - ref, ref), se, trend])
    for o in shapes:
        away = [q for q in ("macro_normal_stress", "pressure_mean", "temperature_mean")
                if abs(o.results[q].values[-1] - base.results[q].estimate.extrapolated) >
                abs(o.results[q].values[0] - base.results[q].estimate.extrapolated)]
        if away:
            report.find("porous.shape", delta=f"{delta:g}", shape=o.series.info["label"], quantities=", ".join(away),
                        fine=f"{r / o.h[-1]:g}", coarse=f"{r / o.h[0]:g}", main_shape=MAIN_SHAPE)
        if o.series.info["comparison"].scene:   # the main shape's scene changed otherwise: the same layouts
            _variant_finding(report, base, o, r)
    table = md_table(["series", "layouts", "quantity", *(f"h/r = 1/{r / h:g}" for h in base.h), "own limit",
                      "order", f"finest - {MAIN_SHAPE} limit", "SE (finest)", "trend"], rows)
    others = [o.series.info["label"] for o in shapes]
    notes = "".join(" " + report.text(o.series.info["comparison"].note, label=o.series.info["label"],
                                      main_shape=MAIN_SHAPE)
                    for o in shapes if o.series.info["comparison"].note)
    return report.text("porous.shapes", delta=f"{delta:g}", table=table, main_shape=MAIN_SHAPE,
                       shapes=", ".join(others[:-1]) + " and " + others[-1] if len(others) > 1 else others[0],
                       cfls=_cfls([base] + shapes), notes=notes)


def _variant_finding(report, base, o, r):
    """A comparison that changes the main shape's scene (volumetric smoothing off) against the main
    shape at the finest cell, layout by layout over the layouts both ran: the mean difference and,
    with two or more layouts, its standard error."""
    n = min(len(base.run_dirs[-1]), len(o.run_dirs[-1]))
    parts = []
    for q in ("macro_normal_stress", "pressure_mean", "macro_density", "temperature_mean"):
        diffs = [plateau(v, q, o.series.window) - plateau(b, q, base.series.window)
                 for b, v in zip(base.run_dirs[-1][:n], o.run_dirs[-1][:n])]
        mean = float(np.mean(diffs))
        ref = base.results[q].values[-1]
        text = error_text(q, mean, ref)
        if n > 1:
            text += " ± " + error_text(q, float(np.std(diffs, ddof=1)) / math.sqrt(n), ref, signed=False)
        parts.append(report.text("finding.porous.variant.quantity", quantity=q, difference=text))
    seeds = ("layouts " if n > 1 else "layout ") + ", ".join(str(1 + s) for s in range(n))
    report.find("porous.variant", delta=f"{o.series.info['delta']:g}", label=o.series.info["label"],
                main_shape=MAIN_SHAPE, seeds=seeds,
                spread=" ± its standard error" if n > 1 else "", fine=f"{r / o.h[-1]:g}",
                differences="; ".join(parts))


# --- part 3: sensitivity ------------------------------------------------------------------------------

SENSITIVE = ("macro_density", "macro_normal_stress", "density_mean", "pressure_mean", "temperature_mean",
             "temperature_std", "velocity_y_std")


def _sensitivity_groups(outcomes):
    """param -> [outcome per value, in the plan's order]."""
    groups = {}
    for o in outcomes:
        groups.setdefault(o.series.info["param"], []).append(o)
    return groups


def sensitivity_section(report, outcomes, failures):
    """Section 3: each numerical parameter varied from its default, the settings that failed."""
    text = report.text
    r = report.plan.void_radius
    h = report.plan.sensitivity_cell
    series = (outcomes or failures)[0].series
    delta = series.info["delta"]
    # the defaults each parameter is varied from: the series' scene as the simulator resolves it
    # without the varied key (automatic cfl and av_linear included)
    defaults = report.study.resolve(report.study.out / series.part / series.name / "study.scene", series.overrides)
    cfls = report.plan.sensitivity_cfl
    chunks = [text("sensitivity", delta=f"{delta:g}", h=h_text(h), ratio=f"{r / h:g}",
                   seeds=report.plan.sensitivity_seeds, finest=h_text(report.plan.porous_cells[-1]),
                   shape=defaults["shape_function"], av_linear=f"{defaults['av_linear']:g}",
                   av_quadratic=f"{defaults['av_quadratic']:g}", cfl=f"{defaults['cfl']:g}",
                   flip_fraction=f"{defaults['flip_fraction']:g}", min_cfl=f"{min(cfls):g}",
                   min_cfl_cost=f"{defaults['cfl'] / min(cfls):g}")]
    for param, group in _sensitivity_groups(outcomes).items():
        chunks.append(_parameter(report, param, group, delta, r / h))
    if failures:
        chunks.append(_failed_settings(report, failures))
    if outcomes:
        chunks.append(text("sensitivity.figure",
                           figure=report.figure("sensitivity", figure_sensitivity, _sensitivity_groups(outcomes))))
    report.sections.append(chunks)


def _parameter(report, param, group, delta, ratio):
    """One parameter's table (the default setting first marked), with its findings."""
    info = group[0].series.info
    values = [o.series.info["value"] for o in group]
    k0 = min(range(len(values)), key=lambda k: abs(values[k] - info["default"]))
    base_o = group[k0]
    spread = {}
    for q in SENSITIVE:
        per_seed = [plateau(p, q, base_o.series.window) for p in base_o.run_dirs[0]]
        spread[q] = 0.5 * (max(per_seed) - min(per_seed))
    rows = []
    for k, o in enumerate(group):
        row = [f"{values[k]:g}" + (" (default)" if k == k0 else "")]
        for q in SENSITIVE:
            v, base = o.value(q, 0), base_o.value(q, 0)
            change = "" if k == k0 else (f" ({100 * (v - base) / abs(base):+.1f} %)" if RELATIVE[q]
                                         else f" ({v - base:+.1f})")
            row.append(unit_value(q, v) + change)
        row += [f"{o.wall(0):.1f}", f"{o.point_steps(0):.3g}", o.summaries[0][0]["steps"],
                f"{max(abs(s['energy_error']) for s in o.summaries[0]):.1e}"]
        rows.append(row)
    rows.append(["layout spread", *(unit_value(q, spread[q], 2) for q in SENSITIVE), "", "", "", ""])
    energy = {values[k]: max(abs(x["energy_error"]) for x in o.summaries[0]) for k, o in enumerate(group)}
    leaky = {v: e for v, e in energy.items() if e > 1e-6}
    if leaky:
        report.find("sensitivity.energy", label=info["label"],
                    settings=", ".join(f"{v:g} (relative error {e:.1e})" for v, e in leaky.items()),
                    default=f"{energy[values[k0]]:.0e}")
    if len(group) > 1:
        _parameter_finding(report, group, k0, values, delta, ratio)
    table = md_table([info["label"], *(f"{q} ({unit_of(q)})" for q in SENSITIVE),
                      "wall (s, all layouts)", "point-steps (all layouts)", "steps", "energy error (largest)"], rows)
    scaled = ""
    if param == "av":
        base = Run(base_o.run_dirs[0][0]).scene
        scaled = " " + report.text("sensitivity.av_scaled", av_linear=f"{base['av_linear']:g}",
                                   av_quadratic=f"{base['av_quadratic']:g}")
    return report.text("sensitivity.parameter", label=info["label"], scaled=scaled, table=table)


def _parameter_finding(report, group, k0, values, delta, ratio):
    """The same layouts run at every setting, so a change that every layout shows with one sign, and
    that grows monotonically along the parameter, is the setting's; the layout spread is the scale of
    what another choice of layouts would move."""
    effects = []
    for q in ("macro_normal_stress", "pressure_mean", "temperature_mean", "temperature_std", "velocity_y_std"):
        per_layout = {k: [plateau(p, q, group[k].series.window) for p in group[k].run_dirs[0]]
                      for k in range(len(group))}
        base = per_layout[k0]
        far = max((k for k in range(len(group)) if k != k0),
                  key=lambda k: abs(np.mean(per_layout[k]) - np.mean(base)))
        diffs = [a - b for a, b in zip(per_layout[far], base)]
        change = float(np.mean(diffs))
        means = [np.mean(per_layout[k]) for k in range(len(group))]
        steps = np.diff(means)
        monotone = bool(np.all(steps > 0) or np.all(steps < 0))
        agree = all(d * change > 0 for d in diffs)
        size = 100 * change / abs(np.mean(base)) if RELATIVE[q] else change
        effects.append(report.text("finding.sensitivity.effect", quantity=q, value=f"{values[far]:g}",
                                   change=f"{size:+.1f} %" if RELATIVE[q] else f"{size:+.0f} {unit_of(q)}",
                                   agreement=report.text("phrase.same_sign" if agree else "phrase.signs_differ"),
                                   trend=report.text("phrase.monotone") if monotone else ""))
    report.find("sensitivity", label=group[0].series.info["label"], delta=f"{delta:g}", ratio=f"{ratio:g}",
                first=f"{values[0]:g}", last=f"{values[-1]:g}", effects="; ".join(effects))


def _failed_settings(report, failures):
    """The settings with a layout that stopped: what their finished layouts measured, and why."""
    rows = []
    for f in failures:
        for run_dir in sorted((report.study.out / f.series.part / f.series.name).glob("level_0*")):
            try:
                summary = Run(run_dir).summary()
            except PostError:
                continue
            finished = summary.get("exit_code") == 0
            values = ([unit_value(q, plateau(run_dir, q, f.series.window)) for q in SENSITIVE] if finished
                      else ["-"] * len(SENSITIVE))
            rows.append([f"{f.series.info['label']} = {f.series.info['value']:g}", run_dir.name.split("seed_")[-1],
                         summary.get("exit_code"), f"{summary.get('end_time', math.nan) / NS:.3g} ns",
                         summary.get("steps"), *values])
    table = md_table(["setting", "seed", "exit code", "reached", "steps",
                      *(f"{q} ({unit_of(q)})" for q in SENSITIVE)], rows)
    items = []
    for f in failures:
        message = f.message.splitlines()
        detail = next((line for line in message if "stopped" in line or "error" in line),
                      message[-1] if message else "")
        setting = dict(label=f.series.info["label"], value=f"{f.series.info['value']:g}", detail=detail.strip())
        items.append(report.text("sensitivity.failure", **setting))
        report.find("sensitivity.failure", **setting)
    return report.text("sensitivity.failures", table=table, list="\n".join(items))


# --- part 4: the answer --------------------------------------------------------------------------------

class CostModel:
    """Points and steps of configs/paper_base.scene at a cell size: --check's points and step lower
    bound, times the ratio of actual to lower-bound steps of the reduced runs, times the anchor's
    excess (the full run to its end_time against that ratio's prediction)."""

    def __init__(self, checks, ratio, anchor_factor, rate, threads):
        self.checks, self.ratio, self.anchor_factor = checks, ratio, anchor_factor
        self.rate, self.threads = rate, threads

    def __call__(self, h, corrected=True):
        checks, ratio = self.checks, self.ratio
        match = next((c for c in checks if abs(c - h) <= 1e-9 * h), None)
        if match is not None:
            points, lower, how = *checks[match], "--check"
        else:
            ref = min(checks)
            points, lower = checks[ref][0] * (ref / h) ** 2, checks[ref][1] * (ref / h)
            how = f"--check at {h_text(ref)} scaled by h^-2 (points) and h^-1 (steps)"
        near = min(ratio, key=lambda c: abs(math.log(c / h)))
        steps = lower * ratio[near] * (self.anchor_factor if corrected else 1.0)
        point_steps = points * steps
        return dict(h=h, points=points, lower=lower, ratio=ratio[near], steps=steps, point_steps=point_steps,
                    core_minutes=self.threads * point_steps / self.rate / 60.0, how=how)


def answer_section(report, o, anchor):
    """Section 4, and the table at the top of the document (report.answer): the cell size and
    core-minutes the paper's geometry needs for each target error."""
    study, plan, text = report.study, report.plan, report.text
    info = o.series.info
    r = info["void_radius"]
    paper = info["paper"]   # the resolved configs/paper_base.scene
    reduced_path = study.out / "answer" / o.series.name / "study.scene"
    checks = {h: study.check(PAPER_SCENE, h) for h in plan.answer_check_cells}
    reduced_checks = {h: study.check(reduced_path, h, o.series.overrides) for h in o.h}
    ratio = {h: float(np.mean([s["steps"] for s in o.summaries[k]])) / reduced_checks[h][1] for k, h in enumerate(o.h)}
    rate, threads, fewer, rate_runs, quartiles = study_rate(study, o)

    # The full run goes on to 1.2 us, past the reflections: the anchor (the full geometry at the
    # coarsest cell) measures how many more steps that takes than the reduced runs' ratio predicts.
    anchor_factor = 1.0
    if anchor is not None:
        h0 = float(anchor.scene["cell_size"])
        lower0 = checks[min(checks, key=lambda c: abs(math.log(c / h0)))][1]
        ratio0 = ratio[min(ratio, key=lambda c: abs(math.log(c / h0)))]
        anchor_factor = anchor.summary()["steps"] / (lower0 * ratio0)
    full_cost = CostModel(checks, ratio, anchor_factor, rate, threads)

    table = _answer_table(o, full_cost, paper["width"], threads)
    full_end = f"{paper['end_time'] / 1e-6:g} us"
    shape = o.series.scene["shape_function"]
    report.answer = text("the_answer", table=table, width=h_text(plan.answer_width), shape=shape,
                         height_mm=f"{plan.answer_height * 1e3:g}", end_ns=f"{plan.answer_end / NS:g}",
                         seeds=o.series.seeds, full_width=f"{paper['width'] / 1e-3:g} mm",
                         full_height=f"{paper['target_height'] / 1e-3:g} mm", full_end=full_end, rate=f"{rate:.3g}",
                         rate_runs=rate_runs, large_run=f"{LARGE_RUN:.0e}", lower_quartile=f"{quartiles[0]:.3g}",
                         upper_quartile=f"{quartiles[1]:.3g}", threads=threads, fewer_percent=f"{100 * fewer:.0f}")

    full_voids = study.voids_per_body(PAPER_SCENE, plan.answer_check_cells[0])
    anchoring = (text("answer.anchored", factor=f"{anchor_factor:.3g}") if anchor is not None
                 else text("answer.unanchored"))
    chunks = [text("answer", delta=f"{info['delta']:g}", r=h_text(r), velocity=f"{info['velocity']:g}", shape=shape,
                   cfl=_values_of([o], "cfl"), av_linear=_values_of([o], "av_linear"),
                   width=h_text(plan.answer_width), height_mm=f"{plan.answer_height * 1e3:g}",
                   end_ns=f"{plan.answer_end / NS:g}", cells=cells_text(o.h), seeds=o.series.seeds,
                   band=o.series.scene["region." + REGION], window=_window_text(o.series),
                   voids=f"{np.mean([s['voids'] for s in o.summaries[-1]]) / 2:.1f}",
                   full_voids=(text("answer.full_voids", count=full_voids) if full_voids is not None
                               else text("answer.more_voids")),
                   table=_answer_convergence(o), cost_table=_cost_model_table(checks, full_cost),
                   ratios=", ".join(f"{ratio[h]:.2f}x" for h in o.h), full_end=full_end, anchoring=anchoring)]
    if anchor is not None:
        chunks.append(_anchor_check(report, o, anchor, full_cost))
    chunks.append(text("answer.figure", figure=report.figure("answer", figure_answer, o,
                                                             [full_cost(h) for h in sorted(checks)])))
    report.sections.append(chunks)
    report.window_cases.append(("paper base, reduced", o))


def _answer_table(o, full_cost, full_width, threads):
    """Per target error: the cell size, how it was found and its cost in the full geometry."""
    r = o.series.info["void_radius"]
    shape = o.series.scene["shape_function"]
    targets = [("pressure_mean", t, True) for t in (1, 3, 10)] + \
              [("macro_normal_stress", t, True) for t in (1, 3, 10)] + \
              [("temperature_mean", t, False) for t in (10, 50)]
    rows = []
    for q, t, relative in targets:
        res = o.results[q]
        h, err, how = needed_resolution(res, o.h, t / 100.0 if relative else float(t), relative)
        if h is None:
            continue
        h_use = h if how == "measured" else nice_cell(h, full_width)
        cost = full_cost(h_use)
        err_text = (f"{100 * err:.2g} %" if relative else f"{err:.2g} K") if how == "measured" else "= target"
        rows.append([f"{t:g} {'%' if relative else 'K'}", q, f"{h_text(h_use)} (h/r = 1/{r / h_use:.3g})", shape,
                     "2", err_text, how + ("" if how == "measured" else f": h = {h / UM:.2g} um, rounded down to a "
                                                                          "divisor of the width"),
                     f"{cost['points']:.3g}", f"{cost['steps']:.3g}", f"{cost['point_steps']:.2g}",
                     f"{cost['core_minutes']:.3g}", f"{cost['core_minutes'] / threads:.3g}"])
    return md_table(["target", "quantity", "cell size", "shape", "ppc", "estimated error there", "how",
                     "points (full)", "steps (full)", "point-steps", "core-minutes", f"minutes on {threads} cores"],
                    rows)


def _answer_convergence(o):
    """The reduced column's seed means per level, limit, order and errors."""
    rows = []
    for q in QUANTITIES:
        res = o.results[q]
        limit = res.estimate.extrapolated
        rows.append([q, *(f"{unit_value(q, v)} ± {unit_value(q, se, 2)}"
                          for v, se in zip(res.values, res.standard_errors)),
                     unit_value(q, limit), order_text(res.estimate),
                     *(error_text(q, e, limit, signed=False) for e in res.estimate.errors),
                     unit_value(q, o.series.exact[q]) if q in o.series.exact else "-"])
    return md_table(["quantity", *(h_text(h) for h in o.h), "limit", "order",
                     *(f"disc. error {h_text(h)}" for h in o.h), "full compaction"], rows)


def _cost_model_table(checks, full_cost):
    rows = []
    for h in sorted(checks, reverse=True):
        c = full_cost(h)
        rows.append([h_text(h), f"{c['points']:.4g}", f"{c['lower']:.4g}", f"{c['ratio']:.3g}",
                     f"{full_cost(h, corrected=False)['steps']:.4g}", f"{c['steps']:.4g}",
                     f"{c['point_steps']:.3g}", f"{c['core_minutes']:.3g}"])
    return md_table(["cell", "points (--check)", "steps, lower bound (--check)",
                     "actual / lower bound (reduced runs)", "steps from the reduced ratio",
                     f"steps x {full_cost.anchor_factor:.3g} (anchor)", "point-steps", "core-minutes"], rows)


def _anchor_check(report, o, anchor, full_cost):
    """The full geometry's one run against the cost model's prediction and the reduced plateau."""
    s = anchor.summary()
    h0 = float(anchor.scene["cell_size"])
    rate = full_cost.rate
    anchor_values = measure_single(anchor, o.series.window)
    c = full_cost(h0, corrected=False)
    table = md_table(["", "predicted from the reduced runs", "measured"],
                     [["material points", f"{c['points']:.4g}", s["material_points"]],
                      ["steps", f"{c['steps']:.4g}", s["steps"]],
                      ["point-steps", f"{c['point_steps']:.3g}", f"{s['material_points'] * s['steps']:.3g}"],
                      ["wall (s)", f"{c['point_steps'] / rate:.3g}", f"{s['wall_seconds']:.3g}"],
                      ["point-steps/s", f"{rate:.3g}", f"{s['point_steps_per_second']:.3g} on {s['threads']} "
                       f"threads ({s['steps_with_fewer_threads']} of {s['steps']} steps on fewer)"]])
    k0 = 0
    rows = []
    for q in ("pressure_mean", "macro_normal_stress", "temperature_mean", "density_mean", "macro_density"):
        res = o.results[q]
        rows.append([q, f"{unit_value(q, anchor_values[q])}",
                     f"{unit_value(q, res.values[k0])} ± {unit_value(q, res.standard_errors[k0], 2)}"])
    values = md_table(["quantity", f"full geometry, {h_text(h0)}", f"reduced, {h_text(h0)}, layout mean"], rows)
    report.find("answer.anchor", h=h_text(h0), steps=f"{c['steps']:.0f}", seconds=f"{c['point_steps'] / rate:.0f}",
                took_steps=s["steps"], took_seconds=f"{s['wall_seconds']:.0f}",
                rate=f"{s['point_steps_per_second']:.3g}", factor=f"{full_cost.anchor_factor:.2f}")
    return report.text("answer.anchor", h=h_text(h0), table=table, voids=f"{s['voids'] / 2:.0f}", values=values)
