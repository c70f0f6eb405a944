"""paper.comparison (studies/paper): each measurement on a series with a known answer, the rows of
comparison.csv from small synthetic run directories (regions.csv with the simulator's columns), the
csv's header and row order, and missing runs giving 'not run' rows. No simulator run is needed.

    /usr/bin/python3 -m pytest -q tests/python/test_paper_comparison.py
"""

import csv
import json

import h5py
import numpy as np
import pytest

from paper import comparison as pc
from paper import measures as pm
from paper import rows as pr

REGION_COLUMNS = ("count", "density_mean", "density_std", "pressure_mean", "pressure_std", "temperature_mean",
                  "temperature_std", "velocity_x_mean", "velocity_x_std", "velocity_y_mean", "velocity_y_std",
                  "rot2_mean", "div2_mean", "strain_rate2_mean", "macro_density", "macro_pressure",
                  "macro_normal_stress")
REGIONS = {"B800": "bottom 1e-04 m 8e-04 m", "B400": "bottom 1e-04 m 4e-04 m", "B100": "bottom 1e-04 m 1e-04 m",
           "T800": "top 8e-04 m", "T400": "top 4e-04 m", "T100": "top 1e-04 m"}
T = np.arange(0.0, 1201.0, 10.0)  # ns
ARRIVAL = 805.0                   # ns: where the synthetic top's u_y crosses 0
SURFACE_VELOCITY = 877.0          # m/s


# --- synthetic runs -----------------------------------------------------------------------------------

def scene_text(velocity=1000.0, porosity=1.03, void_radius=50e-6, cell_size=20e-6, regions=REGIONS):
    lines = [f"velocity = {velocity} m/s", f"porosity = {porosity}", f"void_radius = {void_radius} m",
             f"cell_size = {cell_size} m", "width = 5e-04 m", "target_height = 0.005 m", "shape_function = bspline2",
             "density = 2700 kg/m3", "sound_speed = 5350 m/s", "hugoniot_slope = 1.34", "gruneisen_gamma = 1.96",
             "specific_heat = 880 J/(kg K)", "initial_temperature = 300 K", "youngs_modulus = 6.9e+10 Pa",
             "poisson_ratio = 0.33"]
    lines += [f"region.{name} = {spec}" for name, spec in regions.items()]
    return "\n".join(lines) + "\n"


def write_run(path, series, scene=None, summary=True):
    """A run directory: scene.txt, summary.json and regions.csv from {region: {column: array in SI}}
    (columns not given are 0, count is 100)."""
    path.mkdir(parents=True)
    (path / "scene.txt").write_text(scene or scene_text())
    if summary:
        (path / "summary.json").write_text(json.dumps({"exit_code": 0}))
    with open(path / "regions.csv", "w", newline="") as f:
        writer = csv.writer(f, lineterminator="\n")
        writer.writerow(("time", "region") + REGION_COLUMNS)
        for i, t in enumerate(T):
            for region, columns in series.items():
                values = [repr(float(columns.get(c, np.zeros(T.size))[i])) for c in REGION_COLUMNS[1:]]
                writer.writerow([repr(t * 1e-9), region, 100] + values)
    return path


def write_snapshot(run_dir, index, time_ns, position, fields):
    """snapshot_NNNNN.h5 with the target's points (body 1): position (N x 2, m) and 1-D or N x 2 fields
    (SI), the run's scene as its 'scene' attribute."""
    with h5py.File(run_dir / f"snapshot_{index:05d}.h5", "w") as f:
        f.attrs["time"] = time_ns * 1e-9
        f.attrs["step"] = index
        f.attrs["scene"] = (run_dir / "scene.txt").read_text()
        particles = f.create_group("particles")
        particles["id"] = np.arange(len(position))
        particles["body"] = np.ones(len(position), dtype=np.int32)
        particles["position"] = position
        for name, values in fields.items():
            particles[name] = values


def lattice(x_max_um, y_min_um, y_max_um, spacing_um=10.0):
    x, y = np.meshgrid(np.arange(0.0, x_max_um, spacing_um), np.arange(y_min_um, y_max_um + 1e-9, spacing_um))
    return np.column_stack([x.ravel(), y.ravel()]) * 1e-6


def base_snapshots(run_dir):
    """250 ns: pressure 16 GPa below a front at 1305 + 50 sin(2 pi x / 500 um) um (highest point of
    the 10 um lattice under it: 1350 um); 1150 ns: a flat top
    at 4200 um with one jet of points reaching 4260 um."""
    body = lattice(500.0, 0.0, 2000.0)
    front = 1305e-6 + 50e-6 * np.sin(2 * np.pi * body[:, 0] / 500e-6)
    write_snapshot(run_dir, 0, 250.0, body, {"pressure": np.where(body[:, 1] <= front, 16e9, 0.0)})
    top = lattice(500.0, 3000.0, 4200.0)
    jet = np.column_stack([np.full(6, 110e-6), np.arange(4210.0, 4261.0, 10.0) * 1e-6])
    position = np.vstack([top, jet])
    write_snapshot(run_dir, 1, 1150.0, position, {"pressure": np.zeros(len(position))})


def porous_snapshots(run_dir):
    """1200, 1250, 1300 ns: B800 points whose density follows an exponential distribution (skewness
    2, excess kurtosis 6) and whose velocities are Gaussian; the temperature's spread grows with time."""
    position = lattice(200.0, 110.0, 890.0, spacing_um=2.0)
    n = len(position)
    rng = np.random.default_rng(1)
    exponential = -np.log(1.0 - (np.arange(n) + 0.5) / n)
    for index, time in enumerate((1200.0, 1250.0, 1300.0)):
        write_snapshot(run_dir, index, time, position, {
            "density": 2800.0 + 50.0 * exponential, "pressure": 6e9 + 1e9 * exponential,
            "temperature": 800.0 + (100.0 + time - 1200.0) * exponential, "velocity": rng.normal(0.0, 100.0, (n, 2))})


def rise_and_settle(t, start, peak, settled, t_peak=250.0, dip_at=450.0, dip=0.0):
    """Linear rise to `peak` at t_peak, then a relaxation to `settled` (tau 100 ns), with an optional
    Gaussian dip of depth `dip` at dip_at."""
    rising = start + (peak - start) * t / t_peak
    after = settled + (peak - settled) * np.exp(-(t - t_peak) / 100.0)
    return np.where(t <= t_peak, rising, after) - dip * np.exp(-0.5 * ((t - dip_at) / 20.0) ** 2)


def decaying_std(t, peak, steady, tau=80.0, t_peak=100.0):
    return np.where(t <= t_peak, peak * t / t_peak, steady + (peak - steady) * np.exp(-(t - t_peak) / tau))


def base_series(temperature_offset=0.0):
    """The base case's regions with the paper's Fig. 2 features built in (SI units)."""
    bottom = {
        "density_mean": 1e3 * rise_and_settle(T, 2.7, 3.14, 3.13, dip=0.03),
        "pressure_mean": 1e9 * rise_and_settle(T, 0.0, 16.7, 16.0, dip=1.0),
        "temperature_mean": rise_and_settle(T, 300.0, 432.0, 425.0) + 0.01 * np.maximum(T - 250.0, 0.0)
        + temperature_offset,
        "velocity_y_mean": np.where(T <= 250, -1000 * (1 - T / 250), 0.0),
        "rot2_mean": 1e18 * decaying_std(T, 1e-5, 1e-7, tau=70.0),
        "div2_mean": 1e18 * decaying_std(T, 3e-5, 1.2e-7, tau=40.0),
        "strain_rate2_mean": 1e18 * decaying_std(T, 4e-5, 1.1e-7, tau=45.0),
        "macro_density": 1e3 * rise_and_settle(T, 2.62, 3.12, 3.12),
        "macro_normal_stress": 1e9 * rise_and_settle(T, 0.0, 16.5, 16.3),
    }
    bottom.update({f"{q}_std": decaying_std(T, peak, peak / 5) for q, peak in
                   (("density", 200.0), ("pressure", 8e9), ("temperature", 150.0), ("velocity_x", 150.0),
                    ("velocity_y", 500.0))})
    series = {}
    for name, scale in (("B800", 1.0), ("B400", 0.8), ("B100", 0.5)):
        series[name] = dict(bottom)
        series[name].update({f"{q}_std": bottom[f"{q}_std"] * scale
                             for q in ("density", "pressure", "temperature", "velocity_x", "velocity_y")})
    released = T > ARRIVAL
    top = {"density_mean": np.where(released, 2710.0, 2700.0),
           "pressure_mean": np.where(released, 0.05e9, 0.0),
           "temperature_mean": np.where(released, 360.0 + 0.02 * (T - ARRIVAL), 300.0) + temperature_offset,
           "macro_density": np.where(released, 2660.0, 2650.0),
           "velocity_y_mean": np.interp(T, [0, ARRIVAL - 15, ARRIVAL + 15, 1200],
                                        [-1000, -1000, 1000, 1000]).clip(max=SURFACE_VELOCITY)}
    for name in ("T800", "T400", "T100"):
        series[name] = dict(top)
    series["T100"]["density_mean"] = top["density_mean"] + np.where(T > 900, 5.0 * np.sin(2 * np.pi * T / 30.0), 0)
    return series


def porous_series(slope_density, slope_temperature):
    """A delta 1.4-like B800: first maximum at 300 ns, then straight lines (per us) to 1200 ns."""
    after = (T - 300.0) * 1e-3
    rho = np.where(T <= 300, 2700 + 300 * T / 300, 3000 + 1e3 * slope_density * after)
    temperature = np.where(T <= 300, 300 + 300 * T / 300, 600 + slope_temperature * after)
    bottom = {"density_mean": rho, "temperature_mean": temperature, "pressure_mean": (rho - 2700) * 4e7,
              "macro_density": rho - 100, "macro_normal_stress": (rho - 2700) * 4e7}
    top = {"velocity_y_mean": np.full(T.size, -1000.0)}
    return {"B800": bottom, "T800": top}


def by_quantity(rows):
    return {row["quantity"]: row for row in rows}


# --- measurements with known answers -----------------------------------------------------------------

def test_first_maximum_of_a_rise_and_fall():
    y = rise_and_settle(T, 2.7, 3.14, 3.0)  # the 3-sample smoothing keeps this peak at 250 ns
    assert pm.first_maximum(T, y) == (250.0, pytest.approx(3.14))


def test_first_maximum_skips_noise_on_the_way_up():
    y = rise_and_settle(T, 0.0, 10.0, 5.0) + np.where(T == 100.0, 0.5, 0.0)  # a bump at 40 % of the rise
    assert pm.first_maximum(T, y)[0] == 250.0


def test_first_maximum_of_a_series_still_rising():
    with pytest.raises(pm.NotMeasured):
        pm.first_maximum(T, T * 2.0)


def test_exponential_decay_recovers_the_time_constant():
    decay = pm.exponential_decay(T, decaying_std(T, 5.0, 1.0, tau=80.0), 1200.0)
    assert decay.t_peak == 100.0
    assert decay.tau == pytest.approx(80.0, rel=1e-3)
    assert decay.steady == pytest.approx(1.0, rel=0.01)
    assert decay.r2 > 0.999


def test_exponential_decay_needs_a_decay():
    with pytest.raises(pm.NotMeasured):
        pm.exponential_decay(T, 1.0 + 0.001 * T, 1200.0)


def test_rise_end_and_its_straight_line():
    y = np.minimum(T, 150.0) * 0.01
    t_end, r2 = pm.rise_end(T, y, 1200.0)
    assert 150.0 <= t_end <= 160.0
    assert r2 > 0.99


def test_deepest_dip_between_two_times():
    y = 5.0 - 0.3 * np.exp(-0.5 * ((T - 450.0) / 20.0) ** 2) - 0.1 * np.exp(-0.5 * ((T - 800.0) / 20.0) ** 2)
    t_dip, value = pm.deepest_dip(T, y, 250.0, 700.0)
    assert t_dip == 450.0 and value < 4.8
    with pytest.raises(pm.NotMeasured):
        pm.deepest_dip(T, np.ones_like(T), 250.0, 700.0)


def test_trend_slope_per_microsecond_and_fluctuation():
    fit = pm.trend(T, 3.0 + 0.002 * T + 0.01 * np.sin(T), 600.0, 1200.0)
    assert fit.slope == pytest.approx(2.0, rel=0.01)   # 0.002 per ns = 2 per us
    assert fit.fluctuation == pytest.approx(0.01 / np.sqrt(2), rel=0.1)
    with pytest.raises(pm.NotMeasured):
        pm.trend(T, T, 600.0, 650.0)  # shorter than MIN_WINDOW


def ar1_noise(rng, size, rho, sigma):
    """AR(1) noise of lag-1 correlation rho and stationary standard deviation sigma."""
    e = np.empty(size)
    e[0] = rng.normal(0.0, sigma)
    for i in range(1, size):
        e[i] = rho * e[i - 1] + rng.normal(0.0, sigma * np.sqrt(1.0 - rho ** 2))
    return e


@pytest.mark.parametrize("rho", [0.0, 0.8])
def test_slope_standard_error_matches_the_scatter_of_slopes(rho):
    """Over 400 noisy copies of one line, the mean standard error a single fit reports is the scatter
    of the fitted slopes; for correlated noise (rho 0.8) the ordinary error alone would be about 3
    times too small, so this fails without the autocorrelation factor."""
    rng = np.random.default_rng(7)
    t = np.arange(300.0, 1300.0, 10.0)
    slopes, errors, ordinary = [], [], []
    for _ in range(400):
        y = 3.0 - 0.01e-3 * t + ar1_noise(rng, t.size, rho, 0.01)
        fit = pm.trend(t, y, 300.0, 1290.0)
        slopes.append(fit.slope)
        errors.append(fit.slope_se)
        residual = y - np.polyval(np.polyfit(t, y, 1), t)
        ordinary.append(1e3 * np.sqrt(np.sum(residual ** 2) / (t.size - 2) / np.sum((t - t.mean()) ** 2)))
    assert np.mean(slopes) == pytest.approx(-0.01, abs=3 * np.std(slopes) / np.sqrt(400))
    assert np.mean(errors) == pytest.approx(np.std(slopes), rel=0.2)
    if rho > 0:
        assert np.mean(ordinary) < 0.5 * np.std(slopes)


def test_slope_standard_error_of_a_line_and_of_too_few_samples():
    assert pm.slope_standard_error([0.0, 1.0], [0.1, -0.1]) == 0.0
    assert pm.slope_standard_error(T, np.zeros_like(T)) == 0.0


def test_a_slope_within_two_standard_errors_is_not_distinguishable_from_zero():
    assert not pm.Trend(0.0, 1.0, -0.008, 0.5, 3.0, 0.01, slope_se=0.0055).distinguishable_from_zero
    assert pm.Trend(0.0, 1.0, -0.012, 0.5, 3.0, 0.01, slope_se=0.0055).distinguishable_from_zero


def test_separation_of_a_studys_slopes():
    from paper.rows_studies import separation_text
    fits = [pm.Trend(0.0, 1.0, slope, 0.5, 3.0, 0.01, slope_se=1.0) for slope in (0.0, 2.0, 4.0, 9.0)]
    # neighbours 2, 2 and 5 apart against 2 sqrt(2) = 2.83; first to last 9 / sqrt(2) = 6.4
    assert separation_text(fits) == ("1 of 3 neighbouring slopes differ by more than 2 combined standard "
                                     "errors, the first and the last by 6.4")
    assert separation_text(fits[:2]) == "the two slopes differ by 1.4 combined standard errors"
    assert separation_text(fits[:1]) == "one slope alone"


def test_a_fall_within_the_noise_agrees_in_sign_only(tmp_path):
    """Fig. 9's 'density decreases' on a delta 1.4 run whose fall is small beside correlated noise."""
    rng = np.random.default_rng(2)
    series = porous_series(-0.002, 40.0)
    after = T > 300.0
    series["B800"]["density_mean"] = series["B800"]["density_mean"] + np.where(after, ar1_noise(rng, T.size, 0.9, 20.0),
                                                                               0.0)
    write_run(tmp_path / "delta1.4", series, scene_text(velocity=1000.0, porosity=1.4, void_radius=10e-6,
                                                        cell_size=5e-6, regions={"B800": REGIONS["B800"],
                                                                                 "T800": REGIONS["T800"]}))
    row = by_quantity(pc.comparison_rows(tmp_path))["delta 1.4: B800 density decreases after the initial stage"]
    assert " +- " in row["mpmshock"]
    slope, error = (float(x) for x in row["mpmshock"].split(": ")[1].split(" g/cm3")[0].split(" +- "))
    assert -2 * error < slope < 0  # this seed's noise leaves the fall negative but within the noise
    assert row["note"].startswith("agree in sign only (the slope lies within 2 standard errors of zero)")


def test_oscillation_ignores_slow_trends():
    slow = 2.7 + 1e-4 * T
    fast = slow + 0.005 * np.sin(2 * np.pi * T / 30.0)
    assert pm.oscillation(T, slow, 900.0, 1200.0) < 1e-6
    assert pm.oscillation(T, fast, 900.0, 1200.0) > 1e-3


def test_upward_crossing_interpolates():
    assert pm.upward_crossing(T, T - 805.0, 0.0) == pytest.approx(805.0)


def test_running_mean_ends():
    assert pm.smooth3(np.array([0.0, 3.0, 6.0, 9.0])).tolist() == [1.5, 3.0, 6.0, 7.5]


def test_column_heights_per_bin_across_the_periodic_width():
    x = np.array([5.0, 15.0, 15.0, 25.0, 105.0]) * 1e-6   # 105 um wraps to 5 um in a 100 um column
    y = np.array([1.0, 2.0, 3.0, 4.0, 7.0])
    assert pm.column_heights(x, y, 100e-6, 10e-6).tolist() == [7.0, 3.0, 4.0]


def test_number_verdicts():
    assert pr.number_verdict(3.15, 3.14, 0.005, "").startswith("agree (+0.32 %")
    assert pr.number_verdict(986.0, 877.0, 0.05, "").startswith("differ (+12 %")
    assert pr.number_verdict(470.0, 432.0, 15.0, "K", relative=False).startswith("differ (+38 K")


def test_accuracy_at_nearest_level_and_coarser_runs():
    assert pm.accuracy_at(1.03, 2.5).pressure == pytest.approx(0.048)
    assert pm.accuracy_at(1.01, 5.0).temperature == pytest.approx(7.1)   # nearest studied porosity: 1.03
    coarse = pm.accuracy_at(1.4, 1.0)
    assert coarse.density == pytest.approx(0.028) and "coarser than any level" in coarse.text
    assert "1000 m/s" not in coarse.text
    fast = pm.accuracy_at(1.4, 2.0, velocity=2000.0)
    assert fast.pressure == pytest.approx(0.405) and fast.text.endswith(
        "(estimated at 1000 m/s; this run is at 2000 m/s)")


# --- rows from synthetic runs ---------------------------------------------------------------------------

@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    root = tmp_path_factory.mktemp("runs")
    base_snapshots(write_run(root / "base", base_series()))
    write_run(root / "base-paperT", base_series(temperature_offset=-100.0))
    for case, v, rho_slope, t_slope in (("delta1.4", 1000.0, -0.05, 40.0), ("delta1.4_v1500", 1500.0, -0.1, 80.0),
                                        ("delta1.4_v2000", 2000.0, -0.2, 120.0)):
        write_run(root / case, porous_series(rho_slope, t_slope),
                  scene_text(velocity=v, porosity=1.4, void_radius=10e-6, cell_size=5e-6,
                             regions={"B800": REGIONS["B800"], "T800": REGIONS["T800"]}))
    porous_snapshots(root / "delta1.4")
    write_run(root / "void_r25", base_series(), summary=False)  # an interrupted run
    return root


@pytest.fixture(scope="module")
def rows(runs):
    return pc.comparison_rows(runs)


def test_first_maximum_rows_read_the_papers_numbers(rows):
    table = by_quantity(rows)
    density = table["B800 first maximum of mean density"]
    assert (density["paper"], density["unit"]) == ("3.14", "g/cm3")
    assert float(density["mpmshock"]) == pytest.approx(3.14, rel=1e-3)
    assert density["note"].startswith("agree")
    assert float(table["B800 first maximum of mean pressure"]["mpmshock"]) == pytest.approx(16.7, rel=1e-3)
    assert float(table["B800 time of the first maximum of mean density"]["mpmshock"]) == 250.0


def test_both_temperature_models_get_their_own_rows(rows):
    table = by_quantity(rows)
    energy = table["B800 first maximum of mean temperature (energy T)"]
    paper = table["B800 first maximum of mean temperature (paper T)"]
    assert float(energy["mpmshock"]) > float(paper["mpmshock"])  # the paperT run is 100 K cooler
    assert float(table["T800 temperature left above the initial after release (energy T)"]["mpmshock"]) == \
        pytest.approx(60.0 + 0.02 * (1150.0 - ARRIVAL), abs=1.0)


def test_top_arrival_and_surface_velocity_from_the_thinnest_top_region(rows):
    table = by_quantity(rows)
    arrival = table["shock arrives at the top free surface"]
    assert float(arrival["mpmshock"]) == pytest.approx(ARRIVAL, abs=1.0)
    assert "region T100" in arrival["note"] and arrival["note"].startswith("agree")
    velocity = table["top free surface moves up during unloading (simulation frame)"]
    assert float(velocity["mpmshock"]) == pytest.approx(SURFACE_VELOCITY, rel=1e-3)
    assert "simulation frame" in velocity["note"]


def test_decay_rows_give_tau_and_r2(rows):
    row = by_quantity(rows)["B800 std of density rises fast, then decays nearly exponentially"]
    assert row["mpmshock"].startswith("yes") and "tau 80 ns" in row["mpmshock"]
    larger = by_quantity(rows)["larger measured domains give larger std in the transient"]
    assert larger["mpmshock"].startswith("yes for 5 of 5")


def test_dip_and_t100_oscillations(rows):
    table = by_quantity(rows)
    assert float(table["time of the dip (concave) in B800 density and pressure"]["mpmshock"]) == 450.0
    assert table["evident oscillations in T100 density after 900 ns"]["mpmshock"].startswith("yes")


def test_shock_strength_study_with_a_missing_speed(rows):
    row = by_quantity(rows)["delta 1.4: density decreases faster with a stronger shock"]
    assert row["mpmshock"].startswith("yes")
    assert "-0.05 +- " in row["mpmshock"] and "-0.2 +- " in row["mpmshock"] and "at 2000 m/s" in row["mpmshock"]
    # exact lines: every slope is apart from its neighbours far beyond their (round-off) errors
    assert "2 of 2 neighbouring slopes differ by more than 2 combined standard errors" in row["note"]
    assert "not run: delta1.4_v500" in row["note"]
    temperature = by_quantity(rows)["delta 1.4: temperature increases faster with a stronger shock (energy T)"]
    assert temperature["mpmshock"].startswith("yes") and "+40" in temperature["mpmshock"]


def test_front_and_jets_from_snapshots(rows):
    table = by_quantity(rows)
    front = table["shock front passed the B800 downstream boundary at 250 ns"]
    assert front["mpmshock"] == "yes: front at 1350 um"
    jets = table["jetting at the upper free surface at 1150 ns"]
    assert jets["mpmshock"] == "yes: highest jet 60 um above the median surface"


def test_distributions_from_snapshots(rows):
    table = by_quantity(rows)
    density = table["delta 1.4: distribution of density non-Gaussian"]["mpmshock"]
    assert density.startswith("yes: skewness 2.0") and "excess kurtosis 5.9" in density
    u_x = table["delta 1.4: distribution of u_x non-Gaussian"]["mpmshock"]
    assert u_x.startswith("no")
    assert table["delta 1.4: the distributions vary with time"]["mpmshock"] == "yes: temperature change"


def test_missing_and_incomplete_runs_give_not_run(rows):
    table = by_quantity(rows)
    missing = table["delta 1.4: distribution of temperature (paper T) non-Gaussian"]
    assert missing["mpmshock"] == "" and missing["note"] == "not run: delta1.4-paperT"
    porosity = table["small porosity: density decrease rate grows with porosity"]
    assert porosity["mpmshock"] == "" and porosity["note"].startswith("not run: delta1.01")
    void = table["larger voids give a higher mean temperature (energy T)"]
    assert void["mpmshock"] == "" and "void_r25 (incomplete: no summary.json)" in void["note"]


def test_a_measurement_the_run_cannot_give(runs):
    def too_short(run):
        raise pm.NotMeasured("the run ends too soon")
    row = pr.measured_row(pm.Campaign(runs), "Fig 2", "a claim", "yes", "", ["base"], too_short)
    assert row["mpmshock"] == "" and row["note"].startswith("not measured (base: h 20 um")
    assert row["note"].endswith("the run ends too soon")


def test_an_empty_directory_gives_every_row_not_run(tmp_path):
    rows = pc.comparison_rows(tmp_path)
    measured = [row for row in rows if not row["quantity"].startswith("theory") and row["figure"] != "Fig 6"]
    assert measured and all(row["mpmshock"] == "" and row["note"].startswith("not run") for row in measured)
    assert [row["quantity"] for row in rows] == [row["quantity"] for row in pc.comparison_rows(tmp_path, quick=True)]


def test_rows_in_figure_order_with_the_columns(rows):
    numbers = [int(row["figure"].split()[1]) for row in rows]
    assert numbers == sorted(numbers) and set(numbers) == set(range(1, 14))
    assert all(tuple(row) == pc.COLUMNS for row in rows)
    assert len({row["quantity"] for row in rows}) == len(rows)


def test_theory_rows(rows):
    table = by_quantity(rows)
    t_h = table["theory: T_H of the solid at the paper's 3.14 g/cm3 (the least T of the paper's model there)"]
    assert float(t_h["mpmshock"]) == pytest.approx(462.7, abs=0.1) and t_h["paper"] == "432"
    assert float(table["theory: full-compaction porous Hugoniot density (delta 1.4, 1000 m/s)"]["mpmshock"]) == \
        pytest.approx(2.8175, abs=1e-3)


def test_every_shock_study_case_has_its_hugoniot_rows(rows, runs):
    """Fig. 12 and 13 give the full-compaction porous Hugoniot of each case's own shock (computed here
    with porous_shock at the scene's velocity and porosity), against its B800 late mean where the
    case ran: delta1.4_v2000's synthetic macro_density averages 3000 - 200 * 0.75 - 100 = 2750 kg/m3 over
    the late window 900-1200 ns."""
    from mpmshock_post.hugoniot import porous_shock
    from paper.rows_studies import CASE_SHOCKS
    table = by_quantity(rows)
    material = pm.CaseRun("base", runs / "base").material
    for case, (velocity, porosity) in CASE_SHOCKS.items():
        state = porous_shock(velocity, porosity, material)
        label = f"(delta {porosity:g}, {velocity:.0f} m/s)"
        density = table[f"theory: full-compaction porous Hugoniot density {label}"]
        assert float(density["mpmshock"]) == pytest.approx(state.density * 1e-3, rel=1e-3), case
        assert float(table[f"theory: full-compaction porous Hugoniot temperature (energy T) {label}"]["mpmshock"]) \
            == pytest.approx(state.temperature, rel=1e-3), case
    strong = porous_shock(2000.0, 1.4, material)
    late = pm.CaseRun("delta1.4_v2000", runs / "delta1.4_v2000").late_mean("B800", "macro_density").mean
    assert late == pytest.approx(2.75, abs=1e-3)
    note = table["theory: full-compaction porous Hugoniot density (delta 1.4, 2000 m/s)"]["note"]
    assert f"({pr.signed(100 * (late / (strong.density * 1e-3) - 1), 2)} %)" in note, note
    assert table["theory: full-compaction porous Hugoniot density (delta 1.7, 1000 m/s)"]["note"].endswith(
        "ours: not run: delta1.7")
    assert strong.pressure > porous_shock(1500.0, 1.4, material).pressure > porous_shock(500.0, 1.4, material).pressure


def test_shock_study_scenes_drive_the_shocks_the_theory_rows_assume(mpmshock):
    """studies/paper/scenes/CASE.scene has the velocity and porosity of CASE_SHOCKS[CASE], as the
    simulator resolves them."""
    from paper.rows_studies import CASE_SHOCKS
    from conftest import STUDIES
    from mpmshock_post.resolve import resolved_scene
    for case, (velocity, porosity) in CASE_SHOCKS.items():
        scene = resolved_scene(STUDIES / "paper/scenes" / f"{case}.scene", (), mpmshock)
        assert (scene["velocity"], scene["porosity"]) == (velocity, porosity), case


def test_csv_header_and_quoting(rows, tmp_path):
    path = tmp_path / "comparison.csv"
    pc.write_comparison_csv(rows, path)
    assert path.read_text().splitlines()[0] == "figure,quantity,paper,mpmshock,unit,note"
    with open(path, newline="") as f:
        read = list(csv.DictReader(f))
    assert read == rows


def test_void_size_rows_name_the_porosity_the_layout_gave_each_band(tmp_path):
    """One layout per radius fills B800 with its own porosity (the band density at t = 0); Fig. 7's
    rows give it and the full-compaction Hugoniot there (hugoniot.porous_shock, computed here
    independently), and how far each run's temperature lies from that Hugoniot's."""
    from mpmshock_post.hugoniot import porous_shock
    band_delta = {"void_r25": 1.035, "base": 1.025, "void_r100": 1.02}
    for case, radius in (("void_r25", 25e-6), ("base", 50e-6), ("void_r100", 100e-6)):
        series = base_series(temperature_offset=10.0 * radius / 25e-6)
        series["B800"]["macro_density"] = np.where(T == 0.0, 2700.0 / band_delta[case],
                                                   series["B800"]["macro_density"])
        write_run(tmp_path / case, series, scene_text(void_radius=radius, cell_size=radius / 5))
    table = by_quantity(pc.comparison_rows(tmp_path))
    energy = table["larger voids give a higher mean temperature (energy T)"]
    assert energy["mpmshock"].startswith("yes")  # 10, 20, 40 K added to the same series
    base = pm.CaseRun("base", tmp_path / "base")
    material = base.material
    states = [porous_shock(1000.0, band_delta[case], material) for case in ("void_r25", "base", "void_r100")]
    assert "delta 1.0350/1.0250/1.0200 at r 25 um/r 50 um/r 100 um (body: 1.03/1.03/1.03)" in energy["note"]
    assert "/".join(f"{s.temperature:.0f}" for s in states) + " K (energy T)" in energy["note"]
    assert states[0].temperature - states[2].temperature > 20.0  # the band's porosity matters
    late = base.late_mean("B800", "temperature_mean").mean
    assert "our temperatures minus those: " in energy["note"]
    assert pr.signed(late - states[1].temperature, 2, "K") in energy["note"]
    steady = table["no evident difference in steady density, pressure and velocity"]
    assert "/".join(f"{s.pressure * 1e-9:.4g}" for s in states) + " GPa" in steady["note"]


def test_layouts_give_each_number_with_its_standard_error(tmp_path, capsys):
    """paper-layouts: two layouts of the base case 20 K apart in temperature give the late mean
    temperature and Fig. 2's first maximum as their mean with SE = 10 K (|a - b| / 2), range 20 K."""
    from paper import layouts as paper_layouts
    for seed, offset in ((1, 0.0), (2, 20.0)):
        write_run(tmp_path / f"seed{seed}", base_series(temperature_offset=offset), scene_text() + f"seed = {seed}\n")
    late = pm.CaseRun("base", tmp_path / "seed1").late_mean("B800", "temperature_mean").mean
    assert paper_layouts.main([f"base={tmp_path / 'seed1'}", f"base={tmp_path / 'seed2'}"]) == 0
    out = capsys.readouterr().out
    assert "### base: 2 layouts" in out
    mean_row = next(line for line in out.splitlines() if line.startswith("| mean ± SE |"))
    assert f"| {late + 10.0:.4g} ± 10 |" in mean_row, mean_row
    first = next(line for line in out.splitlines() if "| B800 first maximum of mean temperature (energy T) |" in line)
    assert first.endswith("| 432 | 452 | 442 | 10 | 20 |"), first
    assert "theory:" not in out  # the theory rows are the same for every layout


def test_layouts_put_their_spread_into_the_comparison_notes(tmp_path):
    """with_layouts (reproduce-paper --layouts): the campaign's base run (seed 1) and layouts
    base_seed2, base_seed3 with temperatures 20 and 40 K higher give the first-maximum row the
    mean 452 K, SE 20/sqrt(3) = 11.5 K and the paper's 432 K 1.7 SE away; the number itself, rows
    of other cases and theory rows are left as they are."""
    from paper import layouts as paper_layouts
    runs, layouts = tmp_path / "runs", tmp_path / "layouts"
    write_run(runs / "base", base_series(), scene_text() + "seed = 1\n")
    for seed, offset in ((2, 20.0), (3, 40.0)):
        write_run(layouts / f"base_seed{seed}", base_series(temperature_offset=offset),
                  scene_text() + f"seed = {seed}\noutput_dir = /elsewhere/s{seed}\n")
    (layouts / "notes").mkdir()  # not CASE_seedN: ignored
    plain = pc.comparison_rows(runs)
    rows = paper_layouts.with_layouts(plain, runs, layouts)
    assert [r["mpmshock"] for r in rows] == [r["mpmshock"] for r in plain]
    first = by_quantity(rows)["B800 first maximum of mean temperature (energy T)"]
    assert first["mpmshock"] == "432"
    assert first["note"].startswith(by_quantity(plain)[first["quantity"]]["note"])
    assert first["note"].endswith("; over 3 void layouts (seeds 1, 2, 3): 452 ± 12 K (mean ± SE), range 40; "
                                  "the paper's 432 lies 1.7 SE from that mean"), first["note"]
    for quantity, entry in by_quantity(rows).items():
        if quantity.startswith("theory:") or not entry["mpmshock"]:
            assert entry["note"] == by_quantity(plain)[quantity]["note"], quantity


def test_layouts_of_another_scene_or_the_same_seed_are_refused(tmp_path):
    """A 'layout' that ran another scene (here another velocity) or the campaign's own seed is
    not a layout: PostError naming the record and what differs."""
    from paper import layouts as paper_layouts
    from mpmshock_post.errors import PostError
    runs = tmp_path / "runs"
    write_run(runs / "base", base_series(), scene_text() + "seed = 1\n")
    write_run(tmp_path / "other" / "base_seed2", base_series(), scene_text(velocity=1500.0) + "seed = 2\n")
    write_run(tmp_path / "same" / "base_seed1", base_series(), scene_text() + "seed = 1\n")
    rows = pc.comparison_rows(runs)
    with pytest.raises(PostError, match=r"base_seed2: not a layout of .*velocity \(1500.0 against 1000.0\)"):
        paper_layouts.with_layouts(rows, runs, tmp_path / "other")
    with pytest.raises(PostError, match=r"base_seed1: the same seed"):
        paper_layouts.with_layouts(rows, runs, tmp_path / "same")
    with pytest.raises(PostError, match="no such directory"):
        paper_layouts.with_layouts(rows, runs, tmp_path / "missing")
