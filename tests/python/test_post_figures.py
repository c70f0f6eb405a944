"""What the mpmshock-plot figures say, read from the figure objects: every kind states the run's
resolution (cell size, points per cell, shape function, from scene.txt), a solid run's title has no
void radius, the histograms' axes are in the quantity's unit and its inverse, a narrow column's
field plot keeps its x tick labels apart and its title inside the figure, and compare has a title.

    /usr/bin/python3 -m pytest tests/python/test_post_figures.py [--mpmshock BUILD/src/mpmshock]

Set MPMSHOCK_FIGURES=DIR to also save one PNG of each kind there, to look at.
"""

import os
from pathlib import Path

import matplotlib
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg

from conftest import simulate
from mpmshock_post import cli, reader
from mpmshock_post.hist import QUANTITIES as HIST_QUANTITIES

matplotlib.use("Agg")

RESOLUTION = ("cell 10 µm", "2 × 2 points per cell", "bspline2_domain shape functions")
PROBES = ("probe.free_surface=surface", "probe.p1=point 30um 150um")


@pytest.fixture(scope="module")
def runs(mpmshock, tiny_scene, tmp_path_factory):
    """The tiny porous run, its solid variant (porosity 1), one whose porosity is too close to 1 for
    a single void, one at a coarser resolution, and a narrow column, all with probes."""
    tmp = tmp_path_factory.mktemp("figures")
    made = {"porous": (), "solid": ("porosity=1",), "no_voids": ("porosity=1.001",),
            "coarse": ("cell_size=20um", "particles_per_cell=3", "shape_function=gimp"),
            "narrow": ("width=60um", "target_height=600um", "flyer_height=600um", "void_radius=8um",
                       "void_radius_spread=0um")}
    for name, overrides in made.items():
        simulate(mpmshock, tiny_scene, tmp / name, *PROBES, *overrides)
    return {name: tmp / name for name in made}


def figure(kind, *args):
    """The Figure mpmshock-plot KIND ARGS would save, made as the command line makes it."""
    fig, _, _ = cli._KINDS[kind](cli.build_parser().parse_args([kind, *map(str, args)]))
    folder = os.environ.get("MPMSHOCK_FIGURES")
    if folder:
        Path(folder).mkdir(parents=True, exist_ok=True)
        fig.savefig(Path(folder) / f"{kind}_{Path(str(args[0])).name}.png", dpi=100)
    return fig


def all_texts(fig):
    """Every text of the figure: its own (suptitle, footer), and of each axes the titles, labels,
    notes and legend."""
    texts = [t.get_text() for t in fig.texts]
    for ax in fig.axes:
        texts += [ax.get_title(loc) for loc in ("left", "center", "right")]
        texts += [ax.get_xlabel(), ax.get_ylabel()] + [t.get_text() for t in ax.texts]
        legend = ax.get_legend()
        if legend is not None:
            texts += [legend.get_title().get_text()] + [t.get_text() for t in legend.get_texts()]
    return [text for text in texts if text]


def titles(fig):
    """The suptitle and the axes titles."""
    found = [fig._suptitle.get_text()] if fig._suptitle is not None else []
    return found + [ax.get_title(loc) for ax in fig.axes for loc in ("left", "center", "right") if ax.get_title(loc)]


def kinds(run_dir, other_dir):
    """One figure of every kind, of this run (compare: with `other_dir`)."""
    return {
        "timeseries": figure("timeseries", run_dir),
        "std": figure("std", run_dir),
        "dissipation": figure("dissipation", run_dir),
        "field": figure("field", run_dir),
        "hist": figure("hist", run_dir, "--region", "B800"),
        "compare": figure("compare", run_dir, other_dir, "--quantity", "density,temperature"),
        "probe": figure("probe", run_dir),
    }


def test_every_figure_states_its_resolution(runs):
    for kind, fig in kinds(runs["porous"], runs["solid"]).items():
        footer = "\n".join(all_texts(fig))
        for part in RESOLUTION:
            assert part in footer, f"{kind}: no '{part}' in the figure's texts:\n{footer}"


def test_resolution_of_runs_that_differ(runs):
    """compare of runs at two resolutions states each, named as in the legend."""
    fig = figure("compare", runs["porous"], runs["coarse"])
    footer = "\n".join(t.get_text() for t in fig.texts)
    assert "cell 10 µm, 2 × 2 points per cell" in footer and "bspline2" in footer, footer
    assert "cell 20 µm, 3 × 3 points per cell" in footer and "gimp shape functions" in footer, footer
    legend = [t.get_text() for t in fig.axes[-1].get_legend().get_texts()]
    for label in legend:
        assert label in footer, f"legend entry '{label}' does not name a resolution in:\n{footer}"


def test_solid_title_has_no_void_radius(runs):
    for kind, fig in kinds(runs["solid"], runs["solid"]).items():
        for title in titles(fig):
            assert "$r$" not in title and "µm" not in title, f"{kind}: solid run titled '{title}'"
        if kind != "compare":  # its title holds what the runs share, its legend what differs
            assert any(r"$\delta$=1, $v$=1000 m/s" in title for title in titles(fig)), f"{kind}: {titles(fig)}"
    # porosity 1.001 on this plate leaves no void: said so, and no radius
    assert reader.Run(runs["no_voids"]).void_count() == 0
    fig = figure("timeseries", runs["no_voids"])
    assert r"$\delta$=1.001 (no voids)" in fig._suptitle.get_text() and "$r$" not in fig._suptitle.get_text()
    # the porous run still names its voids
    fig = figure("timeseries", runs["porous"])
    assert "$r$=15 µm" in fig._suptitle.get_text(), fig._suptitle.get_text()


def test_compare_has_a_title(runs):
    fig = figure("compare", runs["porous"], runs["solid"], "--regions", "B800")
    title = fig._suptitle.get_text() if fig._suptitle is not None else ""
    assert "B800" in title and "$v$=1000 m/s" in title, f"compare title: '{title}'"
    assert "$r$" not in title, "the void radius is not shared by a solid run"
    legend = [t.get_text() for t in fig.axes[-1].get_legend().get_texts()]
    # the automatic cfl, volumetric smoothing and A1 differ too: 0.6, on and 0.2 for a porous scene,
    # 0.8, off and 0.6 for a solid one (the legend names three and counts the rest)
    assert legend == [r"$\delta$=1.2, cfl=0.6, volumetric_smoothing=on (+1 more)",
                      r"$\delta$=1, cfl=0.8, volumetric_smoothing=off (+1 more)"], legend
    fig = figure("compare", runs["porous"], runs["solid"], "--title", "mine")
    assert fig._suptitle.get_text() == "mine"


def test_hist_axes_in_the_unit_and_its_inverse(runs):
    fig = figure("hist", runs["porous"], "--region", "B800")
    panels = dict(zip(HIST_QUANTITIES, fig.axes))
    expected = {"density": (r"$\rho$ (g/cm$^3$)", "probability density (cm$^3$/g)"),
                "pressure": ("$P$ (GPa)", "probability density (GPa$^{-1}$)"),
                "temperature": ("$T$ (K)", "probability density (K$^{-1}$)"),
                "velocity_x": ("$u_x$ (m/s)", "probability density (s/m)"),
                "velocity_y": ("$u_y$ (m/s)", "probability density (s/m)")}
    for name, (xlabel, ylabel) in expected.items():
        assert (panels[name].get_xlabel(), panels[name].get_ylabel()) == (xlabel, ylabel), name
    assert not any("(1/" in ax.get_ylabel() for ax in fig.axes)


def _drawn(fig):
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    return canvas.get_renderer()


def _overlap(a, b):
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


def test_narrow_column_field_reads_well(runs):
    for args in ((), ("--arrows",)):
        fig = figure("field", runs["narrow"], *args)
        renderer = _drawn(fig)
        ax = fig.axes[0]
        width_in = ax.get_position().width * fig.get_figwidth()
        height_in = ax.get_position().height * fig.get_figheight()
        assert width_in < 0.1 * height_in, f"not a narrow column: {width_in:.2f} x {height_in:.2f} in"
        lo, hi = ax.get_xlim()
        ticks = [label.get_window_extent(renderer) for tick, label in zip(ax.get_xticks(), ax.get_xticklabels())
                 if lo <= tick <= hi and label.get_text()]
        assert ticks, "no x tick label on the narrow column"
        ticks.sort(key=lambda box: box.x0)
        for left, right in zip(ticks, ticks[1:]):
            assert right.x0 - left.x1 >= 5, f"x tick labels {left} and {right} run into each other"
        figure_box = fig.bbox
        title = ax.title if ax.get_title() else ax._left_title
        box = title.get_window_extent(renderer)
        assert box.x0 >= figure_box.x0 and box.x1 <= figure_box.x1 and box.y1 <= figure_box.y1, \
            f"title {box} leaves the figure {figure_box}"
        assert box.y0 >= ax.get_window_extent(renderer).y1, "the title overlaps the axes"
        others = [text.get_window_extent(renderer) for text in fig.texts]
        others += [artist.text.get_window_extent(renderer) for artist in ax.artists + ax.collections
                   if hasattr(artist, "text") and hasattr(artist.text, "get_window_extent")]
        for other in others:
            assert not _overlap(box, other), f"the title overlaps {other}"
        for text in fig.texts:  # the footer
            footer = text.get_window_extent(renderer)
            assert footer.x1 <= figure_box.x1 and footer.y0 >= figure_box.y0, f"footer {footer} leaves the figure"
            assert footer.y1 <= ax.xaxis.label.get_window_extent(renderer).y0, "footer overlaps the x label"
