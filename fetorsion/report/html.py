"""The report as one self-contained web page: the Markdown report's sections and tables, with
interactive figures in place of the still pictures.

Everything is embedded (plotly.js, the data, the remaining PNGs as data URIs), so the file
opens offline anywhere. Plotly draws every figure: the Campbell diagram, the forced
response, the sensitivity and the f1 studies (Monte Carlo histogram, Sobol' indices) with hover text, and each FE mode shape as a 3D surface that
turns and zooms, coloured by displacement, with a deformation-scale slider and an animation
of the oscillation (a few lines of glue that move the surface by ``scale * sin(phase)`` of
the mode shape through ``Plotly.restyle``; the rendering is Plotly's).
"""

from __future__ import annotations

import base64
import html
import json
import re
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .outcomes import CampbellOutcome, FEOutcome, RunOutcome, SensitivityOutcome, TransientOutcome

if TYPE_CHECKING:
    from ..excitation.campbell import CampbellResult

# The faces of a tetrahedron by its corner indices (VTK order: corners 0-3).
_TET_FACES = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])


def surface(tets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The boundary of a tet mesh: (used node indices, triangles into them), corners only.

    A face lies on the boundary when no second tetrahedron shares it.
    """
    faces = tets[:, :4][:, _TET_FACES].reshape(-1, 3)
    key = np.sort(faces, axis=1)
    _, first, counts = np.unique(key, axis=0, return_index=True, return_counts=True)
    outer = faces[first[counts == 1]]
    used, tri = np.unique(outer, return_inverse=True)
    return used, tri.reshape(-1, 3)


def _b64(array) -> str:
    return base64.b64encode(np.ascontiguousarray(array, dtype=np.float32).tobytes()).decode()


def fe_modes_view(fe: FEOutcome) -> str:
    """The one 3D view of an FE outcome's pictured modes (:func:`mode_view`); "" where the outcome
    has no pictures or no mesh (read back from results.json)."""
    res = fe.modal
    if not fe.images or res.mesh is None:
        return ""
    picks = [img.mode for img in fe.images]
    return mode_view(res.mesh.nodes, res.mesh.tets, [res.shapes[j] for j in picks],
                     [f"mode {j + 1}: {res.frequencies_hz[j]:.1f} Hz, {res.kinds[j]}" for j in picks], "modes")


def mode_view(nodes: np.ndarray, tets: np.ndarray, shapes: list[np.ndarray], titles: list[str], div: str) -> str:
    """HTML of one interactive 3D view of several mode shapes (one mode shown at a time).

    Parameters
    ----------
    nodes : ndarray (N, 3)
        Mesh node coordinates, m (shown in mm).
    tets : ndarray (M, 10 or 4)
        Tetrahedra.
    shapes : list of ndarray (N, 3)
        Mode shapes at the nodes (any scaling: each is shown with its largest displacement
        at 8 % of the crank length times the slider's scale).
    titles : list of str
        One label per mode.
    div : str
        The HTML id of the view.
    """
    import plotly.graph_objects as go

    used, tri = surface(tets)
    xyz = nodes[used] * 1e3
    extent = float(np.ptp(xyz[:, 0]))
    modes = []
    for u in shapes:
        u = u[used] * 1e3
        peak = float(np.linalg.norm(u, axis=1).max()) or 1.0
        u = u * (0.08 * extent / peak)
        modes.append({"u": _b64(u), "mag": _b64(np.linalg.norm(u, axis=1) / (0.08 * extent))})
    fig = go.Figure(go.Mesh3d(x=xyz[:, 0], y=xyz[:, 1], z=xyz[:, 2], i=tri[:, 0], j=tri[:, 1], k=tri[:, 2],
                              intensity=np.zeros(len(xyz)), intensitymode="vertex", colorscale="Turbo",
                              cmin=0.0, cmax=1.0, colorbar={"title": "|u| / max"}, flatshading=False,
                              lighting={"ambient": 0.55, "diffuse": 0.7, "specular": 0.2},
                              hoverinfo="skip"))
    fig.update_layout(scene={"aspectmode": "data", "xaxis_title": "x [mm]", "yaxis_title": "y [mm]",
                             "zaxis_title": "z [mm]"}, margin={"l": 0, "r": 0, "t": 30, "b": 0}, height=520,
                      title=titles[0] if titles else "")
    plot = fig.to_html(full_html=False, include_plotlyjs=False, div_id=div)
    options = "".join(f'<option value="{j}">{html.escape(t)}</option>' for j, t in enumerate(titles))
    data = json.dumps({"base": _b64(xyz), "modes": modes, "titles": titles})
    return f"""<div class="modeview">
<label>mode <select id="{div}-mode">{options}</select></label>
<label>deformation scale <input id="{div}-scale" type="range" min="0" max="3" step="0.1" value="1"></label>
<button id="{div}-play">play</button>
{plot}
<script>fetorsionModeView("{div}", {data});</script>
</div>"""


# The glue: decode the embedded arrays once, then restyle the mesh's coordinates each frame.
_MODE_VIEW_JS = """
function fetorsionDecode(b64) {
  const bytes = Uint8Array.from(atob(b64), c => c.charCodeAt(0));
  return new Float32Array(bytes.buffer);
}
function fetorsionModeView(div, data) {
  const base = fetorsionDecode(data.base), n = base.length / 3;
  const modes = data.modes.map(m => ({u: fetorsionDecode(m.u), mag: fetorsionDecode(m.mag)}));
  const sel = document.getElementById(div + "-mode"), scale = document.getElementById(div + "-scale");
  const play = document.getElementById(div + "-play");
  let mode = 0, phase = Math.PI / 2, running = false;  // still at full deflection until played
  function draw() {
    const u = modes[mode].u, s = Number(scale.value) * Math.sin(phase);
    const x = new Float32Array(n), y = new Float32Array(n), z = new Float32Array(n);
    for (let i = 0; i < n; i++) {
      x[i] = base[3 * i] + s * u[3 * i];
      y[i] = base[3 * i + 1] + s * u[3 * i + 1];
      z[i] = base[3 * i + 2] + s * u[3 * i + 2];
    }
    Plotly.restyle(div, {x: [x], y: [y], z: [z], intensity: [modes[mode].mag]}, [0]);
  }
  sel.onchange = () => { mode = Number(sel.value); Plotly.relayout(div, {title: data.titles[mode]}); draw(); };
  scale.oninput = draw;
  play.onclick = () => { running = !running; play.textContent = running ? "pause" : "play"; };
  setInterval(() => { if (running) { phase += Math.PI / 8; draw(); } }, 120);
  draw();
}
"""


def campbell_figure(camp: CampbellResult, div: str) -> str:
    """The Campbell diagram: mode lines, order lines, crossings sized by severity (hover: mode,
    order, rpm, severity)."""
    import plotly.graph_objects as go

    lo, hi = camp.speed_range_rpm
    top = 1.15 * hi
    fig = go.Figure()
    rpm = np.array([0.0, top])
    for q in camp.orders:
        fig.add_trace(go.Scatter(x=rpm, y=q * rpm / 60.0, mode="lines", line={"color": "#bbbbbb", "width": 1},
                                 name=f"order {q:g}", hovertemplate=f"order {q:g}<extra></extra>", showlegend=False))
    for j, f in enumerate(camp.frequencies_hz):
        fig.add_trace(go.Scatter(x=rpm, y=[f, f], mode="lines", name=f"mode {j + 1}: {f:.1f} Hz"))
    rows = [r for r in camp.crossings if r.in_range]
    if rows:
        sev = np.array([r.severity for r in rows])
        size = 6 + 30 * np.sqrt(sev / sev.max()) if sev.max() > 0 else np.full(len(rows), 8.0)
        fig.add_trace(go.Scatter(
            x=[r.rpm for r in rows], y=[camp.frequencies_hz[r.mode - 1] for r in rows], mode="markers",
            marker={"size": size, "color": sev, "colorscale": "Reds", "line": {"width": 1, "color": "black"}},
            name="crossings", customdata=[[r.mode, r.order, r.rpm, r.severity] for r in rows],
            hovertemplate="mode %{customdata[0]}<br>order %{customdata[1]}<br>%{customdata[2]:.0f} rpm"
                          "<br>severity %{customdata[3]:.4g} " + camp.severity_unit.split(":")[0] + "<extra></extra>"))
    fig.add_vrect(x0=lo, x1=hi, fillcolor="#2a9d8f", opacity=0.08, line_width=0)
    fig.update_layout(title=f"{camp.name}: Campbell diagram ({camp.source})", xaxis_title="engine speed [rpm]",
                      yaxis_title="frequency [Hz]", xaxis_range=[0, top],
                      yaxis_range=[0, 1.1 * float(np.max(camp.frequencies_hz))], height=520)
    return fig.to_html(full_html=False, include_plotlyjs=False, div_id=div)


def response_figure(resp, div: str) -> str:
    """Pulley angle and twist, and the most loaded section's torque, against speed."""
    import plotly.graph_objects as go
    from plotly.subplots import make_subplots

    fig = make_subplots(rows=2, cols=1, shared_xaxes=True, vertical_spacing=0.08)
    fig.add_trace(go.Scatter(x=resp.rpm, y=resp.pulley_angle_deg, name="pulley angle (absolute)"), 1, 1)
    fig.add_trace(go.Scatter(x=resp.rpm, y=resp.pulley_twist_deg, name="pulley twist against flywheel end"), 1, 1)
    worst = int(np.argmax(resp.section_torque_nm.max(axis=0)))
    fig.add_trace(go.Scatter(x=resp.rpm, y=resp.section_torque_nm[:, worst],
                             name=f"torque, section {resp.section_labels[worst]}"), 2, 1)
    fig.update_yaxes(title_text="vibratory angle [deg]", row=1, col=1)
    fig.update_yaxes(title_text="vibratory torque [N m]", row=2, col=1)
    fig.update_xaxes(title_text="engine speed [rpm]", row=2, col=1)
    fig.update_layout(title=f"{resp.name}: forced response, ζ = {resp.damping_ratio:g}", height=620,
                      hovermode="x unified")
    return fig.to_html(full_html=False, include_plotlyjs=False, div_id=div)


def waterfall_figure(transient, max_order: float, div: str) -> str:
    """The run-up's order track as a heat map (log10 of the vibration in deg) against speed and order."""
    import plotly.graph_objects as go

    tr = transient.track
    keep = tr.orders <= max_order
    amp = np.degrees(np.abs(tr.amplitudes[:, keep])).T
    floor = amp.max() * 1e-3 if amp.size and amp.max() > 0 else 1.0
    fig = go.Figure(go.Heatmap(x=tr.rpm, y=tr.orders[keep], z=np.log10(np.maximum(amp, floor)), customdata=amp,
                               colorscale="Viridis", colorbar={"title": "log10 deg"},
                               hovertemplate="%{x:.0f} rpm<br>order %{y:g}<br>%{customdata:.4g} deg<extra></extra>"))
    fig.update_layout(title=f"{transient.name}: {transient.mode}, order track of {transient.track_station}",
                      xaxis_title="mean speed [rpm]", yaxis_title="order", height=520)
    return fig.to_html(full_html=False, include_plotlyjs=False, div_id=div)


def order_cuts_figure(transient, response, cuts, div: str) -> str:
    """Each compared order: the run-up's cut (solid) and the steady-state response (dashed)."""
    import plotly.graph_objects as go

    fig = go.Figure()
    for i, q in enumerate(dict.fromkeys(c.order for c in cuts)):
        k = int(np.flatnonzero(np.isclose(response.orders, q))[0])
        color = _PALETTE[i % len(_PALETTE)]
        fig.add_trace(go.Scatter(x=transient.track.rpm, y=np.degrees(np.abs(transient.track.at(q))),
                                 name=f"order {q:g}, run-up", line={"color": color}))
        fig.add_trace(go.Scatter(x=response.rpm, y=response.order_pulley_deg[:, k], name=f"order {q:g}, steady state",
                                 line={"color": color, "dash": "dash"}))
    fig.update_layout(title=f"{transient.name}: order cuts against the steady-state response",
                      xaxis_title="mean speed [rpm]", yaxis_title=f"{transient.track_station}: vibration [deg]",
                      height=520, hovermode="x unified", yaxis_type="log")
    return fig.to_html(full_html=False, include_plotlyjs=False, div_id=div)


#: Plotly's default colours, so that a run-up's cut and its steady state share one.
_PALETTE = ("#636efa", "#ef553b", "#00cc96", "#ab63fa", "#ffa15a", "#19d3f3")


def sensitivity_figure(sens, div: str) -> str:
    """Tornado chart: f1 at each input's bounds, largest swing on top."""
    import plotly.graph_objects as go

    rows = sorted(sens.rows, key=lambda r: r.swing_hz)
    names = [r.field for r in rows]
    fig = go.Figure()
    for key, label in (("f1_low_hz", "input at its low bound"), ("f1_high_hz", "input at its high bound")):
        fig.add_trace(go.Bar(y=names, x=[getattr(r, key) - sens.f1_hz for r in rows], base=sens.f1_hz,
                             orientation="h", name=label, customdata=[[r.low, r.high, getattr(r, key)] for r in rows],
                             hovertemplate="%{y}<br>range %{customdata[0]:g} .. %{customdata[1]:g}"
                                           "<br>f1 %{customdata[2]:.1f} Hz<extra></extra>"))
    if sens.measured_hz is not None:
        fig.add_vline(x=sens.measured_hz, line_dash="dash", annotation_text=f"measured {sens.measured_hz:g} Hz")
    fig.update_layout(barmode="overlay", title=f"{sens.name}: f1 = {sens.f1_hz:.1f} Hz ({sens.model})",
                      xaxis_title="first torsional frequency [Hz]", height=120 + 28 * len(rows))
    return fig.to_html(full_html=False, include_plotlyjs=False, div_id=div)


def montecarlo_figure(study, div: str) -> str:
    """Histogram of f1 over the Monte Carlo runs, its 5-95 % band and the measured value."""
    import plotly.graph_objects as go

    y = study.Y["f1"][np.isfinite(study.Y["f1"])]
    b = study.bands["f1"]
    fig = go.Figure(go.Histogram(x=y, nbinsx=min(60, max(10, int(np.sqrt(len(y))))), name="runs",
                                 hovertemplate="f1 %{x} Hz<br>%{y} runs<extra></extra>"))
    fig.add_vrect(x0=b["p5"], x1=b["p95"], fillcolor="#1f77b4", opacity=0.12, line_width=0,
                  annotation_text=f"5-95 %: {b['p5']:.0f}-{b['p95']:.0f} Hz")
    if study.measured_hz is not None:
        fig.add_vline(x=study.measured_hz, line_dash="dash", line_color="crimson",
                      annotation_text=f"measured {study.measured_hz:g} Hz ({study.measured_percentile():.0f} % below)")
    fig.update_layout(title=f"{study.name}: f1 over {len(y)} Monte Carlo runs ({study.model})",
                      xaxis_title="first torsional frequency [Hz]", yaxis_title="runs", height=420, showlegend=False)
    return fig.to_html(full_html=False, include_plotlyjs=False, div_id=div)


def sobol_figure(study, div: str) -> str:
    """First-order and total Sobol' indices of f1 with their confidence half-widths."""
    import plotly.graph_objects as go

    idx = study.indices["f1"]
    order = np.argsort(idx["ST"])
    names = [study.input_names[j] for j in order]
    fig = go.Figure()
    for key, label in (("S1", "first order S1"), ("ST", "total ST")):
        fig.add_trace(go.Bar(y=names, x=np.array(idx[key])[order], orientation="h", name=label,
                             error_x={"type": "data", "array": np.array(idx[f"{key}_conf"])[order]},
                             hovertemplate="%{y}<br>%{x:.3f} ± %{error_x.array:.3f}<extra>" + label + "</extra>"))
    fig.update_layout(barmode="group", title=f"{study.name}: Sobol' indices of f1 ({len(study.X)} runs, "
                                             "bars: 95 % confidence)",
                      xaxis_title="share of the variance of f1", height=160 + 30 * len(names))
    return fig.to_html(full_html=False, include_plotlyjs=False, div_id=div)


_IMAGE = re.compile(r'<img alt="[^"]*" src="([^"]+\.png)"\s*/?>')


def page(title: str, markdown_text: str, figures: dict[str, str], folder: Path) -> str:
    """The whole page: the Markdown converted, each ``![](NAME.png)`` replaced by the figure
    ``figures[NAME.png]`` when there is one, else the PNG from ``folder`` as a data URI."""
    import markdown
    from plotly.offline import get_plotlyjs

    body = markdown.markdown(markdown_text, extensions=["tables", "fenced_code"])

    def replace(m):
        name = m.group(1)
        if name in figures:
            return figures[name]
        path = folder / name
        if not path.exists():
            return m.group(0)
        data = base64.b64encode(path.read_bytes()).decode()
        return f'<img alt="{html.escape(name)}" src="data:image/png;base64,{data}">'

    body = _IMAGE.sub(replace, body)
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>{html.escape(title)}</title>
<style>
body {{ font-family: system-ui, sans-serif; max-width: 1200px; margin: 2em auto; padding: 0 1em; color: #222; }}
table {{ border-collapse: collapse; margin: 1em 0; }} td, th {{ border: 1px solid #ccc; padding: 0.25em 0.6em; }}
pre {{ background: #f6f6f6; padding: 0.8em; overflow-x: auto; }} img {{ max-width: 100%; }}
.modeview label {{ margin-right: 1.5em; }}
</style>
<script>{get_plotlyjs()}</script>
<script>{_MODE_VIEW_JS}</script>
</head><body>
{body}
</body></html>
"""


def report_html(run: RunOutcome, folder: Path) -> str:
    """The run's report as a web page: the Markdown report with its pictures made interactive
    (Campbell, forced response, sensitivity, the FE mode shapes in one 3D view)."""
    from .markdown import report_markdown

    figures = {}
    camp = run.campbell
    if isinstance(camp, CampbellOutcome):
        figures[camp.campbell_image] = campbell_figure(camp.campbell, "campbell")
        figures[camp.response_image] = response_figure(camp.response, "response")
    tra = run.transient
    if isinstance(tra, TransientOutcome) and isinstance(camp, CampbellOutcome):
        figures[tra.waterfall_image] = waterfall_figure(tra.transient, float(np.max(camp.response.orders)), "waterfall")
        if tra.cuts:
            figures[tra.cuts_image] = order_cuts_figure(tra.transient, camp.response, tra.cuts, "order_cuts")
    sens = run.sensitivity
    if isinstance(sens, SensitivityOutcome):
        figures[sens.image] = sensitivity_figure(sens.sensitivity, "sensitivity")
        studies, images = sens.studies, sens.study_images
        if studies and "f1" in studies["montecarlo"].Y:  # a study read back without its runs: its picture
            figures[images["montecarlo"]] = montecarlo_figure(studies["montecarlo"], "f1_montecarlo")
            if "not_computed" not in studies["sobol"].indices["f1"]:
                figures[images["sobol"]] = sobol_figure(studies["sobol"], "f1_sobol")
    fe = run.fe
    view = "" if fe is None else (fe.view_html or fe_modes_view(fe))
    if view:  # else (read back, the mesh not kept) the pictures
        figures[fe.images[0].file] = view
        for img in fe.images[1:]:
            figures[img.file] = ""  # all modes are in the one 3D view
    return page(run.crank.name, report_markdown(run), figures, folder)
