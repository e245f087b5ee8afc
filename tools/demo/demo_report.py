#!/usr/bin/env python3
"""Report of the closed-loop demonstration (make demo) and of the robustness campaign.

usage: demo_report.py [DEMO_DIR]          (default: build/demo of this repository)
       demo_report.py --robustness ROBUST_DIR

Reads what build/host/qfoc_demo writes (summary.json; per scenario metrics.json,
trace.csv, zoom.csv and an optional comparison trace) and writes static HTML pages
with PNG plots:

  DEMO_DIR/index.html             summary table, speed thumbnails, robustness summary
  DEMO_DIR/<scenario>/index.html  description, metrics with targets, plots, CSV links
  DEMO_DIR/<scenario>/*.png       plots, next to the CSV files

It prints the metrics table (value, target, PASS/FAIL/info), one verdict line per
scenario and the absolute path of index.html.  A metric fails when its pass flag is
false or when its value lies outside [min, max] (a missing value fails a target); a
disagreement between flag and numbers is reported on stderr.  Exit status: 0 when
every scenario passes, 1 when one fails (the report is still written), 2 on missing
or malformed input.

With --robustness it reads ROBUST_DIR/campaign.json and runs.csv and writes
ROBUST_DIR/index.html: success rate, parameter ranges, criteria, worst cases with
their replay command, scatter plots against each randomised parameter, and the
plots of every replayed case (ROBUST_DIR/replay_<seed>/, laid out like a scenario).
runs.csv needs seed, the eight parameter columns and success; the result columns
(t_reach_s, angle_err_max_deg, ...) are shown where present.  Relative parameter
errors (rs_err .. psi_err and their ranges) are fractions, shown in %.  Exit status:
0 when the success rate is 100 %, 1 otherwise, 2 on missing or malformed input.

The pages use no script and no external resource.
"""
import argparse
import csv
import glob
import html
import json
import math
import multiprocessing
import os
import re
import sys
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

MAX_POINTS = 4000            # points per line in the full-time plots
FIG_W = 11.0                 # figure width, inches; fixed margins align the time axes
LEFT_IN, RIGHT_IN = 1.3, 2.35
STATES = ["PRECHARGE", "STOP", "RUN", "ERROR"]
SUBS = ["-", "BUS_WAIT", "CALIB", "ALIGN", "OPEN_LOOP", "CLOSED_LOOP", "STOPPING", "CATCH"]
FAULTS = ["OC", "OV", "UV", "OT_IPM", "OT_PCB", "STALL", "PHASE", "OFFSET", "LINK", "PARAM", "TIMING"]
TRACE_COLS = ["t_s", "target_rpm", "speed_ref_rpm", "speed_est_rpm", "speed_true_rpm",
              "id_ref_a", "iq_ref_a", "id_a", "iq_a", "id_true_a", "iq_true_a",
              "angle_err_deg", "i_peak_a", "iu_a", "iv_a", "iw_a", "duty_u", "duty_v",
              "duty_w", "pwm_on", "vdc_v", "vdc_meas_v", "t_ipm_c", "load_nm", "torque_nm",
              "state", "sub", "fault"]
ZOOM_COLS = ["t_s", "iu_a", "iv_a", "iw_a", "iu_meas_a", "iv_meas_a", "duty_u", "duty_v",
             "duty_w", "pwm_on"]
RUN_PARAMS = [("rs_err", "R_s error", "%", 100.0), ("ld_err", "L_d error", "%", 100.0),
              ("lq_err", "L_q error", "%", 100.0), ("psi_err", "psi_f error", "%", 100.0),
              ("load_nm", "load torque", "N m", 1.0), ("vdc_v", "V_dc", "V", 1.0),
              ("noise_a", "current noise", "A rms", 1.0),
              ("theta0_deg", "initial angle", "deg", 1.0)]
RUN_COLS = ["seed"] + [p[0] for p in RUN_PARAMS] + ["success"]
# parameters of the campaign's axes (columns of runs.csv when the campaign has axes)
AXIS_PARAMS = [("dead_time_ratio", "dead time / comp.", "x", 1.0),
               ("t_break_frac", "breakaway / nominal", "%", 100.0)]
# success rate by bins of a parameter, on the axes that vary it: (column, label, unit,
# scale, bin edges in the column's units, axes)
AXIS_BINS = [("dead_time_ratio", "real dead time / the table's compensation", "x", 1.0,
              [0.0, 0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0001],
              ("dead_time", "low_flux_dead_time", "combined")),
             ("t_break_frac", "breakaway torque / nominal torque", "%", 100.0,
              [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6001], ("breakaway", "combined")),
             ("psi_err", "psi_f error (plant / table - 1)", "%", 100.0,
              [-0.1501, -0.10, -0.05, 0.0, 0.05, 0.10, 0.1501], ("flux_rs", "combined"))]
RUN_RESULTS = [("t_closed_loop_s", "t closed loop", "s"), ("t_reach_s", "t reach", "s"),
               ("overshoot_pct", "overshoot", "%"), ("ss_err_rpm", "ss error", "rpm"),
               ("ss_err_pct", "ss error", "%"), ("ss_err_max_pct", "max ss error", "%"),
               ("angle_err_rms_deg", "angle err. RMS", "deg"),
               ("angle_err_max_deg", "max angle err.", "deg"), ("i_peak_a", "i peak", "A")]
RANGES = {"rs": ("R_s error", "rel"), "ld": ("L_d error", "rel"), "lq": ("L_q error", "rel"),
          "psi_f": ("psi_f (magnet flux) error", "rel"),
          "load_frac": ("load torque, fraction of nominal", "frac"),
          "load_nm": ("load torque", "N m"),
          "vdc_v": ("DC-bus voltage", "V"), "noise_a_rms": ("current-sensor noise", "A rms"),
          "theta0_deg": ("initial rotor angle", "deg"),
          "dead_time_ratio": ("real dead time / the table's compensation", "x"),
          "t_break_frac": ("breakaway torque, fraction of nominal", "frac")}
CSS = """
body{font-family:system-ui,sans-serif;margin:1.2em auto;max-width:1150px;color:#222;
 padding:0 1em;line-height:1.35}
h1{font-size:1.5em;margin:.2em 0}h2{font-size:1.15em;margin-top:1.4em;
 border-bottom:1px solid #ccc}
table{border-collapse:collapse;margin:.5em 0;font-size:.92em}
th,td{border:1px solid #ccc;padding:.25em .55em;text-align:left;vertical-align:top}
th{background:#f2f2f2}td.num{text-align:right;font-variant-numeric:tabular-nums}
.pass{background:#d7f5d7;color:#0b5a0b;font-weight:bold}
.fail{background:#f9d2d2;color:#8a0000;font-weight:bold}
.info{background:#eee;color:#555}
.badge{padding:.1em .5em;border-radius:.3em;font-size:.8em;vertical-align:middle}
.mpass{color:#0b5a0b}.mfail{color:#8a0000;font-weight:bold}.minfo{color:#555}
figure{margin:1em 0}figure img{max-width:100%;border:1px solid #ddd}
figcaption{font-size:.9em;color:#444}
.thumbs{display:flex;flex-wrap:wrap;gap:.8em}
.thumbs figure{width:350px;margin:0}.thumbs img{width:350px}
.wide{overflow-x:auto}code,.mono{font-family:ui-monospace,monospace;font-size:.9em}
.small{font-size:.85em;color:#555}.box{border:1px solid #ccc;padding:.5em 1em;
 background:#fafafa}
"""


class InputError(Exception):
    """Missing or malformed input (exit status 2)."""


def warn(msg):
    """Print a warning about inconsistent input to stderr."""
    print("demo_report: warning: " + msg, file=sys.stderr)


def esc(x):
    """HTML-escape any value."""
    return html.escape(str(x), quote=True)


def fnum(v):
    """Format a measured value with about four significant digits, None -> n/a."""
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "n/a"
    if isinstance(v, bool) or isinstance(v, int):
        return str(int(v))
    a = abs(v)
    if a == 0:
        return "0"
    if a >= 1e6 or a < 1e-3:
        return f"{v:.3e}"
    text = f"{v:.{max(0, 3 - int(math.floor(math.log10(a))))}f}"
    return text.rstrip("0").rstrip(".") if "." in text else text


def with_unit(text, unit):
    """Join a number and its unit."""
    return f"{text} {unit}" if unit and text not in ("n/a", "-") else text


def load_json(path):
    """Read a JSON file or raise InputError."""
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except OSError as e:
        raise InputError(f"{path}: cannot read ({e.strerror})")
    except ValueError as e:
        raise InputError(f"{path}: malformed JSON ({e})")


def load_csv(path, required, text=()):
    """Read a CSV with a header into {column: list of floats}.  Required columns must
    hold numbers ("nan" or empty where undefined); columns named in `text`, and other
    columns that do not parse, are kept as strings."""
    try:
        with open(path, newline="", encoding="utf-8") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        raise InputError(f"{path}: cannot read ({e.strerror})")
    if len(rows) < 2:
        raise InputError(f"{path}: no data rows")
    head = [h.strip() for h in rows[0]]
    missing = [c for c in required if c not in head]
    if missing:
        raise InputError(f"{path}: missing columns {', '.join(missing)}")
    rows = [r for r in rows[1:] if r]
    for n, r in enumerate(rows, 2):
        if len(r) != len(head):
            raise InputError(f"{path}:{n}: {len(r)} fields, header has {len(head)}")
    cols = {}
    for j, name in enumerate(head):
        raw = [r[j].strip() for r in rows]
        cols[name] = raw
        if name in text:
            continue
        try:
            cols[name] = [float(x) if x else math.nan for x in raw]
        except ValueError:
            if name in required:
                bad = next(i for i, x in enumerate(raw) if not _isfloat(x))
                raise InputError(f"{path}:{bad + 2}: column {name}: not a number: "
                                 f"{raw[bad]!r}")
    return cols


def _isfloat(x):
    """True if x parses as a float (or is empty)."""
    try:
        float(x or "0")
        return True
    except ValueError:
        return False


# ------------------------------------------------------------------ verdicts
def metric_status(m, where):
    """PASS, FAIL or info for one metric; the stricter of the file's and the numbers' view."""
    lo, hi, v = m.get("min"), m.get("max"), m.get("value")
    if isinstance(v, float) and not math.isfinite(v):
        v = None
    if lo is None and hi is None:
        computed = None
    elif v is None:
        computed = False
    else:
        computed = (lo is None or v >= lo) and (hi is None or v <= hi)
    given = m.get("pass", computed)
    if given != computed:
        warn(f"{where}: metric {m.get('key')}: pass is {json.dumps(given)}, value "
             f"{fnum(v)} against target {target_text(m)} gives {json.dumps(computed)}")
    if given is False or computed is False:
        return "FAIL"
    return "info" if given is None and computed is None else "PASS"


def target_text(m):
    """Target of a metric: '<= 3.0 s', '2.0 .. 3.0 s', '>= 1 rpm' or '-'."""
    lo, hi, unit = m.get("min"), m.get("max"), m.get("unit") or ""
    if lo is not None and hi is not None:
        t = f"{lo} .. {hi}"
    elif hi is not None:
        t = f"<= {hi}"
    elif lo is not None:
        t = f">= {lo}"
    else:
        return "-"
    return with_unit(t, unit)


def load_meta(sdir):
    """Read and check <scenario>/metrics.json; add status fields and the verdict."""
    path = os.path.join(sdir, "metrics.json")
    meta = load_json(path)
    if not isinstance(meta, dict) or not isinstance(meta.get("metrics"), list):
        raise InputError(f"{path}: expected an object with a 'metrics' list")
    meta.setdefault("scenario", os.path.basename(os.path.normpath(sdir)))
    meta.setdefault("title", meta["scenario"])
    for m in meta["metrics"]:
        if not isinstance(m, dict) or "key" not in m or "value" not in m:
            raise InputError(f"{path}: every metric needs 'key' and 'value'")
        if m["value"] is not None and not isinstance(m["value"], (int, float)):
            raise InputError(f"{path}: metric {m['key']}: value is not a number")
        m.setdefault("label", m["key"])
        m["status"] = metric_status(m, path)
    for ev in meta.get("events") or []:
        if not isinstance(ev.get("t_s"), (int, float)):
            raise InputError(f"{path}: event without numeric t_s")
    z = meta.get("zoom")
    if z is not None and not all(isinstance(z.get(k), (int, float)) for k in ("t0_s", "t1_s")):
        raise InputError(f"{path}: zoom needs numeric t0_s and t1_s")
    failed = [m["label"] for m in meta["metrics"] if m["status"] == "FAIL"]
    ok = not failed
    if "pass" in meta and meta["pass"] != ok:
        warn(f"{path}: pass is {json.dumps(meta['pass'])} but {len(failed)} metric(s) fail")
        if meta["pass"] is not True and ok:
            ok, failed = False, ["verdict of metrics.json"]
    meta["verdict"] = "PASS" if ok else "FAIL"
    meta["failed"] = failed
    meta["dir"] = sdir
    return meta


# ------------------------------------------------------------------ plotting helpers
def decimate(t, y, limit=MAX_POINTS):
    """Reduce a series to about `limit` points keeping the min and max of each bucket."""
    n = len(t)
    if n <= limit:
        return t, y
    size = math.ceil(2 * n / limit)
    tx, yx = [], []
    for i0 in range(0, n, size):
        chunk = y[i0:i0 + size]
        fin = [v for v in chunk if v == v]
        if not fin:
            tx.append(t[i0])
            yx.append(math.nan)
            continue
        lo, hi = min(fin), max(fin)
        ilo, ihi = chunk.index(lo), chunk.index(hi)
        for i in sorted({ilo, ihi}):
            tx.append(t[i0 + i])
            yx.append(chunk[i])
    return tx, yx


def steps(t, y):
    """Change points of a piecewise-constant series (for drawstyle steps-post)."""
    tx, yx = [t[0]], [y[0]]
    for i in range(1, len(y)):
        if y[i] != y[i - 1]:
            tx.append(t[i])
            yx.append(y[i])
    tx.append(t[-1])
    yx.append(y[-1])
    return tx, yx


def intervals(t, flags):
    """(start, width) pairs of the runs where flags is true, sample-and-hold."""
    dt = t[1] - t[0] if len(t) > 1 else 1e-3
    out, start = [], None
    for ti, f in zip(t, flags):
        if f and start is None:
            start = ti
        elif not f and start is not None:
            out.append((start, ti - start))
            start = None
    if start is not None:
        out.append((start, t[-1] + dt - start))
    return out


def varies(y):
    """True when the finite values of y span more than a rounding error."""
    fin = [v for v in y if v == v]
    return bool(fin) and max(fin) - min(fin) > 1e-6 * max(1.0, abs(max(fin)))


def new_fig(ratios, height, sharex=True):
    """Figure with one column of panels and fixed margins (inches)."""
    fig = plt.figure(figsize=(FIG_W, height))
    gs = fig.add_gridspec(len(ratios), 1, height_ratios=ratios, hspace=0.32 if sharex else 0.5,
                          left=LEFT_IN / FIG_W, right=1 - RIGHT_IN / FIG_W,
                          bottom=0.5 / height, top=1 - 0.32 / height)
    axes = []
    for i in range(len(ratios)):
        ax = fig.add_subplot(gs[i], sharex=axes[0] if axes and sharex else None)
        ax.grid(True, alpha=0.3)
        axes.append(ax)
    for ax in axes[:-1] if sharex else []:
        ax.tick_params(labelbottom=False)
    return fig, axes


def line(ax, tr, col, label, **kw):
    """Plot one trace column against time, decimated."""
    t, y = decimate(tr["t_s"], tr[col])
    kw.setdefault("lw", 1.0)
    ax.plot(t, y, label=label, **kw)


def legend(ax, **kw):
    """Legend in the right margin, long labels wrapped."""
    handles, labels = ax.get_legend_handles_labels()
    ax.legend(handles, [textwrap.fill(x, 30) for x in labels], loc="upper left",
              bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False, **kw)


def mark_events(axes, events, x0, x1, label_ax=None):
    """Dashed vertical markers for the events in [x0, x1] with their labels (on label_ax,
    default the first panel); labels of close events alternate sides and step down."""
    label_ax = label_ax or axes[0]
    placed = []
    for ev in sorted(events, key=lambda e: e["t_s"]):
        t = ev["t_s"]
        if not x0 <= t <= x1:
            continue
        for ax in axes:
            ax.axvline(t, color="0.3", ls="--", lw=0.8, zorder=1)
        near = sum(1 for p in placed if t - p < 0.025 * (x1 - x0))
        placed.append(t)
        right = near % 2 == 1 or t - x0 < 0.03 * (x1 - x0)
        label_ax.text(t, 0.97 - 0.45 * (near // 2 % 2), " " + str(ev.get("label", "")) + " ",
                      rotation=90, va="top", ha="left" if right else "right", fontsize=7,
                      color="0.2", transform=label_ax.get_xaxis_transform(),
                      bbox=dict(fc="white", ec="none", alpha=0.7, pad=1))


def save(fig, path):
    """Write a figure as PNG and free it."""
    fig.savefig(path, dpi=95)
    plt.close(fig)


# ------------------------------------------------------------------ scenario plots
class ScenarioPlots:
    """The PNG plots of one scenario directory, each written with its caption."""

    def __init__(self, meta):
        """Read trace.csv, zoom.csv and the comparison trace of a scenario."""
        self.meta, self.dir = meta, meta["dir"]
        self.tr = load_csv(os.path.join(self.dir, "trace.csv"), TRACE_COLS)
        self.counts = {"trace.csv": len(self.tr["t_s"])}
        self.cmp = None
        if meta.get("compare"):
            name = meta["compare"].get("file", "")
            self.cmp = load_csv(os.path.join(self.dir, name), ["t_s", "speed_true_rpm"])
            self.counts[name] = len(self.cmp["t_s"])
        zpath = os.path.join(self.dir, "zoom.csv")
        self.zoom = None
        if meta.get("zoom") is not None or os.path.exists(zpath):
            self.zoom = load_csv(zpath, ZOOM_COLS)
            self.counts["zoom.csv"] = len(self.zoom["t_s"])
            z = meta.get("zoom") or {"t0_s": self.zoom["t_s"][0], "t1_s": self.zoom["t_s"][-1]}
            self.zr = (z["t0_s"], z["t1_s"])
        t = self.tr["t_s"]
        self.xr = (min(t[0], 0.0), max(t[-1], float(meta.get("t_end_s") or t[-1])))
        self.events = meta.get("events") or []
        self.plots = []

    def finish(self, fig, axes, name, caption, xr, label_ax=None):
        """Common axis limits, event markers and time label; save; note the caption."""
        axes[0].set_xlim(*xr)
        mark_events(axes, self.events, *xr, label_ax)
        axes[-1].set_xlabel("time (s)")
        save(fig, os.path.join(self.dir, name))
        self.plots.append((name, caption))

    def all(self):
        """Write every plot; returns [(file, caption)] and {csv file: rows}."""
        self.speed()
        self.currents()
        self.angle()
        self.phase()
        if self.zoom:
            self.duty()
        self.vdc()
        self.state()
        return self.plots, self.counts

    def speed(self):
        """Target, ramped reference, estimated and true speed (and the comparison run)."""
        fig, axes = new_fig([1], 3.6)
        ax, tr = axes[0], self.tr
        line(ax, tr, "target_rpm", "target (LIN)", color="k", ls=":", lw=1.3, zorder=5)
        line(ax, tr, "speed_ref_rpm", "ramped reference", color="C0", ls="--", zorder=4)
        line(ax, tr, "speed_est_rpm", "estimated", color="C1", zorder=2)
        line(ax, tr, "speed_true_rpm", "true", color="C2", zorder=3)
        cap = "Speed: LIN target, ramped reference, drive's estimate and true speed (rpm)"
        if self.cmp:
            lab = self.meta["compare"].get("label", "comparison run")
            line(ax, self.cmp, "speed_true_rpm", f"true, {lab}", color="0.65", zorder=1.5)
            cap += f"; grey: true speed {lab}"
        ax.set_ylabel("speed (rpm)")
        ax.set_title(self.meta["title"], fontsize=10, loc="left")
        legend(ax)
        self.finish(fig, axes, "speed.png", cap + ".", self.xr)

    def currents(self):
        """d and q current: reference, measured by the drive, true (thin)."""
        fig, axes = new_fig([1, 1], 4.6)
        for ax, x, col in zip(axes, "dq", ("C0", "C1")):
            line(ax, self.tr, f"i{x}_ref_a", f"i{x} reference", color="k", ls="--", zorder=4)
            line(ax, self.tr, f"i{x}_a", f"i{x} measured", color=col)
            line(ax, self.tr, f"i{x}_true_a", f"i{x} true", color="C2", lw=0.6, zorder=3)
            ax.set_ylabel(f"i{x} (A)")
            legend(ax)
        self.finish(fig, axes, "currents.png", "Currents in the drive's d/q frame: references, "
                    "drive's measured values and plant's true rotor-frame currents (thin), A.",
                    self.xr)

    def angle(self):
        """Electrical angle error where defined, with the angle metrics and limit."""
        fig, axes = new_fig([1], 3.0)
        ax = axes[0]
        short = {"angle_err_rms_deg": "RMS", "angle_err_max_deg": "max"}
        am = [m for m in self.meta["metrics"] if m["key"].startswith("angle_err")
              and ("rms" in m["key"] or "max" in m["key"])]
        summary = ", ".join(
            f"{short.get(m['key'], m['label'])} {with_unit(fnum(m['value']), m.get('unit'))}"
            + (f" ({target_text(m)})" if m["status"] != "info" else "") for m in am)
        line(ax, self.tr, "angle_err_deg", "estimate - true", color="C4")
        for k, m in enumerate(x for x in am if "max" in x["key"] and x.get("max") is not None):
            lab = f"limit +/-{m['max']} deg ({short.get(m['key'], m['label'])})"
            ax.axhline(m["max"], color=f"C{3 + k}", ls=":", lw=1, label=lab)
            ax.axhline(-m["max"], color=f"C{3 + k}", ls=":", lw=1)
        if not any(v == v for v in self.tr["angle_err_deg"]):
            ax.text(0.5, 0.5, "not defined: the drive never ran in CLOSED_LOOP/STOPPING",
                    ha="center", transform=ax.transAxes, color="0.4",
                    bbox=dict(fc="white", ec="none"))
        ax.set_ylabel("angle error (deg el.)")
        ax.set_title("electrical angle error" + (f": {summary}" if summary else ""),
                     fontsize=9, loc="left")
        legend(ax)
        self.finish(fig, axes, "angle.png", "Electrical angle error, estimate minus true (deg),"
                    " shown only in CLOSED_LOOP and STOPPING" + (f"; {summary}." if summary
                                                                  else "."), self.xr)

    def phase(self):
        """Envelope of the phase currents over the run, and the zoom on the true and
        measured phase currents below it."""
        z = self.zoom
        fig, axes = new_fig([1, 1.3] if z else [1], 5.8 if z else 3.0, sharex=False)
        ax = axes[0]
        line(ax, self.tr, "i_peak_a", "max |phase current| per ms", color="C3")
        ax.set_ylabel("peak current (A)")
        cap = "Phase currents: envelope (largest |true phase current| in each ms) over the run"
        if z:
            ax.axvspan(*self.zr, color="C0", alpha=0.15, label="zoom window")
            az = axes[1]
            for c, col in zip("uvw", ("C0", "C1", "C2")):
                az.plot(z["t_s"], z[f"i{c}_a"], color=col, lw=1.0, label=f"i{c} true")
            for c, col in zip("uv", ("C0", "C1")):
                az.plot(z["t_s"], z[f"i{c}_meas_a"], ls="none", marker=".", ms=2.5, color=col,
                        alpha=0.7, label=f"i{c} measured (drive)")
            az.set_xlim(*self.zr)
            az.set_ylabel("phase current (A)")
            az.set_xlabel("time (s)")
            legend(az, markerscale=3)
            mark_events([az], self.events, *self.zr)
            cap += (f"; below: zoom {self.zr[0]:g} .. {self.zr[1]:g} s, one sample per PWM "
                    "period, true iu/iv/iw (lines) and the drive's offset-corrected samples "
                    "of iu/iv (dots)")
        legend(ax)
        self.finish(fig, axes[:1], "phase.png", cap + ".", self.xr)

    def duty(self):
        """Duty cycles in the zoom window, shaded where the inverter switches."""
        fig, axes = new_fig([1], 3.2)
        ax, z = axes[0], self.zoom
        ax.broken_barh(intervals(z["t_s"], [p > 0.5 for p in z["pwm_on"]]), (0, 1),
                       color="C2", alpha=0.12, label="PWM on",
                       transform=ax.get_xaxis_transform())
        for c, col in zip("uvw", ("C0", "C1", "C2")):
            ax.plot(z["t_s"], z[f"duty_{c}"], color=col, lw=1.0, label=f"duty {c}",
                    drawstyle="steps-post")
        ax.set_ylim(-0.03, 1.03)
        ax.set_ylabel("duty cycle (0..1)")
        legend(ax)
        self.finish(fig, axes, "duty.png", f"Duty cycles of phases u, v, w per PWM period in "
                    f"the zoom window {self.zr[0]:g} .. {self.zr[1]:g} s; shaded where the "
                    "inverter switches.", self.zr)

    def vdc(self):
        """True and measured DC-bus voltage."""
        fig, axes = new_fig([1], 3.0)
        line(axes[0], self.tr, "vdc_v", "true", color="C0")
        line(axes[0], self.tr, "vdc_meas_v", "measured (drive, filtered)", color="C1", ls="--")
        axes[0].set_ylabel("DC-bus voltage (V)")
        legend(axes[0])
        self.finish(fig, axes, "vdc.png", "DC-bus voltage: plant's true value and the drive's "
                    "filtered measurement (V).", self.xr)

    def state(self):
        """State, sub-state, PWM on and fault bits; load and temperature when they vary."""
        tr, t = self.tr, self.tr["t_s"]
        faults = [int(v) if v == v else 0 for v in tr["fault"]]
        bits = [b for b in range(max(faults).bit_length()) if any(f >> b & 1 for f in faults)]
        extra = [c for c in ("load_nm", "t_ipm_c") if varies(tr[c])]
        ratios = [1.1, 1.6, 0.5 + 0.3 * (len(bits) + 1)] + [1.0] * len(extra)
        fig, axes = new_fig(ratios, 1.2 + 1.1 * sum(ratios))
        for ax, col, names in ((axes[0], "state", STATES), (axes[1], "sub", SUBS)):
            ax.plot(*steps(t, tr[col]), drawstyle="steps-post", color="C0", lw=1.5)
            ax.set_yticks(range(len(names)))
            ax.set_yticklabels(names, fontsize=8)
            ax.set_ylim(-0.5, len(names) - 0.5)
            ax.set_ylabel("state" if col == "state" else "sub-state")
        ax = axes[2]
        rows = [("PWM on", [p > 0.5 for p in tr["pwm_on"]], "C2")]
        rows += [(FAULTS[b] if b < len(FAULTS) else f"bit{b}", [f >> b & 1 for f in faults],
                  "C3") for b in bits]
        for k, (_, flags, col) in enumerate(rows):
            ax.broken_barh(intervals(t, flags), (k - 0.35, 0.7), color=col)
        ax.set_yticks(range(len(rows)))
        ax.set_yticklabels([r[0] for r in rows], fontsize=8)
        ax.set_ylim(-0.6, len(rows) - 0.4)
        ax.set_ylabel("PWM, faults")
        ax.grid(False)
        if not bits:
            ax.text(1.01, 0.5, "no fault bit set", ha="left", va="center", fontsize=8,
                    color="0.4", transform=ax.transAxes)
        for ax, col in zip(axes[3:], extra):
            if col == "load_nm":
                line(ax, tr, "load_nm", "load torque", color="C5", lw=1.4, zorder=4)
                line(ax, tr, "torque_nm", "electromagnetic torque", color="C0", lw=0.6,
                     alpha=0.7)
                ax.set_ylabel("torque (N m)")
            else:
                line(ax, tr, "t_ipm_c", "IPM temperature", color="C3")
                ax.set_ylabel("temperature (degC)")
            legend(ax)
        names = ", ".join({"load_nm": "load and electromagnetic torque",
                           "t_ipm_c": "IPM temperature"}[c] for c in extra)
        self.finish(fig, axes, "state.png", "Drive state and sub-state; inverter switching "
                    "(PWM on) and every fault bit that is ever set, as bars where set"
                    + (f"; {names}." if names else "."), self.xr, axes[1])


def plot_worker(meta):
    """Pool entry point: plots of one scenario, or the InputError to hand back."""
    try:
        return ScenarioPlots(meta).all()
    except InputError as e:
        return e


def plot_all(metas):
    """Plot all scenarios with two worker processes; raises the first InputError."""
    if len(metas) > 1:
        with multiprocessing.Pool(2) as pool:
            results = pool.map(plot_worker, metas, chunksize=1)
    else:
        results = [plot_worker(m) for m in metas]
    for r in results:
        if isinstance(r, InputError):
            raise r
    return results


# ------------------------------------------------------------------ HTML
def page(title, body):
    """A complete static HTML page."""
    return (f"<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<title>{esc(title)}</title><style>{CSS}</style></head>\n<body>\n{body}\n"
            "</body></html>\n")


def badge(verdict):
    """A coloured PASS/FAIL label."""
    return f'<span class="badge {verdict.lower()}">{verdict}</span>'


def metrics_table(meta):
    """HTML table of a scenario's metrics with targets and results."""
    out = ['<table><tr><th>metric</th><th>value</th><th>target</th><th>result</th>'
           '<th>key</th></tr>']
    for m in meta["metrics"]:
        st = m["status"]
        out.append(f'<tr><td>{esc(m["label"])}</td><td class="num">'
                   f'{esc(with_unit(fnum(m["value"]), m.get("unit")))}</td>'
                   f'<td>{esc(target_text(m))}</td><td class="{st.lower()}">{st}</td>'
                   f'<td class="mono small">{esc(m["key"])}</td></tr>')
    out.append("</table>")
    return "\n".join(out)


def scenario_body(meta, plots, counts, prefix="", level=1):
    """Body of a scenario page (prefix: path from the page to the scenario directory;
    level: heading level of the title)."""
    h1, h2 = f"h{level}", f"h{level + 1}"
    f = meta.get("f_pwm_hz")
    facts = [("scenario", f'<code>{esc(meta["scenario"])}</code>'),
             ("motor", esc(meta.get("motor", "-"))),
             ("parameter table", esc(meta.get("table", "-"))),
             ("PWM frequency", f"{fnum(f / 1000)} kHz" if isinstance(f, (int, float)) else "-"),
             ("DC-bus voltage", esc(with_unit(fnum(meta.get("vdc_v")), "V"))),
             ("simulated time", esc(with_unit(fnum(meta.get("t_end_s")), "s"))),
             ("requirements", esc(", ".join(meta.get("requirements") or []) or "-"))]
    out = [f'<{h1}>{esc(meta["title"])} {badge(meta["verdict"])}</{h1}>',
           f'<p>{esc(meta.get("description", ""))}</p><table>']
    out += [f"<tr><th>{k}</th><td>{v}</td></tr>" for k, v in facts]
    out.append(f"</table><{h2}>Metrics</{h2}>")
    out.append(metrics_table(meta))
    if meta["failed"]:
        out.append(f'<p class="mfail">Failed: {esc(", ".join(meta["failed"]))}</p>')
    evs = meta.get("events") or []
    if evs:
        out.append(f"<{h2}>Events</{h2}><ul>" + "".join(
            f"<li>t = {ev['t_s']:g} s: {esc(ev.get('label', ''))}</li>" for ev in evs)
            + "</ul>")
    links = [f'<a href="{esc(prefix + n)}">{esc(n)}</a> ({k} rows)' for n, k in counts.items()]
    links.append(f'<a href="{esc(prefix)}metrics.json">metrics.json</a>')
    out.append(f"<{h2}>Plots</{h2}><p>CSV of every trace next to the plots: "
               + ", ".join(links) + ".</p>")
    for name, cap in plots:
        out.append(f'<figure><img src="{esc(prefix + name)}" alt="{esc(cap)}">'
                   f"<figcaption>{esc(cap)}</figcaption></figure>")
    return "\n".join(out)


def write_scenario_page(meta, plots, counts, back_href, back_text):
    """Write <scenario>/index.html."""
    body = (f'<p class="small"><a href="{esc(back_href)}">&larr; {esc(back_text)}</a></p>\n'
            + scenario_body(meta, plots, counts))
    with open(os.path.join(meta["dir"], "index.html"), "w", encoding="utf-8") as f:
        f.write(page(meta["title"], body))


def headline(meta, n=3):
    """Up to n metrics for the summary: failing ones first, then in file order."""
    ms = meta["metrics"]
    order = [m for m in ms if m["status"] == "FAIL"] + [m for m in ms if m["status"] != "FAIL"]
    return order[:n]


def robustness_summary(demo_dir, rel):
    """HTML box and terminal line about the campaign that summary.json names."""
    if not rel:
        return "", ""
    path = os.path.normpath(os.path.join(demo_dir, rel))
    if not os.path.exists(path):
        return (f'<h2>Robustness</h2><p class="small">campaign not run yet '
                f'(no {esc(rel)})</p>', "")
    camp = load_json(path)
    n, ok = camp.get("count"), camp.get("successes")
    if not isinstance(n, int) or not isinstance(ok, int):
        raise InputError(f"{path}: count and successes must be integers")
    rate = camp.get("rate_pct", 100.0 * ok / n if n else 0.0)
    if not isinstance(rate, (int, float)):
        raise InputError(f"{path}: rate_pct is not a number")
    every = camp.get("all") if isinstance(camp.get("all"), dict) else {}
    n_all, ok_all = every.get("count", n), every.get("successes", ok)
    every = every if n_all != n else {}   # the base axis alone: no second figure
    verdict = "PASS" if ok == n and ok_all == n_all else "FAIL"
    rdir = os.path.dirname(path)
    page_ = os.path.join(rdir, "index.html")
    link = os.path.relpath(page_, demo_dir)
    more = (f'<a href="{esc(link)}">campaign report</a>' if os.path.exists(page_) else
            f'<a href="{esc(os.path.relpath(path, demo_dir))}">campaign.json</a> (report not '
            f"written yet: tools/demo/demo_report.py --robustness {esc(rdir)})")
    axes_txt = (f" (base axis); <b>{ok_all} of {n_all}</b> on every axis" if every else "")
    return (f'<h2>Robustness</h2><div class="box"><p>{badge(verdict)} '
            f"<b>{ok} of {n}</b> randomised starts successful: <b>{rate:.1f} %</b>{axes_txt} &mdash; "
            f"{more}</p><p class=\"small\">{esc(camp.get('criteria', ''))}</p></div>",
            f"robustness: {ok}/{n} successful starts ({rate:.1f} %)"
            + (f", every axis {ok_all}/{n_all}" if every else "") + ", "
            + os.path.abspath(page_ if os.path.exists(page_) else path))


def write_index(demo_dir, summary, metas, robust_html):
    """Write DEMO_DIR/index.html."""
    nfail = sum(m["verdict"] == "FAIL" for m in metas)
    verdict = "PASS" if not nfail else "FAIL"
    head = (f"all {len(metas)} scenarios pass" if not nfail
            else f"{nfail} of {len(metas)} scenarios fail")
    wall = summary.get("sim_wall_s")
    out = [f"<h1>qfoc closed-loop demonstration {badge(verdict)}</h1>",
           f"<p>{head}. Q15 field-oriented control of a sensorless PMSM compressor drive, "
           "run in closed loop against a double-precision motor and inverter model"
           + (f" (simulation wall time {fnum(wall)} s)" if isinstance(wall, (int, float)) else "")
           + ". Each scenario page shows its description, the metrics against their targets, "
           "the plots and the CSV traces.</p>",
           "<table><tr><th>#</th><th>scenario</th><th>verdict</th><th>metrics</th>"
           "<th>key metrics</th><th>requirements</th></tr>"]
    for i, m in enumerate(metas, 1):
        sc = m["scenario"]
        npass = sum(x["status"] == "PASS" for x in m["metrics"])
        nt = sum(x["status"] != "info" for x in m["metrics"])
        hl = "; ".join(f'<span class="m{x["status"].lower()}">{esc(x["label"])} '
                       f'{esc(with_unit(fnum(x["value"]), x.get("unit")))}'
                       + (f' (target {esc(target_text(x))})' if x["status"] == "FAIL" else "")
                       + "</span>" for x in headline(m))
        out.append(f'<tr><td>{i}</td><td><a href="{esc(sc)}/index.html">{esc(m["title"])}</a>'
                   f'<br><span class="mono small">{esc(sc)}</span></td>'
                   f'<td class="{m["verdict"].lower()}">{m["verdict"]}</td>'
                   f'<td class="num">{npass}/{nt} pass</td><td class="small">{hl}</td>'
                   f'<td class="small">{esc(", ".join(m.get("requirements") or []))}</td></tr>')
    out.append("</table>")
    out.append(robust_html)
    out.append('<h2>Speed of every scenario</h2><div class="thumbs">')
    for m in metas:
        sc = m["scenario"]
        out.append(f'<figure><a href="{esc(sc)}/index.html"><img src="{esc(sc)}/speed.png" '
                   f'alt="speed, {esc(m["title"])}"></a><figcaption>{badge(m["verdict"])} '
                   f'{esc(m["title"])}</figcaption></figure>')
    out.append("</div>")
    path = os.path.join(demo_dir, "index.html")
    with open(path, "w", encoding="utf-8") as f:
        f.write(page("qfoc demonstration", "\n".join(out)))
    return path


def print_table(metas):
    """Print the metrics of every scenario and one verdict line per scenario."""
    rows = [("scenario", "metric", "value", "target", "result")]
    for m in metas:
        for x in m["metrics"]:
            label = textwrap.wrap(x["label"], 46) or [""]
            rows.append((m["scenario"], label[0], with_unit(fnum(x["value"]), x.get("unit")),
                         target_text(x), x["status"]))
            rows += [("", more, "", "", "") for more in label[1:]]
    w = [max(len(r[i]) for r in rows) for i in range(5)]
    for k, r in enumerate(rows):
        print("  ".join(c.ljust(w[i]) if i != 2 else c.rjust(w[i]) for i, c in enumerate(r))
              .rstrip())
        if k == 0:
            print("  ".join("-" * x for x in w))
    print()
    ws = max(len(m["scenario"]) for m in metas)
    for m in metas:
        tail = f"  (failed: {', '.join(m['failed'])})" if m["failed"] else ""
        print(f"{m['verdict']:4}  {m['scenario']:{ws}}  {m['title']}{tail}")


def demo_main(demo_dir):
    """Report of DEMO_DIR; returns the exit status."""
    summary = load_json(os.path.join(demo_dir, "summary.json"))
    names = summary.get("scenarios") if isinstance(summary, dict) else None
    if not isinstance(names, list) or not names:
        raise InputError(f"{demo_dir}/summary.json: 'scenarios' must be a non-empty list")
    metas = [load_meta(os.path.join(demo_dir, str(n))) for n in names]
    for n, m in zip(names, metas):
        if m["scenario"] != n:
            warn(f"{demo_dir}/{n}/metrics.json names scenario {m['scenario']!r}")
            m["scenario"] = n
    for m, (plots, counts) in zip(metas, plot_all(metas)):
        write_scenario_page(m, plots, counts, "../index.html", "all scenarios")
    robust_html, robust_line = robustness_summary(demo_dir, summary.get("robustness"))
    path = write_index(demo_dir, summary, metas, robust_html)
    print_table(metas)
    if robust_line:
        print(robust_line)
    print(f"report: {os.path.abspath(path)}")
    return 0 if all(m["verdict"] == "PASS" for m in metas) else 1


# ------------------------------------------------------------------ robustness
def fault_names(v):
    """Names of the bits set in a fault word."""
    try:
        w = int(float(v))
    except (TypeError, ValueError):
        return "-"
    return "+".join(FAULTS[b] if b < len(FAULTS) else f"bit{b}"
                    for b in range(w.bit_length()) if w >> b & 1) or "-"


def range_text(key, r):
    """Readable range of one randomised parameter."""
    what, unit = RANGES.get(key, (key, ""))
    if not (isinstance(r, list) and len(r) == 2):
        return what, esc(r)
    if unit == "rel":
        return what, f"{100 * r[0]:+g} % .. {100 * r[1]:+g} %"
    if unit == "frac":
        return what, f"{100 * r[0]:g} .. {100 * r[1]:g} % of nominal"
    return what, f"{r[0]:g} .. {r[1]:g} {unit}"


def run_params(runs):
    """The randomised parameters of a campaign: the base ones, and the axes' when present."""
    return RUN_PARAMS + [p for p in AXIS_PARAMS if isinstance(runs.get(p[0], [""])[0], float)]


def plot_scatter(runs, ycol, ylabel, title, out):
    """A panel per randomised parameter: ycol against it, failures as red crosses."""
    ok = [s > 0.5 for s in runs["success"]]
    ys = runs[ycol]
    fin = [v for v in ys if v == v]
    top = (max(fin) + 0.08 * (max(fin) - min(fin) or 1.0)) if fin else 1.0
    params = run_params(runs)
    ncol = (len(params) + 1) // 2
    fig, axes = plt.subplots(2, ncol, figsize=(FIG_W, 5.6), sharey=True)
    for ax in axes.flat[len(params):]:
        ax.set_visible(False)
    for ax, (col, name, unit, scale) in zip(axes.flat, params):
        xs = [v * scale for v in runs[col]]
        ax.plot([x for x, g in zip(xs, ok) if g], [y for y, g in zip(ys, ok) if g], "o",
                ms=3, color="C0", alpha=0.6, label="success")
        bad = [(x, y) for x, y, g in zip(xs, ys, ok) if not g and y == y]
        if bad:
            ax.plot(*zip(*bad), "x", ms=7, mew=1.8, color="C3", label="failure")
        bad = [(x, top) for x, y, g in zip(xs, ys, ok) if not g and y != y]
        if bad:
            ax.plot(*zip(*bad), "^", ms=6, color="C3",
                    label="failure, no value (drawn at the top)")
        ax.set_xlabel(f"{name} ({unit})")
        ax.grid(True, alpha=0.3)
    for ax in axes[:, 0]:
        ax.set_ylabel(ylabel)
    handles, labels = axes.flat[0].get_legend_handles_labels()
    for ax in axes.flat[1:]:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            if lab not in labels:
                handles.append(h)
                labels.append(lab)
    fig.legend(handles, labels, loc="upper right", fontsize=8, ncol=3, frameon=False)
    fig.suptitle(title, x=0.01, ha="left", fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    save(fig, out)


def load_campaign(rdir):
    """Read campaign.json and runs.csv; returns (campaign, runs, worst records, passed)."""
    camp = load_json(os.path.join(rdir, "campaign.json"))
    if not isinstance(camp, dict) or not all(isinstance(camp.get(k), int)
                                             for k in ("count", "successes")):
        raise InputError(f"{rdir}/campaign.json: count and successes must be integers")
    n, ok = camp["count"], camp["successes"]
    if not isinstance(camp.get("rate_pct", 0.0), (int, float)):
        raise InputError(f"{rdir}/campaign.json: rate_pct is not a number")
    camp.setdefault("rate_pct", 100.0 * ok / n if n else 0.0)
    runs = load_csv(os.path.join(rdir, "runs.csv"), RUN_COLS,
                    text=("reason", "axis", "table", "kind"))
    n_csv, ok_csv = len(runs["seed"]), sum(s > 0.5 for s in runs["success"])
    every = camp.get("all")
    if isinstance(every, dict):
        # count and successes are the base axis's; "all" counts every axis
        n, ok = every.get("count"), every.get("successes")
    if (n_csv, ok_csv) != (n, ok):
        warn(f"{rdir}: campaign.json says {ok}/{n} successes, runs.csv has {ok_csv}/{n_csv}")
    if not all(math.isfinite(s) for s in runs["seed"]):
        raise InputError(f"{rdir}/runs.csv: every run needs a seed")
    by_seed = {int(s): {c: v[i] for c, v in runs.items()} for i, s in enumerate(runs["seed"])}
    worst = []
    for w in camp.get("worst") or []:
        if not isinstance(w, dict) or not isinstance(w.get("seed"), (int, float)):
            raise InputError(f"{rdir}/campaign.json: every worst case needs a numeric seed")
        rec = dict(by_seed.get(int(w["seed"]), {}))
        rec.update(w)
        rec["seed"] = int(rec["seed"])
        worst.append(rec)
    camp["seeds"] = sorted(by_seed)
    return camp, runs, worst, ok == n and ok_csv == n_csv and n > 0


def replay_cmd(rec, template):
    """The command that replays one run: its own, or the campaign's with the seed."""
    return str(rec.get("replay") or template.replace("<seed>", str(rec["seed"])) or "-")


def worst_table(rdir, worst, replay):
    """HTML table of the worst cases with their parameters, results and replay command."""
    results = [r for r in RUN_RESULTS if any(r[0] in w for w in worst)]
    params = RUN_PARAMS + [p for p in AXIS_PARAMS if any(p[0] in w for w in worst)]
    cols = ([("seed", ""), ("result", "")]
            + ([("axis", ""), ("table", "")] if any("axis" in w for w in worst) else [])
            + [(p[1], p[2]) for p in params]
            + [(r[1], r[2]) for r in results] + [("fault", ""), ("reason", ""),
                                                 ("replay", "")])
    out = ['<div class="wide"><table class="small"><tr>' + "".join(
        f"<th>{esc(c)}" + (f" ({esc(u)})" if u else "") + "</th>" for c, u in cols) + "</tr>"]
    for w in worst:
        seed, good = w["seed"], _f(w.get("success")) > 0.5
        cells = [f"<td>{seed}</td>", f'<td class="{"pass" if good else "fail"}">'
                 f'{"OK" if good else "FAIL"}</td>']
        if any("axis" in x for x in worst):
            cells += [f"<td>{esc(w.get('axis', '-'))}</td>", f"<td>{esc(w.get('table', '-'))}</td>"]
        cells += [f'<td class="num">{fnum(_f(w.get(c)) * s)}</td>' for c, _, _, s in params]
        cells += [f'<td class="num">{fnum(_f(w.get(c)))}</td>' for c, _, _ in results]
        cmd = f"<code>{esc(replay_cmd(w, replay))}</code>"
        if os.path.exists(os.path.join(rdir, f"replay_{seed}", "index.html")):
            cmd = f'<a href="replay_{seed}/index.html">plots</a><br>{cmd}'
        cells += [f"<td>{esc(fault_names(w.get('fault')))}</td>",
                  f"<td>{esc(w.get('reason') or '-')}</td>", f"<td>{cmd}</td>"]
        out.append("<tr>" + "".join(cells) + "</tr>")
    out.append("</table></div>")
    return "\n".join(out)


KIND_TEXT = {"t_closed_loop_s": "closed loop not reached (or out of its window)",
             "t_target_s": "target speed not reached in time",
             "overshoot_pct": "speed overshoot", "ss_err_max_pct": "speed not held",
             "faults": "fault"}


def kind_text(k):
    """Readable failure kind: "fault <bits>" or the first metric off its target."""
    return k if k.startswith("fault") else KIND_TEXT.get(k, k)


def axes_table(rdir, camp):
    """HTML table of the campaign's axes and the terminal lines; ([], []) without axes."""
    axes = camp.get("axes") or []
    if not axes:
        return [], []
    out = ['<h2>Axes</h2><p>Goal: ' + esc(camp.get("goal", "-")) + '. A false fault is a fault '
           'raised in a run that reached the target speed (the campaign injects none). Each axis '
           'is a block of runs with its own seeds (axis a: a x 100000 + i); replay any with '
           '<code>make robustness-replay SEED=n</code>.</p>'
           '<div class="wide"><table class="small"><tr><th>axis</th><th>what is drawn</th>'
           '<th>table</th><th>runs</th><th>successes</th><th>rate</th><th>reached target</th>'
           '<th>runs with a fault</th><th>false faults (target reached)</th>'
           '<th>failure kinds</th><th>worst seeds</th></tr>']
    lines = [f"  {'axis':19} {'runs':>5} {'success':>8} {'rate %':>7} {'faults':>7} "
             f"{'false*':>7}  {'worst seeds':22} failure kinds"]
    for a in axes:
        runs, ok = int(a.get("runs", 0)), int(a.get("successes", 0))
        good = ok == runs and int(a.get("false_faults_reached", 0)) == 0
        kinds = a.get("kinds") or {}
        ktxt = "; ".join(f"{kind_text(k)}: {n}" for k, n in sorted(kinds.items(), key=lambda x: -x[1]))
        seeds = []
        for sd in a.get("worst") or []:
            link = os.path.join(rdir, f"replay_{sd}", "index.html")
            seeds.append(f'<a href="replay_{sd}/index.html">{sd}</a>' if os.path.exists(link) else str(sd))
        out.append(f"<tr><td class=\"mono\">{esc(a.get('axis'))}</td><td>{esc(a.get('what', ''))}</td>"
                   f"<td>{esc(a.get('table', ''))}</td><td class=\"num\">{runs}</td>"
                   f"<td class=\"num\">{ok}</td><td class=\"{'pass' if good else 'fail'}\">"
                   f"{fnum(_f(a.get('rate_pct')))} %</td><td class=\"num\">{a.get('reached')}</td>"
                   f"<td class=\"num\">{a.get('faulted')}</td>"
                   f"<td class=\"num\">{a.get('false_faults_reached')}</td>"
                   f"<td>{esc(ktxt or '-')}</td><td>{', '.join(seeds) or '-'}</td></tr>")
        lines.append(f"  {str(a.get('axis')):19} {runs:5d} {ok:8d} {_f(a.get('rate_pct')):7.1f} "
                     f"{int(a.get('faulted', 0)):7d} {int(a.get('false_faults_reached', 0)):7d}  "
                     f"{' '.join(str(x) for x in a.get('worst') or []):22} {ktxt}")
    out.append("</table></div>")
    lines.append("  (* false faults: runs that reached the target speed and raised a fault)")
    return out, lines


def bins_tables(runs):
    """HTML tables: success rate by bins of each axis parameter, on the axes that vary it."""
    if "axis" not in runs:
        return []
    out = ["<h2>Success rate against the axes' parameters</h2><p>Runs of the axes that draw the "
           "parameter, by bins of it: runs / successes (rate), the failure kinds.</p>"]
    for col, label, unit, scale, edges, axes in AXIS_BINS:
        if col not in runs or not isinstance(runs[col][0], float):
            continue
        rows = []
        for lo, hi in zip(edges[:-1], edges[1:]):
            idx = [i for i, (ax, v) in enumerate(zip(runs["axis"], runs[col]))
                   if ax in axes and lo <= v < hi]
            if not idx:
                continue
            ok = sum(runs["success"][i] > 0.5 for i in idx)
            kinds = {}
            for i in idx:
                if runs["success"][i] <= 0.5:
                    k = kind_text(str(runs.get("kind", [""] * len(idx))[i]))
                    kinds[k] = kinds.get(k, 0) + 1
            ktxt = "; ".join(f"{k}: {n}" for k, n in sorted(kinds.items(), key=lambda x: -x[1]))
            hi_txt = f"{min(hi, edges[-1]) * scale:.3g}"
            rows.append(f"<tr><td>{lo * scale:.3g} .. {hi_txt} {esc(unit)}</td>"
                        f'<td class="num">{len(idx)}</td><td class="num">{ok}</td>'
                        f'<td class="{"pass" if ok == len(idx) else "fail"}">'
                        f"{100.0 * ok / len(idx):.1f} %</td><td>{esc(ktxt or '-')}</td></tr>")
        if rows:
            out.append(f"<h3>{esc(label)} (axes {esc(', '.join(axes))})</h3><table class=\"small\">"
                       "<tr><th>bin</th><th>runs</th><th>successes</th><th>rate</th>"
                       "<th>failure kinds</th></tr>" + "".join(rows) + "</table>")
    return out


def robust_main(rdir):
    """Report of a robustness campaign; returns the exit status."""
    camp, runs, worst, passed = load_campaign(rdir)
    n, ok, rate = camp["count"], camp["successes"], camp["rate_pct"]
    every = camp.get("all") if isinstance(camp.get("all"), dict) else None
    every = every if every and every.get("count") != n else None
    replay = str(camp.get("replay") or "")
    dirs = [d for d in glob.glob(os.path.join(rdir, "replay_*")) if os.path.isdir(d)]
    dirs.sort(key=lambda p: int(re.sub(r"\D", "", os.path.basename(p)) or 0))
    metas = [load_meta(d) for d in dirs]
    results = plot_all(metas)
    for m, (plots, counts) in zip(metas, results):
        write_scenario_page(m, plots, counts, "../index.html", "robustness campaign")
    figs = [("scatter_reach.png", "t_reach_s", "time to target (s)", "time to target speed",
             "Time to reach the target speed against each randomised parameter; failed runs "
             "in red (triangles at the top when the target was never reached)."),
            ("scatter_angle.png", "angle_err_max_deg", "max angle error (deg)",
             "largest angle error", "Largest electrical angle error (estimate - true) "
             "against each randomised parameter; failed runs in red."),
            ("scatter_ipeak.png", "i_peak_a", "peak phase current (A)", "peak phase current",
             "Peak phase current against each randomised parameter; failed runs in red.")]
    figs = [f for f in figs if isinstance(runs.get(f[1], [""])[0], float)]
    for name, col, ylab, title, _ in figs:
        plot_scatter(runs, col, ylab, f"{title} against the randomised parameters",
                     os.path.join(rdir, name))

    seeds = camp["seeds"]
    out = [f"<h1>Start-up robustness campaign {badge('PASS' if passed else 'FAIL')}</h1>",
           f'<p style="font-size:1.2em"><b>{ok} of {n}</b> randomised starts successful: '
           f"<b>{rate:.1f} %</b>"
           + (f" on the base axis (the ranges of REQ-SCN-011); <b>{every['successes']} of "
              f"{every['count']}</b> on every axis: <b>{_f(every.get('rate_pct')):.1f} %</b>"
              if every else "") + "</p><table>",
           f"<tr><th>runs</th><td>{len(seeds)} (seeds {seeds[0]} .. {seeds[-1]})</td></tr>",
           f"<tr><th>wall time</th><td>{esc(with_unit(fnum(camp.get('wall_s')), 's'))}</td></tr>",
           f"<tr><th>parameter table</th><td>{esc(camp.get('table', '-'))}</td></tr>",
           f"<tr><th>success criteria</th><td>{esc(camp.get('criteria', '-'))}</td></tr>",
           "</table><h2>Randomised parameters</h2><p>Each run draws every parameter "
           "uniformly from its range; errors are of the drive's parameter against the "
           "motor model's; the ranges of the base axis (the other axes widen or add to them: see Axes).</p><table><tr><th>parameter</th><th>meaning</th><th>range</th></tr>"]
    for k, r in (camp.get("ranges") or {}).items():
        what, txt = range_text(k, r)
        out.append(f'<tr><td class="mono">{esc(k)}</td><td>{esc(what)}</td><td>{txt}</td></tr>')
    axes_html, axes_lines = axes_table(rdir, camp)
    out.append("</table>")
    out += axes_html
    out += bins_tables(runs)
    out.append("<h2>Worst cases</h2><p>Worst first, failures first."
               + (f" Replay one case with <code>{esc(replay)}</code>." if replay else "")
               + "</p>")
    out.append(worst_table(rdir, worst, replay))
    out.append("<h2>Results against the parameters</h2>"
               '<p>Raw data: <a href="runs.csv">runs.csv</a> (one row per run), '
               '<a href="campaign.json">campaign.json</a>.</p>')
    for name, _, _, _, cap in figs:
        out.append(f'<figure><img src="{name}" alt="{esc(cap)}"><figcaption>{esc(cap)}'
                   "</figcaption></figure>")
    if metas:
        out.append("<h2>Replayed cases</h2>")
    for m, (plots, counts) in zip(metas, results):
        sub = os.path.basename(os.path.normpath(m["dir"])) + "/"
        out.append(f'<div class="box"><p class="small"><a href="{esc(sub)}index.html">'
                   f"{esc(sub)}index.html</a></p>" + scenario_body(m, plots, counts, sub, 3)
                   + "</div>")
    path = os.path.join(rdir, "index.html")
    with open(path, "w", encoding="utf-8") as f:
        f.write(page("qfoc robustness campaign", "\n".join(out)))

    print(f"robustness: {ok}/{n} successful starts ({rate:.1f} %)"
          + (f" on the base axis, {every['successes']}/{every['count']} on every axis "
             f"({_f(every.get('rate_pct')):.1f} %)" if every else "")
          + f", wall time {with_unit(fnum(camp.get('wall_s')), 's')}")
    for line in axes_lines:
        print(line)
    for w in worst[:5]:
        res = "OK  " if _f(w.get("success")) > 0.5 else "FAIL"
        print(f"  {res} seed {w['seed']}: t_reach {with_unit(fnum(_f(w.get('t_reach_s'))), 's')}"
              f", angle max {with_unit(fnum(_f(w.get('angle_err_max_deg'))), 'deg')}, "
              f"fault {fault_names(w.get('fault'))}, {w.get('reason') or '-'}"
              + (f"   replay: {replay_cmd(w, replay)}" if replay or w.get("replay") else ""))
    print(f"{'PASS' if passed else 'FAIL'}  robustness")
    print(f"report: {os.path.abspath(path)}")
    return 0 if passed else 1


def _f(v):
    """A number from a run record field (None, text or number), nan if absent."""
    try:
        return float(v)
    except (TypeError, ValueError):
        return math.nan


def main():
    """Parse the command line and write the report."""
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    ap = argparse.ArgumentParser(description="Report of the qfoc closed-loop demonstration.")
    ap.add_argument("demo_dir", nargs="?", metavar="DEMO_DIR",
                    help="demonstration output (default: build/demo)")
    ap.add_argument("--robustness", metavar="ROBUST_DIR",
                    help="write the robustness campaign report instead")
    a = ap.parse_args()
    if a.robustness and a.demo_dir:
        ap.error("give either DEMO_DIR or --robustness ROBUST_DIR")
    try:
        if a.robustness:
            return robust_main(a.robustness)
        return demo_main(a.demo_dir or os.path.join(root, "build", "demo"))
    except InputError as e:
        print(f"demo_report: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
