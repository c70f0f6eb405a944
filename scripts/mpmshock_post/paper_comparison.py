"""Every number and every qualitative claim of Xu et al. (arXiv:0904.0135) set against mpmshock's
runs: the rows of comparison.csv.

    from mpmshock_post.paper_comparison import comparison_rows, write_comparison_csv
    rows = comparison_rows("DIR/runs")            # list of dicts, in the paper's figure order
    write_comparison_csv(rows, "DIR/comparison.csv")

Runs. runs_dir/<case>/ is an mpmshock run directory of configs/paper/<case>.scene with the default
(energy) temperature model; runs_dir/<case>-paperT/ is the same case with `temperature_model =
paper`. Cases: base (delta 1.03, r 50 um, 1000 m/s; Fig. 1-8), void_r25, void_r100 (Fig. 7-8),
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
import math
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

import numpy as np

from .errors import PostError
from .hist import distribution_moments
from .hugoniot import Material, default_material, hugoniot_temperature_table, porous_shock
from .reader import Run
from .units import TIME, quantity

COLUMNS = ("figure", "quantity", "paper", "mpmshock", "unit", "note")
PAPER_T_SUFFIX = "-paperT"
TEMPERATURE_MODELS = ("energy T", "paper T")

BOTTOM = "B800"                  # the paper's main measured domain
BOTTOM_REGIONS = ("B800", "B400", "B100")
TOP_REGIONS = ("T800", "T400", "T100")
LATE_WINDOW = 300.0              # ns before t_stop: the 'steady' values
EARLY_RISE = 100.0               # ns: the window of the early rate of the rise (rise_end)
PEAK_FRACTION = 0.9              # first_maximum: share of the full rise a maximum must reach
RELEASE_SPEED_FACTOR = 1.25      # release_time: the release runs at most this times c_L0
MIN_WINDOW = 100.0               # ns: the shortest window a slope is taken over
DIP_WINDOW_END = 700.0           # ns: Fig. 2's dip near 450 ns is looked for before this
PAPER_DOWNSTREAM_BOUNDARY = 810.0   # um: the paper's 'downstream boundary' of B800 at 250 ns


class NotMeasured(Exception):
    """A measurement the run cannot give (too short, no snapshot near the time, region absent)."""


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


# --- measurements on a series (t in ns, values in the paper's units) ----------------------------------

def running_mean(values, width):
    """Centred running mean over `width` (odd) samples; near the ends, over the samples available."""
    values = np.asarray(values, dtype=float)
    half = width // 2
    sums = np.concatenate([[0.0], np.cumsum(values)])
    lo = np.clip(np.arange(values.size) - half, 0, values.size)
    hi = np.clip(np.arange(values.size) + half + 1, 0, values.size)
    return (sums[hi] - sums[lo]) / (hi - lo)


def smooth3(values):
    """Centred running mean over 3 samples; each end sample averages itself and its one neighbour."""
    return running_mean(values, 3)


def first_maximum(t, y):
    """The first maximum of a rising series: the first local maximum of the 3-sample smoothed series
    (s[i-1] <= s[i] > s[i+1]) whose rise above the first sample is at least PEAK_FRACTION (90 %) of
    the largest rise of the smoothed series, so that noise on the way up is not taken for it; then
    the largest raw sample among the three the smoothing averaged there. Returns (time, raw value);
    NotMeasured if the series never turns down."""
    s = smooth3(y)
    rise = s - y[0]
    if s.size < 3 or not np.nanmax(rise) > 0:
        raise NotMeasured("the series does not rise")
    threshold = PEAK_FRACTION * np.nanmax(rise)
    for i in range(1, s.size - 1):
        if s[i - 1] <= s[i] > s[i + 1] and rise[i] >= threshold:
            k = i - 1 + int(np.argmax(y[i - 1:i + 2]))
            return t[k], y[k]
    raise NotMeasured("the series has no maximum (still rising at its end)")


def linear_fit(t, y):
    """Least-squares line through (t, y): (slope per ns, intercept, R^2); R^2 is 1 for a flat series."""
    t, y = np.asarray(t, dtype=float), np.asarray(y, dtype=float)
    if t.size < 3:
        raise NotMeasured(f"{t.size} samples are too few for a line")
    slope, intercept = np.polyfit(t, y, 1)
    residual = y - (slope * t + intercept)
    total = np.sum((y - y.mean()) ** 2)
    r2 = 1.0 - np.sum(residual ** 2) / total if total > 0 else 1.0
    return slope, intercept, r2


def in_window(t, y, t0, t1):
    """The samples with t0 <= t <= t1."""
    keep = (t >= t0 - 1e-6) & (t <= t1 + 1e-6)
    return t[keep], y[keep]


@dataclass(frozen=True)
class Trend:
    """A series over a window: least-squares slope (per us), R^2, mean, and the rms of the residual
    about the line (the fluctuation once the trend is removed)."""

    t0: float
    t1: float
    slope: float      # per us
    r2: float
    mean: float
    fluctuation: float


def trend(t, y, t0, t1, min_length=MIN_WINDOW):
    """Trend of the samples in [t0, t1]; NotMeasured when the window is shorter than min_length."""
    if t1 - t0 < min_length:
        raise NotMeasured(f"the window {t0:.0f}-{t1:.0f} ns is shorter than {min_length:.0f} ns")
    tw, yw = in_window(t, y, t0, t1)
    slope, intercept, r2 = linear_fit(tw, yw)
    residual = yw - (slope * tw + intercept)
    return Trend(t0, t1, 1e3 * slope, r2, float(yw.mean()), float(np.sqrt(np.mean(residual ** 2))))


def rise_end(t, y, t_max):
    """End of the near-linear rise before the first maximum at t_max: the early rate is the
    least-squares slope over t <= EARLY_RISE (100 ns); the rise ends at the first sample after that
    at which the slope of the 3-sample smoothed series (centred difference) falls below half the
    early rate. Returns (time, R^2 of a straight line over [0, that time])."""
    early_t, early_y = in_window(t, y, t[0], EARLY_RISE)
    early_rate, _, _ = linear_fit(early_t, early_y)
    if not early_rate > 0:
        raise NotMeasured("no rise in the first 100 ns")
    s = smooth3(y)
    rate = np.gradient(s, t)
    for i in range(1, t.size - 1):
        if EARLY_RISE < t[i] <= t_max and rate[i] < 0.5 * early_rate:
            return t[i], linear_fit(*in_window(t, y, t[0], t[i]))[2]
    raise NotMeasured("the rate does not fall to half its early value before the first maximum")


def deepest_dip(t, y, t0, t1):
    """The deepest local minimum (s[i-1] >= s[i] < s[i+1]) of the 3-sample smoothed series with
    t0 < t < t1: (time, smoothed value)."""
    s = smooth3(y)
    minima = [i for i in range(1, t.size - 1) if t0 < t[i] < t1 and s[i - 1] >= s[i] < s[i + 1]]
    if not minima:
        raise NotMeasured(f"no local minimum between {t0:.0f} and {t1:.0f} ns")
    i = min(minima, key=lambda k: s[k])
    return t[i], s[i]


@dataclass(frozen=True)
class Decay:
    """y ~ steady + amplitude exp(-(t - t_peak) / tau) for t >= t_peak."""

    t_peak: float
    peak: float
    tau: float
    steady: float
    r2: float


def _decay_fit(td, yd, tau):
    """Least-squares a and c of y = c + a exp(-td / tau) for a given tau: (sum of squared residuals, a, c)."""
    basis = np.column_stack([np.exp(-td / tau), np.ones_like(td)])
    (a, c), *_ = np.linalg.lstsq(basis, yd, rcond=None)
    return float(np.sum((yd - basis @ np.array([a, c])) ** 2)), a, c


def exponential_decay(t, y, t_stop):
    """Fit of the decay after the peak: t_peak is the time of the largest value of the 3-sample
    smoothed series up to t_stop; over [t_peak, t_stop], y = c + a exp(-(t - t_peak)/tau) is fitted by
    least squares: a and c linear for each tau, tau the best of a logarithmic grid of 400 values from
    the sample spacing to 10 times the window, refined on a grid 100 times finer around it. R^2 = 1 -
    SS_residual / SS_total. NotMeasured when the best fit is no decay (a <= 0) or tau sits at the
    grid's end (no decay within the window)."""
    t, y = in_window(t, y, t[0], t_stop)
    i_peak = int(np.argmax(smooth3(y)))
    td, yd = t[i_peak:] - t[i_peak], y[i_peak:]
    if td.size < 5:
        raise NotMeasured("fewer than 5 samples after the peak")
    taus = np.geomspace(np.median(np.diff(td)), 10.0 * td[-1], 400)
    k = min(range(taus.size), key=lambda i: _decay_fit(td, yd, taus[i])[0])
    if k == taus.size - 1:
        raise NotMeasured("no exponential decay after the peak")
    fine = np.geomspace(taus[max(k - 1, 0)], taus[k + 1], 200)
    tau = min(fine, key=lambda value: _decay_fit(td, yd, value)[0])
    sse, a, c = _decay_fit(td, yd, tau)
    if not a > 0:
        raise NotMeasured("no exponential decay after the peak")
    total = float(np.sum((yd - yd.mean()) ** 2))
    return Decay(t[i_peak], float(y[i_peak]), float(tau), float(c), 1.0 - sse / total if total > 0 else 1.0)


def oscillation(t, y, t0, t1):
    """Short-period oscillation of the samples in [t0, t1]: the rms of their difference from the
    5-sample centred running mean (periods under about 5 samples, 50 ns at the paper's 10 ns),
    which slow trends such as a release leave out (a straight line gives 0); the two samples at each
    end of the window, where the mean is not centred, are left out."""
    if t1 - t0 < MIN_WINDOW:
        raise NotMeasured(f"the window {t0:.0f}-{t1:.0f} ns is shorter than {MIN_WINDOW:.0f} ns")
    _, yw = in_window(t, y, t0, t1)
    residual = (yw - running_mean(yw, 5))[2:-2]
    return float(np.sqrt(np.mean(residual ** 2)))


def upward_crossing(t, y, level):
    """First time the series crosses `level` from below (linear interpolation between samples)."""
    above = np.flatnonzero((y[1:] >= level) & (y[:-1] < level))
    if above.size == 0:
        raise NotMeasured(f"the series never rises through {level:g}")
    i = above[0]
    return t[i] + (level - y[i]) * (t[i + 1] - t[i]) / (y[i + 1] - y[i])


def value_at(t, y, time):
    """The series at `time`, linearly interpolated; NotMeasured outside the samples."""
    if not t[0] <= time <= t[-1]:
        raise NotMeasured(f"no sample near {time:.0f} ns (the series spans {t[0]:.0f}-{t[-1]:.0f} ns)")
    return float(np.interp(time, t, y))


def window_mean(t, y, t0, t1):
    """Mean of the samples in [t0, t1]; NotMeasured if there are none."""
    _, yw = in_window(t, y, t0, t1)
    if yw.size == 0:
        raise NotMeasured(f"no samples in {t0:.0f}-{t1:.0f} ns")
    return float(yw.mean())


def column_heights(x, y, width, bin_width):
    """Highest y in each x bin of `bin_width` across the periodic column [0, width) (empty bins left
    out)."""
    bins = np.floor(np.mod(x, width) / bin_width).astype(int)
    tops = np.full(int(math.ceil(width / bin_width)), -np.inf)
    np.maximum.at(tops, bins, y)
    return tops[np.isfinite(tops)]


# --- docs/accuracy.md: the estimated numerical error at a resolution --------------------------------

# Per porosity, per r/h: how far the band means at that resolution lie from the converged limit
# (docs/accuracy.md: section 4 for delta 1.03 at r = 50 um, levels 20/10/5 um; section 2 for delta
# 1.1 and 1.4 at r = 20 um, each level against the Richardson limit): density_mean and
# pressure_mean too high by (%), temperature_mean too low by (K).
ACCURACY = {
    1.03: {2.5: (0.62, 4.8, 15.0), 5.0: (0.41, 3.2, 7.1), 10.0: (0.27, 2.2, 3.3)},
    1.1: {2.0: (2.0, 16.6, 129.0), 4.0: (1.0, 7.0, 70.0), 8.0: (0.5, 2.9, 37.0)},
    1.4: {2.0: (2.8, 40.5, 157.0), 4.0: (0.96, 13.7, 40.0), 8.0: (0.36, 4.6, 10.0)},
}


@dataclass(frozen=True)
class Accuracy:
    density: float       # share (0.0062 = 0.62 %)
    pressure: float      # share
    temperature: float   # K
    text: str


def accuracy_at(porosity, cells_per_radius):
    """The docs/accuracy.md estimate at the studied porosity and r/h nearest (in log) to the run's;
    a run coarser than the coarsest studied level gets that level's numbers as lower bounds."""
    studied = min(ACCURACY, key=lambda d: abs(math.log(d) - math.log(porosity)))
    levels = ACCURACY[studied]
    level = min(levels, key=lambda r: abs(math.log(r) - math.log(cells_per_radius)))
    density, pressure, temperature = levels[level]
    coarser = cells_per_radius < min(levels) / 1.2
    where = f"delta {studied:g}, h = r/{level:g}"
    bound = "more than " if coarser else "~"
    text = (f"docs/accuracy.md at {where}: cells of this size overstate density by {bound}{density:g} % and "
            f"pressure by {bound}{pressure:g} %, understate T by {bound}{temperature:g} K")
    if coarser:
        text += f" (this run, h = r/{cells_per_radius:.2g}, is coarser than any level studied)"
    return Accuracy(density / 100.0, pressure / 100.0, temperature, text)


# --- one run ----------------------------------------------------------------------------------------

def _display_quantity(column):
    """The units.quantity of a regions.csv or probes.csv column ('density_mean', 'macro_density',
    'velocity_y_std', 'rot2_mean', 'velocity_y')."""
    name = column
    for suffix in ("_mean", "_std"):
        if name.endswith(suffix):
            name = name[:-len(suffix)]
    name = {"macro_density": "density", "macro_pressure": "pressure", "macro_normal_stress": "pressure"}.get(name, name)
    return quantity(name)


class CaseRun:
    """One run directory of the campaign, with its series in the paper's units (read once)."""

    def __init__(self, case, path, quick=False):
        self.case = case
        self.path = Path(path)
        self.quick = quick
        self.run = Run(self.path)
        self.scene = self.run.scene

    @cached_property
    def regions(self):
        return self.run.regions()

    @cached_property
    def probes(self):
        return self.run.probes() if (self.path / "probes.csv").is_file() else {}

    def series(self, region, column):
        """(t in ns, values in the paper's units) of a regions.csv column."""
        if region not in self.regions:
            raise NotMeasured(f"{self.case} has no region {region}")
        data = self.regions[region]
        values = data[column] * _display_quantity(column).factor
        if not np.all(np.isfinite(values)):
            raise NotMeasured(f"{self.case}: {region} {column} is not finite at every sample (thermal = off?)")
        return data["time"] * TIME.factor, values

    @property
    def velocity(self):
        return float(self.scene["velocity"])

    @property
    def porosity(self):
        return float(self.scene["porosity"])

    @property
    def t_end(self):
        """The last sample time [ns]."""
        if not self.regions:
            raise NotMeasured(f"{self.case}: regions.csv has no rows")
        return float(next(iter(self.regions.values()))["time"][-1] * TIME.factor)

    @cached_property
    def material(self):
        return Material.from_scene(self.scene)

    @cached_property
    def hugoniot_state(self):
        """The full-compaction porous Hugoniot state of this case (hugoniot.porous_shock)."""
        return porous_shock(self.velocity, self.porosity, self.material)

    def region_top(self, region=BOTTOM):
        """Upper edge y1 + h of a bottom region [m]."""
        spec = self.scene.regions.get(region)
        if spec is None or spec.kind != "bottom":
            raise NotMeasured(f"{self.case} has no bottom region {region}")
        return spec.y1 + spec.height

    def front_exit_time(self, region=BOTTOM):
        """When the full-compaction porous front passes the region's top [ns] (theory)."""
        return self.region_top(region) / self.hugoniot_state.front_speed * TIME.factor

    @cached_property
    def top_arrival(self):
        """When the shock reaches the top free surface: the first upward crossing of u_y = 0 (the
        middle of the jump from -v to about +v) by a surface probe (probes.csv, a probe.NAME =
        surface key), else by the mean u_y of the thinnest top region. (time ns, source, t, u_y)."""
        surface = [key[len("probe."):] for key, value in self.scene.items()
                   if key.startswith("probe.") and str(value).split()[:1] == ["surface"]]
        if surface and surface[0] in self.probes:
            data = self.probes[surface[0]]
            t, u = data["time"] * TIME.factor, data["velocity_y"]
            source = f"probe.{surface[0]} (surface)"
        else:
            tops = [name for name, spec in self.scene.regions.items() if spec.kind == "top" and name in self.regions]
            if not tops:
                raise NotMeasured("no surface probe and no top region")
            name = min(tops, key=lambda n: self.scene.regions[n].height)
            t, u = self.series(name, "velocity_y_mean")
            source = f"region {name} mean u_y"
        return upward_crossing(t, u, 0.0), source, t, u

    def release_time(self, region=BOTTOM):
        """Earliest time the release from the top free surface can reach the top of `region`:
        t_top + (y_top(t_top) - (y1 + h)) / (RELEASE_SPEED_FACTOR c_L0). y_top(t_top) = H - v t_top
        (the top moves down at v until the shock arrives), c_L0 = sqrt((rho0 c0^2 + 4G/3) / rho0) the
        longitudinal sound speed at rest, raised by 25 % for the compressed material: an early
        (conservative) estimate. Without a measured arrival: the run's end."""
        try:
            t_top = self.top_arrival[0]
        except NotMeasured:
            return math.inf
        height_top = float(self.scene["target_height"]) - self.velocity * t_top / TIME.factor
        region_top = self.region_top(region)
        rho0 = self.material.density
        shear = float(self.scene["youngs_modulus"]) / (2.0 * (1.0 + float(self.scene["poisson_ratio"])))
        c_L0 = math.sqrt((self.material.bulk_modulus + 4.0 * shear / 3.0) / rho0)
        return t_top + max(height_top - region_top, 0.0) / (RELEASE_SPEED_FACTOR * c_L0) * TIME.factor

    @cached_property
    def t_stop(self):
        """The shock-free end: min(run end, release_time(B800))."""
        return min(self.t_end, self.release_time())

    @property
    def late_window(self):
        """The last LATE_WINDOW (300 ns) before t_stop."""
        return self.t_stop - LATE_WINDOW, self.t_stop

    def initial_stage_end(self, region=BOTTOM):
        """End of the initial stage: the first maximum of the region's mean density."""
        t, rho = self.series(region, "density_mean")
        t_max, _ = first_maximum(*in_window(t, rho, t[0], self.t_stop))
        return t_max

    def after_initial_stage(self, region, column):
        """Trend of a column over [initial_stage_end, t_stop]."""
        t, y = self.series(region, column)
        return trend(t, y, self.initial_stage_end(region), self.t_stop)

    def late_mean(self, region, column):
        """Trend of a column over the late window (its mean is the 'steady' value)."""
        return trend(*self.series(region, column), *self.late_window)

    @property
    def cells_per_radius(self):
        """r / h: the void radius in cells."""
        return float(self.scene["void_radius"]) / float(self.scene["cell_size"])

    @cached_property
    def accuracy(self):
        """docs/accuracy.md's error estimate at this run's porosity and r/h (accuracy_at)."""
        return accuracy_at(self.porosity, self.cells_per_radius)

    @property
    def resolution(self):
        """'base: h 20 um = r/2.5, 0.5 x 5 mm, bspline2' (after 'quick run, ' in quick mode)."""
        h, width, height = (float(self.scene[key]) * 1e3 for key in ("cell_size", "width", "target_height"))
        text = (f"{self.case}: h {h * 1e3:.3g} um = r/{self.cells_per_radius:.2g}, {width:.3g} x {height:.3g} mm, "
                f"{self.scene.get('shape_function', '?')}")
        return ("quick run, " if self.quick else "") + text

    @cached_property
    def distributions(self):
        """distribution_table of this run, read once."""
        return distribution_table(self)

    def snapshot_near(self, time_ns):
        try:
            return self.run.snapshot(time=time_ns / TIME.factor)
        except PostError as e:
            raise NotMeasured(str(e)) from None


# --- the campaign -----------------------------------------------------------------------------------

CASES = ("base", "void_r25", "void_r100", "delta1.4", "delta1.4_v500", "delta1.4_v1500", "delta1.4_v2000",
         "delta1.01", "delta1.02", "delta1.1", "delta1.7")


class Campaign:
    """The run directories under runs_dir: case name -> CaseRun, or None where the run is missing
    (no regions.csv) or did not finish (no summary.json, or an exit code other than 0); `why(case)`
    says which."""

    def __init__(self, runs_dir, quick=False):
        self.runs_dir = Path(runs_dir)
        self.quick = quick
        self._runs = {}
        self._why = {}

    def get(self, case):
        if case not in self._runs:
            self._runs[case] = None
            path = self.runs_dir / case
            if not (path / "regions.csv").is_file():
                self._why[case] = case
            elif not (path / "summary.json").is_file():
                self._why[case] = f"{case} (incomplete: no summary.json)"
            else:
                try:
                    run = CaseRun(case, path, self.quick)
                    exit_code = run.run.summary().get("exit_code", 0)
                except PostError as e:
                    self._why[case] = f"{case} (unreadable: {e})"
                    return None
                if exit_code == 0:
                    self._runs[case] = run
                else:
                    self._why[case] = f"{case} (stopped with exit code {exit_code})"
        return self._runs[case]

    def why(self, case):
        """The missing case as the notes name it: 'CASE', 'CASE (incomplete: ...)'."""
        return self._why.get(case, case)

    @staticmethod
    def temperature_case(case, model):
        """The case whose temperatures follow `model` ('energy T' or 'paper T')."""
        return case if model == "energy T" else case + PAPER_T_SUFFIX

    @cached_property
    def material(self):
        """The material of any run present (their scenes), else the simulator's defaults."""
        for case in CASES:
            run = self.get(case)
            if run is not None:
                return run.material
        return default_material()


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
            t_max, value = first_maximum(*in_window(t, y, t[0], run.t_stop))
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
            t, y = run.series(BOTTOM, column)
            t_max, _ = first_maximum(*in_window(t, y, t[0], run.t_stop))
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
        return f"our B800 {column} {fmt(late.mean)} over {late.t0:.0f}-{late.t1:.0f} ns ({run.resolution})"

    rows += [
        row("Fig 2", "theory: full-compaction porous Hugoniot density (delta 1.03, 1000 m/s)", "3.14", "g/cm3",
            fmt(state.density * 1e-3), f"{number_verdict(state.density * 1e-3, 3.14, 0.005, '')}: the paper's "
            f"number is its transient first maximum, the nearest it gives; {ours('base', 'macro_density')}"),
        row("Fig 2", "theory: full-compaction porous Hugoniot pressure (delta 1.03, 1000 m/s)", "16.7", "GPa",
            fmt(state.pressure * 1e-9), f"{number_verdict(state.pressure * 1e-9, 16.7, 0.03, '')}: the paper's "
            f"first maximum overshoots the steady state; {ours('base', 'macro_normal_stress')}"),
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
            t_max, _ = first_maximum(*in_window(t, y, t[0], run.t_stop))
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

DISSIPATION_COLUMNS = (("rotation", "rot2_mean"), ("divergence", "div2_mean"), ("strain rate", "strain_rate2_mean"))
SQUARED_RATE_UNIT = "1/ns^2"


def late_dissipation(run, region=BOTTOM):
    """Late-window means of <Rot^2>, <Div^2>, <D:D> (1/ns^2) by name."""
    return {name: run.late_mean(region, column).mean for name, column in DISSIPATION_COLUMNS}


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


def radius_label(run):
    return f"r {float(run.scene['void_radius']) * 1e6:.3g} um"


def fig7_rows(c):
    """Late-window B800 means for each void radius: temperature rising with r; density, pressure and
    u_y with no evident difference, i.e. a spread between the radii (max - min) no larger than twice
    the largest within-run fluctuation (rms about the window's line)."""
    rows = []
    for model in TEMPERATURE_MODELS:
        def hotter(runs, model=model):
            late = {case: run.late_mean(BOTTOM, "temperature_mean") for case, run in runs.items()}
            values = [late[case].mean for case in runs]
            increasing = all(b > a for a, b in zip(values, values[1:]))
            return ("{}: ".format(yes_no(increasing)) + ", ".join(
                f"{fmt(late[case].mean)} K ({radius_label(run)})" for case, run in runs.items()),
                f"{'agree' if increasing else 'differ'}: B800 late-window means (last {LATE_WINDOW:.0f} ns before each "
                f"run's t_stop); {void_resolution_text(runs)}; " + "; ".join(run.resolution for run in runs.values()))
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
                f"twice the largest fluctuation; units g/cm3, GPa, m/s; {void_resolution_text(runs)}")

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
            return (f"{yes_no(down)}: {signed(fit.slope, 3, unit + '/us')} (R^2 {fit.r2:.2f})",
                    f"{'agree' if down else 'differ'}: least-squares slope over {fit.t0:.0f}-{fit.t1:.0f} ns (first "
                    f"maximum of the density to t_stop); {run.accuracy.text}; {run.resolution}")
        return measure

    rows = [measured_row(c, "Fig 9", "delta 1.4: B800 density decreases after the initial stage", "yes", "g/cm3/us",
                         ["delta1.4"], falling("density_mean", "g/cm3")),
            measured_row(c, "Fig 9", "delta 1.4: B800 pressure decreases after the initial stage", "yes", "GPa/us",
                         ["delta1.4"], falling("pressure_mean", "GPa"))]
    for model in TEMPERATURE_MODELS:
        def faster(high, low):
            fast = high.after_initial_stage(BOTTOM, "temperature_mean")
            slow = low.after_initial_stage(BOTTOM, "temperature_mean")
            return (f"{yes_no(fast.slope > slow.slope)}: {signed(fast.slope, 3, 'K/us')} vs "
                    f"{signed(slow.slope, 3, 'K/us')} at delta 1.03",
                    f"{'agree' if fast.slope > slow.slope else 'differ'}: slopes over {fast.t0:.0f}-{fast.t1:.0f} ns "
                    f"(delta 1.4) and {slow.t0:.0f}-{slow.t1:.0f} ns (delta 1.03); {high.resolution}; {low.resolution}")
        rows.append(measured_row(c, "Fig 9", f"temperature rises faster at delta 1.4 than at 1.03 ({model})", "yes",
                                 "K/us", [c.temperature_case("delta1.4", model), c.temperature_case("base", model)],
                                 faster))
    return rows + theory_delta14_rows(c)


def theory_delta14_rows(c):
    """The full-compaction porous Hugoniot at delta 1.4, 1000 m/s, against our B800 late-window means
    (macro_density, macro_normal_stress, temperature_mean of each model)."""
    try:
        material = c.material
    except PostError as e:
        return [row("Fig 9", "theory: full-compaction porous Hugoniot (delta 1.4, 1000 m/s)", "", "", "",
                    f"not computed: {e}")]
    state = porous_shock(1000.0, 1.4, material)
    t_h = hugoniot_temperature_table(material).hugoniot_temperature(state.J)
    entries = (("full-compaction porous Hugoniot density", "macro_density", state.density * 1e-3, "g/cm3",
                "delta1.4"),
               ("full-compaction porous Hugoniot pressure", "macro_normal_stress", state.pressure * 1e-9, "GPa",
                "delta1.4"),
               ("full-compaction porous Hugoniot temperature (energy T)", "temperature_mean", state.temperature, "K",
                "delta1.4"),
               (PAPER_T_LEAST, "temperature_mean", t_h, "K", "delta1.4" + PAPER_T_SUFFIX))
    rows = []
    for name, column, theory, unit, case in entries:
        run = c.get(case)
        if run is None:
            note = f"theory (hugoniot.porous_shock); ours: not run: {c.why(case)}"
        else:
            try:
                late = run.late_mean(BOTTOM, column)
                note = (f"theory (hugoniot.porous_shock); ours: B800 {column} {fmt(late.mean)} over {late.t0:.0f}-"
                        f"{late.t1:.0f} ns ({signed(100 * (late.mean / theory - 1), 2)} %); {run.accuracy.text}; "
                        f"{run.resolution}")
            except NotMeasured as e:
                note = f"theory (hugoniot.porous_shock); ours not measured: {e}"
        rows.append(row("Fig 9", f"theory: {name} (delta 1.4, 1000 m/s)", "", unit,
                        fmt(theory), note))
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

FIG11_TIMES = (1200.0, 1250.0, 1300.0)
NON_GAUSSIAN_SKEWNESS = 0.5
NON_GAUSSIAN_KURTOSIS = 1.0


def fig11_snapshots(run):
    """The snapshots at 1200, 1250 and 1300 ns; a run that ends earlier uses its last three."""
    infos = run.run.snapshots()
    times = np.array([info.time for info in infos]) * TIME.factor
    if len(infos) < 3:
        raise NotMeasured(f"{len(infos)} snapshots, 3 needed")
    if times[-1] < FIG11_TIMES[-1] - 1.0:
        return [run.run.snapshot(index=info.index) for info in infos[-3:]], "the run's last three snapshots"
    return [run.snapshot_near(time) for time in FIG11_TIMES], "1200, 1250, 1300 ns"


def distribution_table(run):
    """hist.distribution_moments of B800 at the Fig. 11 times, by quantity: list of (time ns, mean,
    std, skewness, excess kurtosis); and which times they are (CaseRun.distributions keeps it)."""
    snapshots, which = fig11_snapshots(run)
    table = {}
    for time, name, count, mean, std, skewness, kurtosis in distribution_moments(snapshots, BOTTOM):
        table.setdefault(name, []).append((time * TIME.factor, mean, std, skewness, kurtosis))
    return table, which


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


def slopes_after_initial_stage(runs, column):
    """CaseRun.after_initial_stage of B800 for each run, by case."""
    return {case: run.after_initial_stage(BOTTOM, column) for case, run in runs.items()}


def fig12_rows(c):
    """delta 1.4 at 500, 1000, 1500, 2000 m/s: the slopes after the initial stage of B800's density
    (falling faster) and temperature (rising faster) as the shock strengthens, i.e. the density slope
    decreasing and the temperature slope increasing with v."""

    def trend_with_speed(column, unit, sign):
        def measure(runs):
            fits = slopes_after_initial_stage(runs, column)
            values = [sign * fits[case].slope for case in runs]
            grows = all(b > a for a, b in zip(values, values[1:]))
            return (f"{yes_no(grows)}: " + ", ".join(f"{signed(fits[case].slope, 3)} at {run.velocity:.0f} m/s"
                                                      for case, run in runs.items()) + f" {unit}/us",
                    f"{'agree' if grows else 'differ'}: B800 least-squares slopes from the first maximum of the "
                    f"density to t_stop; " + "; ".join(run.resolution for run in runs.values()))
        return measure

    rows = [study_row(c, "Fig 12", "delta 1.4: density decreases faster with a stronger shock", "yes", "g/cm3/us",
                      list(SPEED_CASES), trend_with_speed("density_mean", "g/cm3", -1.0))]
    for model in TEMPERATURE_MODELS:
        rows.append(study_row(c, "Fig 12", f"delta 1.4: temperature increases faster with a stronger shock ({model})",
                              "yes", "K/us", [c.temperature_case(case, model) for case in SPEED_CASES],
                              trend_with_speed("temperature_mean", "K", 1.0)))
    return rows


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
        return (f"{yes_no(grows)}: " + ", ".join(f"{signed(fits[case].slope, 3)} at delta {run.porosity:g}"
                                                 for case, run in runs.items()) + " g/cm3/us",
                f"{'agree' if grows else 'differ'}: B800 slopes from the first maximum of the density to t_stop; "
                + "; ".join(run.resolution for run in runs.values()))

    def large(runs):
        fits = slopes_after_initial_stage(runs, "density_mean")
        small_r2 = [fits[case].r2 for case in runs if case in SMALL_POROSITY_CASES]
        large_r2 = [fits[case].r2 for case in runs if case in LARGE_POROSITY_CASES]
        if not small_r2 or not large_r2:
            raise NotMeasured("needs a small- and a large-porosity run")
        slopes = [fits[case].slope for case in runs]
        monotone = all(b < a for a, b in zip(slopes, slopes[1:]))
        complex_ = not monotone or np.mean(large_r2) < np.mean(small_r2)
        return (f"{yes_no(complex_)}: " + ", ".join(f"{signed(fits[case].slope, 3)} (R^2 {fits[case].r2:.2f}) at delta "
                                                    f"{run.porosity:g}" for case, run in runs.items()) + " g/cm3/us",
                f"{'agree' if complex_ else 'differ'}: more complex read as slopes that stop falling with delta or a "
                f"worse straight-line fit at large porosity; slopes fall monotonically with delta: {yes_no(monotone)}; "
                f"mean R^2 {np.mean(large_r2):.2f} (large) vs {np.mean(small_r2):.2f} (small); "
                + "; ".join(run.resolution for run in runs.values()))

    return [study_row(c, "Fig 13", "small porosity: density decrease rate grows with porosity", "yes", "g/cm3/us",
                      list(SMALL_POROSITY_CASES), small),
            study_row(c, "Fig 13", "large porosity: density shows more complex behaviour", "yes", "g/cm3/us",
                      list(SMALL_POROSITY_CASES + LARGE_POROSITY_CASES), large)]


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
