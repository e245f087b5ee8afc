#!/usr/bin/env python3
"""Plots of the estimator validation (make estimator-report).

usage: plot_estimators.py REPORT_DIR

Reads the CSV files that build/host/estimator_report writes into REPORT_DIR and
writes PNG plots beside them: angle error against speed (with and without ADC
noise), angle bias against parameter error (measured and predicted by the
document's bias analysis 2-31), and the cold-start convergence traces.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

NAMES = ["flux observer + PLL", "back-EMF + atan2", "disturbance obs. + atan2",
         "disturbance obs. + ATO"]


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def speed_plot(rows, title, out):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    for j, name in enumerate(NAMES):
        sel = [r for r in rows if int(r["estimator"]) == j]
        x = [float(r["speed_pct"]) for r in sel]
        axes[0].plot(x, [float(r["err_mean_deg"]) for r in sel], "o-", label=name)
        axes[1].plot(x, [float(r["err_max_deg"]) for r in sel], "o-", label=name)
    for ax, lim, lab in ((axes[0], 2.0, "mean error (deg el.)"),
                         (axes[1], 5.0, "max |error| (deg el.)")):
        ax.axhline(lim, color="k", ls="--", lw=0.8)
        if lim == 2.0:
            ax.axhline(-lim, color="k", ls="--", lw=0.8)
        ax.axvline(10.0, color="grey", ls=":", lw=0.8)
        ax.set_xlabel("speed (% of rated)")
        ax.set_ylabel(lab)
        ax.grid(True, alpha=0.3)
    axes[1].set_yscale("log")
    axes[0].legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def params_plot(rows, out):
    cases = []
    for r in rows:
        if r["case"] not in cases:
            cases.append(r["case"])
    speeds = sorted({float(r["speed_pct"]) for r in rows})
    fig, axes = plt.subplots(1, len(speeds), figsize=(4 * len(speeds), 4), sharey=True)
    for ax, sp in zip(axes, speeds):
        sel = {r["case"]: r for r in rows if float(r["speed_pct"]) == sp}
        x = range(len(cases))
        ax.bar([i - 0.2 for i in x], [float(sel[c]["flux_mean"]) for c in cases], 0.4,
               label="measured (flux + PLL)")
        ax.bar([i + 0.2 for i in x], [float(sel[c]["pred_bias"]) for c in cases], 0.4,
               label="predicted by 2-31")
        ax.set_xticks(list(x))
        ax.set_xticklabels(cases, rotation=60, ha="right", fontsize=8)
        ax.set_title("%.0f %% rated speed" % sp)
        ax.grid(True, axis="y", alpha=0.3)
    axes[0].set_ylabel("mean angle error (deg el.)")
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def trace_plot(paths, out):
    fig, axes = plt.subplots(len(paths), 1, figsize=(10, 3.5 * len(paths)))
    for ax, (label, path) in zip(axes, paths):
        rows = read(path)
        t = [1000.0 * float(r["t_s"]) for r in rows]
        for key, name in zip(["err_flux_pll", "err_emf_atan", "err_dob_atan", "err_dob_ato"],
                             NAMES):
            ax.plot(t, [float(r[key]) for r in rows], lw=0.8, label=name)
        ax.axhspan(-5, 5, color="green", alpha=0.1)
        ax.axvline(50.0, color="k", ls="--", lw=0.8)
        ax.set_ylim(-100, 100)
        ax.set_xlabel("time after cold start (ms)")
        ax.set_ylabel("angle error (deg el.)")
        ax.set_title(label)
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def main():
    if len(sys.argv) != 2:
        sys.stderr.write(__doc__)
        return 2
    d = sys.argv[1]
    speed_plot(read(os.path.join(d, "estimators_speed.csv")),
               "Angle error against speed, nominal parameters",
               os.path.join(d, "estimators_speed.png"))
    speed_plot(read(os.path.join(d, "estimators_speed_noise.csv")),
               "Angle error against speed, 0.2 A rms ADC noise",
               os.path.join(d, "estimators_speed_noise.png"))
    params_plot(read(os.path.join(d, "estimators_params.csv")),
                os.path.join(d, "estimators_params.png"))
    trace_plot([("cold start at 25 % rated speed, PLL 90 deg off",
                 os.path.join(d, "trace_25pct.csv")),
                ("cold start at 100 % rated speed, PLL 90 deg off",
                 os.path.join(d, "trace_100pct.csv"))],
               os.path.join(d, "estimators_convergence.png"))
    print("estimator plots: %s/estimators_*.png" % d)
    return 0


if __name__ == "__main__":
    sys.exit(main())
