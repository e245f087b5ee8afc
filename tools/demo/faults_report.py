#!/usr/bin/env python3
"""Report of the fault-injection campaign (make faults, make faults-check).

usage: faults_report.py FAULTS_DIR [--findings TOML] [--assumptions TOML] [--junit FILE]

TOML: the open findings (specs/fault-findings.toml, REQ-FINJ-007): the failures it names are
reported as OPEN; any other failure, or a named injection that passes, is a failure.
--assumptions: the item's FTTIs (specs/item-assumptions.toml; by default the file the campaign
read): the report gives each assumption with its hazard, its derivation, the mechanisms that
rest on it and the campaign's verdict against it.

Reads what build/host/qfoc_faults writes (FAULTS_DIR/results.json, flips.csv; the format is
described in sim/apps/faults.c and specs/fault-campaign.md) and writes

  FAULTS_DIR/results.md    the fault table, the item's FTTIs with the verdicts against them,
                           the library's budgets and their sources, the findings, the
                           bit flips by field and every flip that failed
  FAULTS_DIR/index.html    the same as a static page, with two plots (PNG beside it)
  FILE (--junit)           JUnit XML: one test case per class, one for the model checks and
                           one named faults.c for the whole campaign (the program the
                           requirements name, specs/requirements/faults.md)

It prints the fault table and the FTTI table.  Exit status: 0 when every class passes and
every mechanism's specified reaction is within the item's FTTI, 1 otherwise (the report is
still written), 2 on missing or malformed input.

Requirements: REQ-FINJ-005, REQ-FINJ-008.
"""
import argparse
import json
import os
import sys
import xml.etree.ElementTree as ET

from demo_report import badge, esc, fnum, page, plt, save

FAULTS = ["OC", "OV", "UV", "OT_IPM", "OT_PCB", "STALL", "PHASE", "OFFSET", "LINK", "PARAM", "TIMING"]
OUTCOMES = [("param", "PARAM in time"), ("other_fault", "other fault in time"),
            ("masked", "no fault, harmless"), ("late_harmless", "fault after its FTTI, harmless"),
            ("fail", "failed")]


def load(fdir):
    try:
        with open(os.path.join(fdir, "results.json"), encoding="utf-8") as f:
            d = json.load(f)
        for key in ("classes", "injections", "flips", "mechanisms", "model_checks"):
            d[key]  # noqa: B018 (presence check)
        return d
    except (OSError, ValueError, KeyError) as e:
        print(f"faults_report: {fdir}/results.json: missing or malformed ({e})", file=sys.stderr)
        sys.exit(2)


def load_findings(path):
    """The open findings (specs/fault-findings.toml): each names the injection that fails
    by class and `what` (or, for a bit flip, field and bit) and its finding ID."""
    import tomllib
    try:
        with open(path, "rb") as f:
            items = tomllib.load(f).get("finding", [])
    except (OSError, ValueError) as e:
        print(f"faults_report: {path}: {e}", file=sys.stderr)
        sys.exit(2)
    for it in items:
        if not isinstance(it, dict) or "id" not in it or "class" not in it or \
                not (("what" in it) != ("field" in it and "bit" in it)):
            print(f"faults_report: {path}: a finding needs id, class and either what or field "
                  f"and bit: {it!r}", file=sys.stderr)
            sys.exit(2)
    return items


def apply_findings(d, findings):
    """Mark the failures an open finding names (record["finding"] = its ID).  A class whose
    every failure is named gets the verdict OPEN (reported, not a gate failure).  A finding
    whose injection ran and passed is stale: the gate fails until it is removed, so the
    list stays exact.  A bit flip's finding is not stale when its flip was not drawn or did
    not fail at the instant it was drawn (the flips are random in time)."""
    d["stale_findings"] = []
    for fd in findings:
        if "what" in fd:
            runs = [r for r in d["injections"] if r["class"] == fd["class"] and r["what"] == fd["what"]]
            for r in runs:
                if not r["pass"]:
                    r["finding"] = fd["id"]
            if runs and all(r["pass"] for r in runs):
                d["stale_findings"].append(f"{fd['id']} ({fd['class']}: {fd['what']}) passes now: "
                                           "remove it from the open findings")
        else:
            for x in d["flips"].get(fd["class"], {}).get("failures", []):
                if x.get("field") == fd["field"] and x.get("bit") == fd["bit"]:
                    x["record"]["finding"] = fd["id"]
    for c in d["classes"]:
        if c["verdict"] == "PASS":
            continue
        bad = [r for r in d["injections"] if r["class"] == c["class"] and not r["pass"]]
        if c["class"] in d["flips"]:
            bad = [x["record"] for x in d["flips"][c["class"]]["failures"]]
        if bad and all(r.get("finding") for r in bad):
            c["verdict"] = "OPEN"
            c["findings"] = sorted({r["finding"] for r in bad})


def verdict_ok(c):
    """PASS, or OPEN (every failure an open finding)."""
    return c["verdict"] in ("PASS", "OPEN")


def span(v, unit="ms"):
    """'a .. b unit' of a [min, max] pair, '-' when empty."""
    if not v or v[0] is None:
        return "-"
    a, b = fnum(v[0]), fnum(v[1])
    return f"{a} {unit}" if a == b else f"{a} .. {b} {unit}"


def budget_text(c):
    return f"{fnum(c['budget_ms'])} ms" if c.get("budget_ms") is not None else "-"


def campaign_ok(d, rows):
    return all(verdict_ok(c) for c in d["classes"]) and all(r["adequate"] for r in rows)


def ftti_text(c):
    if c["ftti_ms"] is not None:
        return f"{fnum(c['ftti_ms'])} ms"
    return "no fault allowed" if c["within_limits"] else "of the fault raised"


def bits_text(c):
    per = c.get("per_bit") or {}
    return ", ".join(f"{b} {per[b]}" for b in FAULTS if b in per) or "-"


def region(field):
    """Where a field lives: the drive's half and member (f.pll), the table's group."""
    parts = field.split(".")
    if parts[0] in ("f", "s"):
        return ".".join(parts[:2])
    return parts[0]


def by_region(fl):
    out = {}
    for r in fl["fields"]:
        g = out.setdefault(region(r["field"]), {"bytes": 0, **{k: 0 for k, _ in OUTCOMES}})
        g["bytes"] += r["bytes"]
        for k, _ in OUTCOMES:
            g[k] += r[k]
    return out


def load_assumptions(path):
    """The item's assumptions by mechanism key (hazard, assumption, derivation, id, ftti_ms)."""
    import tomllib
    try:
        with open(path, "rb") as f:
            return tomllib.load(f)
    except (OSError, ValueError) as e:
        print(f"faults_report: {path}: {e}", file=sys.stderr)
        sys.exit(2)


def ftti_rows(d, assumptions):
    """One row per mechanism with an item FTTI: its assumption, the library's specified
    reaction and budget, the injections judged against it (the bit-flip classes by their
    counts), how many were detected and how many of those in time (within the FTTI and the
    budget), the worst reaction, and the verdict: PASS when the specified reaction is within
    the FTTI and no injection judged against it failed; OPEN when every one that failed is
    named by an open finding (apply_findings first); FAIL otherwise."""
    rows = []
    for m in d["mechanisms"]:
        if m["ftti_ms"] is None:
            continue
        name = m["mechanism"]
        inj = [r for r in d["injections"] if r.get("mechanism") == name]
        det = [r for r in inj if r["faults"] and r["t_react_ms"] is not None]
        flips = [c for c in d["classes"] if c["class"] in d["flips"] and c.get("mechanism") == name]
        flips_failed = [x["record"] for fl in d["flips"].values() for x in fl["failures"]
                        if x["record"].get("mechanism") == name]
        worst = [r["t_react_ms"] for r in det] + [c["t_react_ms"][1] for c in flips
                                                  if c.get("t_react_ms") and c["t_react_ms"][1] is not None]
        a = assumptions.get(m["key"], {})
        row = {
            "id": m["assumption"], "mechanism": name, "hazard": a.get("hazard", ""),
            "assumption": a.get("assumption", ""), "derivation": a.get("derivation", ""),
            "ftti_ms": m["ftti_ms"], "spec_ms": m["spec_ms"], "budget_ms": m["budget_ms"],
            "adequate": m["adequate"],
            "judged": len(inj) + sum(c["injected"] for c in flips),
            "detected": len(det) + sum(c["detected"] for c in flips),
            "within": sum(1 for r in det if r["in_time"]) + sum(c["in_time"] for c in flips),
            "worst_ms": max(worst, default=None),
            "failed": sum(1 for r in inj + flips_failed if not r["pass"] and not r.get("finding")),
            "open": sum(1 for r in inj + flips_failed if not r["pass"] and r.get("finding")),
        }
        row["verdict"] = ("FAIL" if not row["adequate"] or row["failed"] else
                          "OPEN" if row["open"] else "PASS")
        rows.append(row)
    return rows


def findings(d):
    return [r for r in d["injections"] if not r["pass"]]


def observations(d):
    """Injections detected within their FTTI that were not harmless before the reaction."""
    return [r for r in d["injections"] if r["pass"] and r["in_time"] and not r["harmless"]]


def harm_text(r):
    why = []
    if r["oc_missed"]:
        why.append(f"true current above i_trip with the inverter left switching (peak {fnum(r['i_peak_a'])} A)")
    if r["over_full_scale"]:
        why.append(f"true current above the sensing full scale (peak {fnum(r['i_peak_a'])} A)")
    if r["state_bad"]:
        why.append("state out of range or invalid drive object")
    if r["pwm_outside_run"]:
        why.append("PWM outside RUN")
    if r["cmd_changed"]:
        why.append("command changed")
    if not why and r.get("rpm_peak") is not None:
        why.append(f"speed {fnum(r['rpm_peak'])} rpm")
    if r.get("finding"):
        why.append(f"open finding {r['finding']}")
    return "; ".join(why)


def det_text(r):
    if not r["faults"]:
        return "not detected"
    return (f"{'+'.join(r['first'])} after {fnum(r['t_det_ms'])} ms, PWM off after "
            f"{fnum(r['t_react_ms'])} ms (FTTI {fnum(r['ftti_ms'])} ms, budget "
            f"{fnum(r.get('budget_ms'))} ms)")


# ------------------------------------------------------------------ markdown

def write_md(d, path, rows):
    cl = d["classes"]
    ok = campaign_ok(d, rows)
    out = [f"# Fault-injection campaign ({d['mode']})", "",
           f"Table `{d['table']}` ({d['motor']}, {fnum(d['f_pwm_hz'])} Hz PWM); operating point "
           f"{d['operating_point']['rpm']} rpm at {fnum(d['operating_point']['load_nm'])} N m, "
           f"{fnum(d['operating_point']['vdc_v'])} V.  i_trip {fnum(d['limits']['i_trip_a'])} A, "
           f"sensing full scale {fnum(d['limits']['i_full_scale_a'])} A, maximum speed "
           f"{fnum(d['limits']['max_speed_rpm'])} rpm.  {sum(c['injected'] for c in cl)} injections, "
           f"{d['drive_flips']} random drive-object flips (seed {d['seed']}), table bits every "
           f"{d['table_step']}; {fnum(d['wall_s'])} s.  Verdict: **{'PASS' if ok else 'FAIL'}**.", "",
           "Method, FTTIs and the verdict rule: `specs/fault-campaign.md`.", "",
           "## Fault table", "",
           "| class | injected | detected | bits raised | detection time | reaction time | budget | "
           "FTTI | in time | harmless | verdict |",
           "|---|---:|---:|---|---|---|---|---|---:|---:|---|"]
    for c in cl:
        out.append(f"| {c['class']} | {c['injected']} | {c['detected']} | {bits_text(c)} | "
                   f"{span(c['t_det_ms'])} | {span(c['t_react_ms'])} | {budget_text(c)} | {ftti_text(c)} | "
                   f"{c['in_time']} | {c['harmless']} | {c['verdict']}"
                   f"{'' if c['verdict'] == 'PASS' else ' (' + str(c['failed']) + ' failed)'} |")
    out += ["", "What each class injects:", ""]
    out += [f"- `{c['class']}`: {c['title']}." for c in cl]
    out += ["", "## The item's FTTIs and the verdicts against them", "",
            f"From the item's assumptions `{d.get('assumptions', '')}` (AoU-25): each mechanism's "
            "FTTI, the library's specified reaction and its budget "
            f"({d['margin']} x the specified reaction), the injections judged against it, how many "
            "of the detected ones reacted in time (within the FTTI and the budget), the worst "
            "reaction.  An injection passes when detected in time, or harmless.", "",
            "| assumption | mechanism | hazard | assumed | FTTI | specified | budget | judged | "
            "in time / detected | worst reaction | verdict |",
            "|---|---|---|---|---:|---:|---:|---:|---:|---:|---|"]
    for r in rows:
        out.append(f"| {r['id']} | {r['mechanism']} | {r['hazard']} | {r['assumption']}; "
                   f"{r['derivation']} | {fnum(r['ftti_ms'])} ms | {fnum(r['spec_ms'])} ms | "
                   f"{fnum(r['budget_ms'])} ms | {r['judged']} | {r['within']} / {r['detected']} | "
                   f"{'-' if r['worst_ms'] is None else fnum(r['worst_ms']) + ' ms'} | {r['verdict']} |")
    out += ["", "## The library's budgets", "", f"Budget = {d['margin']} x the specified "
            "reaction time (`specs/safety-manual.md` section 2.2, from the table's values).", "",
            "| mechanism | specified reaction | budget | from |", "|---|---:|---:|---|"]
    for m in d["mechanisms"]:
        if m["budget_ms"] is not None:
            out.append(f"| {m['mechanism']} | {fnum(m['spec_ms'])} ms | {fnum(m['budget_ms'])} ms | "
                       f"{m['source']} |")
    fnd = findings(d)
    out += ["", f"## Findings: injections neither detected within their FTTI nor harmless ({len(fnd)})", ""]
    out += [f"- `{r['class']}` {r['what']}: {det_text(r)}; {harm_text(r)}." for r in fnd] or ["None."]
    obs = observations(d)
    out += ["", f"## Detected within the FTTI, not harmless before the reaction ({len(obs)})", ""]
    out += [f"- `{r['class']}` {r['what']}: {det_text(r)}; {harm_text(r)}." for r in obs] or ["None."]
    for key, title in (("table_flip", "RAM table copy"), ("drive_flip", "drive object")):
        fl = d["flips"][key]
        tot = fl["totals"]
        out += ["", f"## Bit flips: {title} ({fl['bytes']} bytes, {sum(tot.values())} flips)", "",
                ", ".join(f"{lab}: {tot[k]}" for k, lab in OUTCOMES) + ".", "",
                "| region | bytes | flips | " + " | ".join(lab for _k, lab in OUTCOMES) + " |",
                "|---|---:|---:|" + "---:|" * len(OUTCOMES)]
        for g, v in by_region(fl).items():
            n = sum(v[k] for k, _ in OUTCOMES)
            out.append(f"| {g} | {v['bytes']} | {n} | " + " | ".join(str(v[k]) for k, _ in OUTCOMES) + " |")
        out += ["", f"Failed flips ({len(fl['failures'])}):", ""]
        out += [f"- `{x['field']}` bit {x['bit']} ({fnum(x['delay_ms'])} ms after RUN): "
                f"{det_text(x['record'])}; {harm_text(x['record'])}." for x in fl["failures"]] or ["None."]
    out += ["", "## Model checks", ""]
    out += [f"- {m['check']}: {fnum(m['value'])} ({'ok' if m['ok'] else 'FAILED'})" for m in d["model_checks"]]
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(out) + "\n")


# ------------------------------------------------------------------ HTML

def plot_times(d, path):
    """Reaction time against the FTTI of every detected injection."""
    cl = [c["class"] for c in d["classes"]]
    fig, ax = plt.subplots(figsize=(11.0, 5.2))
    for r in d["injections"]:
        if r["t_react_ms"] is None or not r["faults"]:
            continue
        y = cl.index(r["class"])
        t = max(r["t_react_ms"], 1e-2)
        ax.plot(t, y, "o", ms=5, color=("tab:green" if r["pass"] else "tab:red"), alpha=0.7)
        if r["ftti_ms"] is not None:
            ax.plot(r["ftti_ms"], y, "|", ms=14, color="0.3")
    ax.set_xscale("log")
    ax.set_yticks(range(len(cl)))
    ax.set_yticklabels(cl, fontsize=8)
    ax.invert_yaxis()
    ax.set_xlabel("time from the injection to PWM off, ms (bar: FTTI; red: failed)")
    ax.grid(True, which="both", axis="x", alpha=0.3)
    fig.tight_layout()
    save(fig, path)


def plot_flips(d, path):
    """Outcome of the drive-object flips by region."""
    reg = by_region(d["flips"]["drive_flip"])
    names = list(reg)
    fig, ax = plt.subplots(figsize=(11.0, 0.25 * len(names) + 1.4))
    left = [0] * len(names)
    colours = ["tab:blue", "tab:cyan", "tab:green", "tab:olive", "tab:red"]
    for (k, lab), col in zip(OUTCOMES, colours):
        vals = [reg[n][k] for n in names]
        ax.barh(names, vals, left=left, color=col, label=lab)
        left = [a + b for a, b in zip(left, vals)]
    ax.invert_yaxis()
    ax.tick_params(axis="y", labelsize=7)
    ax.set_xlabel("flips")
    ax.legend(fontsize=8, ncol=len(OUTCOMES), loc="lower center", bbox_to_anchor=(0.5, 1.0))
    fig.tight_layout()
    save(fig, path)


def table_html(headers, rows, num=()):
    out = ["<table><tr>" + "".join(f"<th>{esc(h)}</th>" for h in headers) + "</tr>"]
    for r in rows:
        cells = []
        for i, v in enumerate(r):
            if isinstance(v, tuple):
                cells.append(f'<td class="{v[0]}">{v[1]}</td>')
            else:
                cells.append(f'<td{" class=num" if i in num else ""}>{esc(v)}</td>')
        out.append("<tr>" + "".join(cells) + "</tr>")
    out.append("</table>")
    return "\n".join(out)


def write_html(d, fdir, rows):
    cl = d["classes"]
    ok = campaign_ok(d, rows)
    plot_times(d, os.path.join(fdir, "times.png"))
    plot_flips(d, os.path.join(fdir, "flips.png"))
    crow = [[c["class"], c["injected"], c["detected"], bits_text(c), span(c["t_det_ms"]),
             span(c["t_react_ms"]), budget_text(c), ftti_text(c), c["in_time"], c["harmless"],
             (c["verdict"].lower(), c["verdict"] + ("" if c["verdict"] == "PASS" else f" ({c['failed']})"))]
            for c in cl]
    body = [f"<h1>Fault-injection campaign {badge('PASS' if ok else 'FAIL')}</h1>",
            f"<p>Mode {esc(d['mode'])}: {sum(c['injected'] for c in cl)} injections on table "
            f"<code>{esc(d['table'])}</code> ({esc(d['motor'])}), {d['drive_flips']} random "
            f"drive-object flips (seed {d['seed']}), table bits every {d['table_step']}; "
            f"{fnum(d['wall_s'])} s.  i_trip {fnum(d['limits']['i_trip_a'])} A, full scale "
            f"{fnum(d['limits']['i_full_scale_a'])} A, maximum speed "
            f"{fnum(d['limits']['max_speed_rpm'])} rpm.  Method, FTTIs and the verdict rule: "
            "<code>specs/fault-campaign.md</code>; figures in <a href=\"results.md\">results.md"
            "</a>, <a href=\"results.json\">results.json</a>, <a href=\"flips.csv\">flips.csv</a>.</p>",
            "<h2>Fault table</h2>",
            table_html(["class", "injected", "detected", "bits raised", "detection time",
                        "reaction time", "budget", "FTTI", "in time", "harmless", "verdict"], crow,
                       num=(1, 2, 8, 9)),
            "<ul>" + "".join(f"<li><code>{esc(c['class'])}</code>: {esc(c['title'])}.</li>" for c in cl)
            + "</ul>",
            '<figure><img src="times.png" alt="reaction times"><figcaption>Reaction time (injection '
            'to PWM off) of every detected injection, with its FTTI.</figcaption></figure>',
            "<h2>The item's FTTIs and the verdicts against them</h2>",
            f"<p>From <code>{esc(d.get('assumptions', ''))}</code> (AoU-25, confirmed by the "
            "integrator); an injection passes when detected within both its FTTI and the library's "
            "budget, or harmless.</p>",
            table_html(["assumption", "mechanism", "hazard", "assumed", "FTTI", "specified", "budget",
                        "judged", "in time / detected", "worst reaction", "verdict"],
                       [[r["id"], r["mechanism"], r["hazard"], f"{r['assumption']}; {r['derivation']}",
                         f"{fnum(r['ftti_ms'])} ms", f"{fnum(r['spec_ms'])} ms", f"{fnum(r['budget_ms'])} ms",
                         r["judged"], f"{r['within']} / {r['detected']}",
                         "-" if r["worst_ms"] is None else f"{fnum(r['worst_ms'])} ms",
                         (r["verdict"].lower(), r["verdict"])] for r in rows], num=(4, 5, 6, 7, 8, 9)),
            "<h2>The library's budgets</h2>",
            f"<p>Budget = {d['margin']} x the specified reaction time.</p>",
            table_html(["mechanism", "specified", "budget", "from"],
                       [[m["mechanism"], f"{fnum(m['spec_ms'])} ms", f"{fnum(m['budget_ms'])} ms",
                         m["source"]] for m in d["mechanisms"] if m["budget_ms"] is not None], num=(1, 2))]
    for title, lst in (("Findings: neither detected within the FTTI nor harmless", findings(d)),
                       ("Detected within the FTTI, not harmless before the reaction", observations(d))):
        body.append(f"<h2>{esc(title)} ({len(lst)})</h2>")
        body.append(table_html(["class", "injection", "detection", "harm"],
                               [[r["class"], r["what"], det_text(r), harm_text(r)] for r in lst])
                    if lst else "<p>None.</p>")
    for key, title in (("table_flip", "RAM table copy"), ("drive_flip", "drive object")):
        fl = d["flips"][key]
        tot = fl["totals"]
        body.append(f"<h2>Bit flips: {esc(title)} ({fl['bytes']} bytes, {sum(tot.values())} flips)</h2>")
        body.append("<p>" + esc(", ".join(f"{lab}: {tot[k]}" for k, lab in OUTCOMES)) + ".</p>")
        body.append(table_html(["region", "bytes", "flips"] + [lab for _k, lab in OUTCOMES],
                               [[g, v["bytes"], sum(v[k] for k, _ in OUTCOMES)] + [v[k] for k, _ in OUTCOMES]
                                for g, v in by_region(fl).items()], num=range(1, 8)))
        if key == "drive_flip":
            body.append('<figure><img src="flips.png" alt="flips by region"></figure>')
        body.append(f"<p>Failed flips: {len(fl['failures'])}.</p>")
        if fl["failures"]:
            body.append(table_html(["field", "bit", "after RUN", "detection", "harm"],
                                   [[x["field"], x["bit"], f"{fnum(x['delay_ms'])} ms", det_text(x["record"]),
                                     harm_text(x["record"])] for x in fl["failures"]]))
        body.append('<div class="wide">' + table_html(
            ["field", "offset", "bytes"] + [lab for _k, lab in OUTCOMES],
            [[r["field"], r["offset"], r["bytes"]] + [r[k] for k, _ in OUTCOMES]
             for r in fl["fields"] if sum(r[k] for k, _ in OUTCOMES)], num=range(1, 8)) + "</div>")
    body.append("<h2>Model checks</h2>")
    body.append(table_html(["check", "value", "result"],
                           [[m["check"], fnum(m["value"]), ("pass" if m["ok"] else "fail", "ok" if m["ok"] else "FAILED")]
                            for m in d["model_checks"]]))
    path = os.path.join(fdir, "index.html")
    with open(path, "w", encoding="utf-8") as f:
        f.write(page("qfoc fault-injection campaign", "\n".join(body)))
    return path


# ------------------------------------------------------------------ JUnit

def write_junit(d, path, rows):
    cases = [(f"ftti_{r['id']}_{r['mechanism']}", r["verdict"] in ("PASS", "OPEN"),
              f"specified {fnum(r['spec_ms'])} ms, worst {fnum(r['worst_ms'])} ms against the "
              f"item's FTTI {fnum(r['ftti_ms'])} ms; {r['failed']} failed, {r['open']} named by "
              f"an open finding") for r in rows]
    for c in d["classes"]:
        bad = [r for r in d["injections"] if r["class"] == c["class"] and not r["pass"]]
        if c["class"] in d["flips"]:
            bad = [x["record"] for x in d["flips"][c["class"]]["failures"]]
        msg = "; ".join(f"{r['what']}: {det_text(r)}; {harm_text(r)}" for r in bad[:20])
        bad = [r for r in bad if not r.get("finding")]
        cases.append((c["class"], verdict_ok(c) and c["injected"] > 0,
                      f"{c['failed']} of {c['injected']} failed: {msg}"))
    mc = all(m["ok"] for m in d["model_checks"])
    cases.append(("model_checks", mc, "a fault model of sim.h does not do what it is meant to"))
    cases.append(("findings_current", not d["stale_findings"], "; ".join(d["stale_findings"])))
    cases.append(("faults.c", all(ok for _n, ok, _m in cases),
                  "the campaign has failing classes: " + ", ".join(n for n, ok, _m in cases if not ok)))
    suite = ET.Element("testsuite", name="faults", tests=str(len(cases)),
                       failures=str(sum(1 for _n, ok, _m in cases if not ok)), errors="0",
                       time=f"{d['wall_s']:.1f}")
    props = ET.SubElement(suite, "properties")
    ET.SubElement(props, "property", name="mode", value=str(d["mode"]))
    for name, ok, msg in cases:
        tc = ET.SubElement(suite, "testcase", classname="faults", name=name)
        if not ok:
            ET.SubElement(tc, "failure", message=msg[:2000])
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    ET.ElementTree(suite).write(path, encoding="utf-8", xml_declaration=True)


def main():
    ap = argparse.ArgumentParser(description="Report of the qfoc fault-injection campaign.")
    ap.add_argument("faults_dir")
    ap.add_argument("--junit", metavar="FILE", help="write the JUnit XML there")
    ap.add_argument("--findings", metavar="TOML", help="the open findings (specs/fault-findings.toml)")
    ap.add_argument("--assumptions", metavar="TOML",
                    help="the item's FTTIs (default: the file the campaign read)")
    a = ap.parse_args()
    d = load(a.faults_dir)
    apply_findings(d, load_findings(a.findings) if a.findings else [])
    rows = ftti_rows(d, load_assumptions(a.assumptions or d.get("assumptions")
                                         or "specs/item-assumptions.toml"))
    write_md(d, os.path.join(a.faults_dir, "results.md"), rows)
    path = write_html(d, a.faults_dir, rows)
    if a.junit:
        write_junit(d, a.junit, rows)
    print(f"{'class':22} {'injected':>8} {'detected':>8} {'detection':>20} {'reaction':>22} "
          f"{'FTTI':>20}  verdict")
    for c in d["classes"]:
        print(f"{c['class']:22} {c['injected']:8} {c['detected']:8} {span(c['t_det_ms']):>20} "
              f"{span(c['t_react_ms']):>22} {ftti_text(c):>20}  {c['verdict']}")
    print(f"\n{'assumption':10} {'mechanism':31} {'FTTI':>11} {'specified':>11} {'worst':>11}  verdict")
    for r in rows:
        worst = "-" if r["worst_ms"] is None else f"{fnum(r['worst_ms'])} ms"
        print(f"{r['id']:10} {r['mechanism']:31} {fnum(r['ftti_ms']) + ' ms':>11} "
              f"{fnum(r['spec_ms']) + ' ms':>11} {worst:>11}  {r['verdict']}")
    print(f"report: {os.path.abspath(path)}")
    for msg in d["stale_findings"]:
        print(f"faults: {msg}")
    return 0 if campaign_ok(d, rows) and not d["stale_findings"] else 1


if __name__ == "__main__":
    sys.exit(main())
