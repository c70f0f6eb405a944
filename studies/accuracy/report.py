"""The accuracy study's report, docs/accuracy.md: its prose comes from the template accuracy.md.in
beside this module (blocks of string.Template text, filled with the study's numbers, tables and
figures), its part sections from sections.py; this module assembles the document: the header, the
findings, what was chosen and why, the sections, the plateau figure and the run time.

Part of the study in studies/accuracy/ of the checkout, run as `studies/accuracy/accuracy-study`.
"""

import re
import string
import time
from pathlib import Path

from .figures import figure_windows
from .formats import cells_text, h_text, md_table
from .plan import MAIN_SHAPE, NS, PARTS, ROOT

TEMPLATE = Path(__file__).resolve().with_name("accuracy.md.in")


class Prose:
    """The blocks of the report's template: `@@ NAME` lines open them, a backslash at a line's end
    continues it on the next line, and each block is a string.Template."""

    def __init__(self, path=TEMPLATE):
        self.path = Path(path)
        text = self.path.read_text(encoding="utf-8").replace("\\\n", "")
        self.blocks, name, lines = {}, None, []
        for line in text.split("\n") + ["@@ "]:
            if line.startswith("@@ "):
                if name:
                    self.blocks[name] = string.Template("\n".join(lines).strip("\n"))
                name, lines = line[3:].strip(), []
            else:
                lines.append(line)

    def __call__(self, block, /, **values):
        """The block filled with these values (every placeholder must have one)."""
        try:
            return self.blocks[block].substitute(values)
        except KeyError as e:
            raise KeyError(f"{self.path.name}: block {block!r}: no value for {e}") from None

    def heading(self, name):
        """The heading that opens block NAME, without its '#'s."""
        return self.blocks[name].template.split("\n", 1)[0].lstrip("#").strip()


def anchor(heading):
    """The link target a markdown renderer (GitHub's) gives a heading."""
    return re.sub(r"[^\w\- ]", "", heading.lower()).replace(" ", "-")


class Report:
    """Collects the document's sections, the findings for its summary, the figures it links, the
    plateaus the last figure shows and the answer's table for the top of the document."""

    def __init__(self, docs, plan, study, prose=None):
        self.docs, self.plan, self.study = docs, plan, study
        self.text = prose or Prose()
        self.sections, self.findings, self.figures = [], [], []
        self.window_cases = []   # (title, Outcome) of each plateau the windows figure shows
        self.answer = None       # the answer's table and its note, for the top of the document

    def figure(self, name, draw, *args):
        """Draws docs/accuracy_NAME.png; its markdown image link."""
        path = self.docs / f"accuracy_{name}.png"
        draw(*args, path)
        self.figures.append(path)
        return f"![{name}](accuracy_{name}.png)"

    def find(self, block, /, **values):
        """Adds the finding of template block finding.BLOCK."""
        self.findings.append(self.text(f"finding.{block}", **values))


def choices(report, parts):
    """What was chosen and why, for the parts that ran: the rows of the template's choices blocks."""
    plan, text = report.plan, report.text
    rows = []
    if "solid" in parts:
        extra = (" " + text("choices.solid.extra_cell", cell=h_text(plan.solid_extra_cell))
                 if plan.solid_extra_cell else "")
        rows.append(text("choices.solid", width=h_text(plan.solid_width), height_mm=f"{plan.solid_height * 1e3:g}",
                         columns=f"{plan.solid_width / plan.solid_cells[0]:g} cells at {h_text(plan.solid_cells[0])}",
                         end_ns=f"{plan.solid_end / NS:g}", cells=cells_text(plan.solid_cells), extra_cell=extra))
    if "porous" in parts:
        rows.append(text("choices.porous", r=h_text(plan.void_radius), width=h_text(plan.porous_width),
                         wider=", ".join(f"{h_text(w)} at delta {d:g}" for d, w in plan.porous_width_for.items()),
                         height=h_text(plan.porous_height),
                         seeds=", ".join(f"delta {d:g}: {n}" for d, n in plan.porous_seeds.items())))
    if "sensitivity" in parts:
        rows.append(text("choices.sensitivity", delta=f"{plan.sensitivity_delta:g}", h=h_text(plan.sensitivity_cell),
                         seeds=plan.sensitivity_seeds))
    if "answer" in parts:
        rows.append(text("choices.answer", width=h_text(plan.answer_width), height_mm=f"{plan.answer_height * 1e3:g}",
                         end_ns=f"{plan.answer_end / NS:g}", cells=cells_text(plan.answer_cells),
                         seeds=plan.answer_seeds))
    return text("choices", rows="\n".join(rows))


def _and(words):
    words = list(words)
    return ", ".join(words[:-1]) + " and " + words[-1] if len(words) > 1 else "".join(words)


def shape_note(report, parts):
    """The shape function, time step and viscosity every part runs, as the simulator resolves them
    (automatic cfl and av_linear), and the comparison shapes of the parts that ran."""
    study, plan, text = report.study, report.plan, report.text

    def resolved(key, shape=MAIN_SHAPE, *more):
        return f"{study.defaults([f'shape_function={shape}', *more])[key]:g}"

    def compared(shapes):
        return dict(shapes=_and(shapes), cfls=", ".join(f"{shape} {resolved('cfl', shape)}" for shape in shapes))

    comparisons = ""
    solid = [shape for shape in plan.solid_shapes if shape != MAIN_SHAPE]
    if "solid" in parts and solid:
        other_ppc = [f"{ppc:g}" for ppc in plan.solid_ppc if ppc != 2]   # at 1000 m/s (plan.solid_series)
        other_ppc = (" " + text("parts.solid_ppc", ppc=_and(other_ppc))
                     if other_ppc and 1000.0 in plan.solid_speeds else "")
        comparisons += " " + text("parts.solid_shapes", other_ppc=other_ppc, **compared(solid))
    if "porous" in parts and plan.porous_shapes_at in plan.porous_deltas:
        delta = f"{plan.porous_shapes_at:g}"
        porous = list(dict.fromkeys(c.shape for c in plan.porous_comparisons if c.shape != MAIN_SHAPE))
        if porous:
            comparisons += " " + text("parts.porous_shapes", delta=delta, **compared(porous))
        for c in plan.porous_comparisons:
            if c.scene:   # not only another shape: say what else it sets
                comparisons += " " + text("parts.porous_variant", delta=delta, label=c.label, shape=c.shape,
                                          keys=c.keys_text)
    every_solid, one_porous = "porosity=1", f"porosity={plan.sensitivity_delta:g}"
    return text("parts.shapes", main_shape=MAIN_SHAPE, cfl=resolved("cfl"),
                av_solid=resolved("av_linear", MAIN_SHAPE, every_solid),
                av_porous=resolved("av_linear", MAIN_SHAPE, one_porous),
                smoothing_solid=study.defaults([f"shape_function={MAIN_SHAPE}", every_solid])["volumetric_smoothing"],
                smoothing_porous=study.defaults([f"shape_function={MAIN_SHAPE}", one_porous])["volumetric_smoothing"],
                comparisons=comparisons)


def run_time(report, parts, elapsed):
    """(the Run time section, the simulator wall time of every distinct run in s)."""
    study = report.study
    runs = study.all_runs()
    rows, total_wall, total_ps = [], 0.0, 0.0
    for part in parts:
        mine = {d: s for d, s in runs.items() if d.relative_to(study.out).parts[0] == part}
        if not mine:
            continue
        wall = sum(s["wall_seconds"] for s in mine.values())
        ps = sum(s["material_points"] * s["steps"] for s in mine.values())
        total_wall += wall
        total_ps += ps
        rows.append([part, len(mine), f"{wall:.0f}", f"{ps:.3g}", f"{ps / wall:.3g}" if wall else "-"])
    rows.append(["all", sum(int(r[1]) for r in rows), f"{total_wall:.0f}", f"{total_ps:.3g}",
                 f"{total_ps / total_wall:.3g}" if total_wall else "-"])
    table = md_table(["part", "runs", "wall (s)", "point-steps", "point-steps/s"], rows)
    section = report.text("run_time", table=table, elapsed=f"{elapsed:.0f}", made=len(study.ran),
                          binaries=", ".join(f"{name} {count}" for name, count in sorted(study.made_by().items())))
    return section, total_wall


def write_document(report, parts, elapsed, fingerprint):
    """Writes DOCS/accuracy.md (and the plateau figure); its path."""
    study, plan, text = report.study, report.plan, report.text
    version, digest = fingerprint
    run_time_section, total_wall = run_time(report, parts, elapsed)
    chunks = [text("head", quick_flag=" --quick" if plan.quick else "", date=time.strftime("%Y-%m-%d"),
                   version=version, digest=digest, binary_dir=_display_path(study.binary.parent),
                   minutes=f"{total_wall / 60:.0f}", out=_display_path(study.out))]
    if plan.quick:
        chunks.append(text("quick"))
    chunks.append(text("parts", shapes=shape_note(report, parts),
                       links=", ".join(f"[{p}](#{anchor(text.heading(p))})" for p in parts)))
    if report.answer:
        chunks.append(report.answer)
    chunks.append(text("findings", items="\n".join(f"- {f}" for f in report.findings)))
    if not plan.quick and list(parts) == list(PARTS):
        chunks.append(text("reading"))
    chunks.append(choices(report, parts))
    for section in report.sections:
        chunks += section
    if report.window_cases:
        chunks.append(text("plateaus", figure=report.figure("windows", figure_windows, report.window_cases)))
    if study.failures:
        chunks.append(text("failures", list="\n".join(
            text("failure", part=f.series.part, name=f.series.name, message=f.message) for f in study.failures)))
    chunks.append(run_time_section)
    path = report.docs / "accuracy.md"
    path.write_text("\n\n".join(chunk.strip("\n") for chunk in chunks if chunk.strip("\n")) + "\n")
    return path


def _display_path(path):
    """A path inside the checkout relative to it, any other as it is."""
    try:
        return str(Path(path).resolve().relative_to(ROOT))
    except ValueError:
        return str(path)
