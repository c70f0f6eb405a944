"""The runs of the Xu et al. campaign and the measurements on them, for paper_comparison.py's rows:
a run's series in the paper's units (CaseRun), which runs are present (Campaign), and every number
computed from them (first maximum, rise end, dip, exponential decay, slopes, oscillation, top arrival,
release time, distributions). The definitions they share are in paper_comparison.py's docstring.
"""

import math
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

import numpy as np

from mpmshock_post.errors import PostError
from mpmshock_post.hist import distribution_moments
from mpmshock_post.hugoniot import Material, default_material, porous_shock
from mpmshock_post.reader import PaperTemperatureRun, Run, has_paper_temperature
from mpmshock_post.units import TIME, quantity

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


class NotMeasured(Exception):
    """A measurement the run cannot give (too short, no snapshot near the time, region absent)."""


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


def slope_standard_error(t, residual):
    """Standard error of a least-squares slope (per unit of t) whose residuals are correlated in
    time, as a region mean's are: the ordinary error sqrt(s^2 / Sxx), s^2 = sum r^2 / (n - 2),
    widened by sqrt((1 + rho) / (1 - rho)) for the residuals' lag-1 autocorrelation rho (an AR(1)
    noise has n (1 - rho) / (1 + rho) independent samples); rho is taken in [0, 0.95]."""
    t, residual = np.asarray(t, dtype=float), np.asarray(residual, dtype=float)
    sxx = np.sum((t - t.mean()) ** 2)
    energy = np.sum(residual ** 2)
    if t.size < 3 or sxx <= 0 or energy <= 0:
        return 0.0
    rho = float(np.clip(np.sum(residual[1:] * residual[:-1]) / energy, 0.0, 0.95))
    return float(np.sqrt(energy / (t.size - 2) / sxx * (1.0 + rho) / (1.0 - rho)))


@dataclass(frozen=True)
class Trend:
    """A series over a window: least-squares slope (per us) with its standard error
    (slope_standard_error), R^2, mean, and the rms of the residual about the line (the fluctuation
    once the trend is removed)."""

    t0: float
    t1: float
    slope: float      # per us
    r2: float
    mean: float
    fluctuation: float
    slope_se: float = 0.0  # per us

    @property
    def distinguishable_from_zero(self):
        """|slope| beyond twice its standard error."""
        return abs(self.slope) > 2.0 * self.slope_se


def trend(t, y, t0, t1, min_length=MIN_WINDOW):
    """Trend of the samples in [t0, t1]; NotMeasured when the window is shorter than min_length."""
    if t1 - t0 < min_length:
        raise NotMeasured(f"the window {t0:.0f}-{t1:.0f} ns is shorter than {min_length:.0f} ns")
    tw, yw = in_window(t, y, t0, t1)
    slope, intercept, r2 = linear_fit(tw, yw)
    residual = yw - (slope * tw + intercept)
    return Trend(t0, t1, 1e3 * slope, r2, float(yw.mean()), float(np.sqrt(np.mean(residual ** 2))),
                 1e3 * slope_standard_error(tw, residual))


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


ACCURACY_VELOCITY = 1000.0  # m/s: every porous level of ACCURACY was run at this impact velocity


def accuracy_at(porosity, cells_per_radius, velocity=ACCURACY_VELOCITY):
    """The docs/accuracy.md estimate at the studied porosity and r/h nearest (in log) to the run's;
    a run coarser than the coarsest studied level gets that level's numbers as lower bounds, and a
    run at another velocity is told that the estimate was made at ACCURACY_VELOCITY."""
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
    if abs(velocity - ACCURACY_VELOCITY) > 1.0:
        text += f" (estimated at {ACCURACY_VELOCITY:.0f} m/s; this run is at {velocity:.0f} m/s)"
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

    def __init__(self, case, path, quick=False, run=None):
        """`run`: the reader.Run to read (default Run(path)), e.g. a PaperTemperatureRun."""
        self.case = case
        self.path = Path(path)
        self.quick = quick
        self.run = run if run is not None else Run(self.path)
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

    def band_porosity(self, region=BOTTOM):
        """delta of the material a region holds at t = 0: the solid density over its band density
        (macro_density, voids counted) in the first sample. With few voids in the region this is
        not the body's porosity: the layout samples it."""
        data = self.regions.get(region)
        if data is None or len(data["time"]) == 0 or data["time"][0] != 0.0:
            raise NotMeasured(f"{self.case}: {region} has no sample at t = 0")
        return self.material.density / float(data["macro_density"][0])

    def band_hugoniot(self, region=BOTTOM):
        """The full-compaction porous Hugoniot state at the region's own initial porosity."""
        return porous_shock(self.velocity, self.band_porosity(region), self.material)

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

    def first_maximum(self, region, column):
        """(time, value) of the first maximum (first_maximum) of a region's column before t_stop."""
        t, y = self.series(region, column)
        return first_maximum(*in_window(t, y, t[0], self.t_stop))

    def initial_stage_end(self, region=BOTTOM):
        """End of the initial stage: the first maximum of the region's mean density."""
        return self.first_maximum(region, "density_mean")[0]

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
        return accuracy_at(self.porosity, self.cells_per_radius, self.velocity)

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
            reader = None
            if case.endswith(PAPER_T_SUFFIX) and not path.is_dir():
                # No paper-model run of its own: the energy-model run, where it reports both models.
                energy = self.runs_dir / case[:-len(PAPER_T_SUFFIX)]
                if has_paper_temperature(energy):
                    path, reader = energy, PaperTemperatureRun
            if not (path / "regions.csv").is_file():
                self._why[case] = case
            elif not (path / "summary.json").is_file():
                self._why[case] = f"{case} (incomplete: no summary.json)"
            else:
                try:
                    run = CaseRun(case, path, self.quick, reader(path) if reader else None)
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


# --- Fig. 5, 8, 10: mean squared rotation, divergence, strain rate ------------------------------------

DISSIPATION_COLUMNS = (("rotation", "rot2_mean"), ("divergence", "div2_mean"), ("strain rate", "strain_rate2_mean"))
SQUARED_RATE_UNIT = "1/ns^2"


def late_dissipation(run, region=BOTTOM):
    """Late-window means of <Rot^2>, <Div^2>, <D:D> (1/ns^2) by name."""
    return {name: run.late_mean(region, column).mean for name, column in DISSIPATION_COLUMNS}


# --- Fig. 11: distributions ---------------------------------------------------------------------------

FIG11_TIMES = (1200.0, 1250.0, 1300.0)


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


# --- Fig. 12 and 13: shock strength and porosity ------------------------------------------------------

def slopes_after_initial_stage(runs, column):
    """CaseRun.after_initial_stage of B800 for each run, by case."""
    return {case: run.after_initial_stage(BOTTOM, column) for case, run in runs.items()}
