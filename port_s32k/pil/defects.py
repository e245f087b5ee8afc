#!/usr/bin/env python3
"""defects.py -- seeded port defects that the processor-in-the-loop run must catch
(make pil-defects).

Each defect is one exact substitution (the old text must occur exactly once) in a copy of
the port's source (port_s32k/*.c, *.S, *.h, the linker script), built into its own image
in its own directory (build/pil/defects/NAME/; build/s32k144 is not touched) with the
flags of mk/port.mk and the same target library, and run through the scenarios of
DEFECT_SCENARIOS (scenarios.py).  A defect is caught when at least one scenario fails;
the control (the copy without a substitution, built the same way) must pass them all.
Exit status 1 when a defect is missed or the control fails.

Usage: defects.py --cc arm-none-eabi-gcc --cflags "..." --ldflags "..." --lib libqfoc.a
                  [--out build/pil/defects] [--only NAME,...] [--jobs 2]

Requirement: REQ-PIL-005 (specs/requirements/pil.md).
"""
import argparse
import glob
import os
import shlex
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import scenarios as sc  # noqa: E402

ROOT = sc.run_mod.ROOT
PORT = os.path.join(ROOT, "port_s32k")

# name, file, old text, new text, what it breaks
DEFECTS = [
    ("control", None, None, None, "no substitution: the unmodified port built the same way"),
    ("pdb-delay-half-period", "mcu.c",
     "s32k_write(base + S32K_PDB_CH0DLY0, (uint32_t)period);",
     "s32k_write(base + S32K_PDB_CH0DLY0, 0u);",
     "PDB0/PDB1 CH0DLY0 0 instead of MOD: the phase currents sampled half a PWM period early "
     "(counter at CNTIN, the centre of the high-side zero vector)"),
    ("compare-wrong-channel-pair", "hal_s32k.c",
     "s32k_write(S32K_FTM3_C0V + (16u * k), s32k_cmp(pwm->cmp[k]));",
     "s32k_write(S32K_FTM3_C0V + (16u * ((k + 1u) % 3u)), s32k_cmp(pwm->cmp[k]));",
     "phase k's compare value written to the channel pair of phase k+1"),
    ("deadtime-disabled", "mcu.c",
     "const uint32_t pair = comb | S32K_FTM_COMB_COMP | S32K_FTM_COMB_DTEN | S32K_FTM_COMB_SYNCEN |",
     "const uint32_t pair = comb | S32K_FTM_COMB_COMP | S32K_FTM_COMB_SYNCEN |",
     "COMBINE[DTENm] clear in the three pairs: no dead time inserted while the table "
     "compensates 1 us"),
    ("complementary-off", "mcu.c",
     "const uint32_t pair = comb | S32K_FTM_COMB_COMP | S32K_FTM_COMB_DTEN | S32K_FTM_COMB_SYNCEN |",
     "const uint32_t pair = comb | S32K_FTM_COMB_DTEN | S32K_FTM_COMB_SYNCEN |",
     "COMBINE[COMPm] clear: each low-side channel a PWM of its own (at 50 %) instead of the "
     "high side's complement: both switches of a leg on together"),
    ("soscdiv2-halved", "s32k144_port.h",
     "#define QFOC_S32K_SOSCDIV2_FIELD (1u)",
     "#define QFOC_S32K_SOSCDIV2_FIELD (2u)",
     "SCG_SOSCDIV[SOSCDIV2] divide by 2 instead of 1: the clock of LPIT0, LPUART1 and the CAN "
     "engine 4 MHz where the port counts 8 MHz (the tick period, the LIN and CAN bit rates doubled)"),
    ("adc-priority-below-tick", "s32k144_port.h",
     "#define QFOC_S32K_PRIO_ADC      (1u)",
     "#define QFOC_S32K_PRIO_ADC      (4u)",
     "the ADC-complete interrupt at priority 4, below the 1 ms interrupt (3)"),
]
DEFECT_SCENARIOS = ["short", "tick-preempted"]


def build(name, fname, old, new, a):
    d = os.path.join(a.out, name)
    src = os.path.join(d, "port_s32k")
    if os.path.isdir(src):
        shutil.rmtree(src)
    os.makedirs(src)
    for f in glob.glob(os.path.join(PORT, "*.[chS]")) + [os.path.join(PORT, "s32k144.ld")]:
        shutil.copy(f, src)
    if fname is not None:
        p = os.path.join(src, fname)
        text = open(p).read()
        if text.count(old) != 1:
            raise SystemExit("defects: %s: the text to substitute occurs %d times in %s"
                             % (name, text.count(old), fname))
        open(p, "w").write(text.replace(old, new))
    objs = []
    cflags = shlex.split(a.cflags) + ["-I" + src, "-I" + os.path.join(ROOT, "tables"),
                                      "-I" + os.path.join(ROOT, "include")]
    for f in sorted(glob.glob(os.path.join(src, "*.c")) + glob.glob(os.path.join(src, "*.S"))) + \
            [os.path.join(ROOT, "tables", "reference_params.c")]:
        o = os.path.join(d, "obj", os.path.splitext(os.path.basename(f))[0] + ".o")
        os.makedirs(os.path.dirname(o), exist_ok=True)
        subprocess.check_call([a.cc] + cflags + ["-c", f, "-o", o], cwd=ROOT)
        objs.append(o)
    elf = os.path.join(d, "qfoc_compressor.elf")
    subprocess.check_call([a.cc] + shlex.split(a.ldflags) + ["-T", os.path.join(src, "s32k144.ld"),
                          "-Wl,-Map=" + os.path.join(d, "qfoc_compressor.map")] + objs + [a.lib, "-o", elf],
                          cwd=ROOT)
    return elf


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cc", default="arm-none-eabi-gcc")
    ap.add_argument("--cflags", required=True)
    ap.add_argument("--ldflags", required=True)
    ap.add_argument("--lib", required=True)
    ap.add_argument("--out", default=os.path.join(ROOT, "build", "pil", "defects"))
    ap.add_argument("--only", default=None)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--plant-lib", default=None)
    ap.add_argument("--twin-lib", default=None)
    a = ap.parse_args(argv[1:])
    sel = [x for x in DEFECTS if a.only is None or x[0] in a.only.split(",") or x[0] == "control"]
    rows = []
    for name, fname, old, new, what in sel:
        elf = build(name, fname, old, new, a)
        res = sc.run_all(elf, DEFECT_SCENARIOS, a.jobs, os.path.join(a.out, name, "logs"), a.plant_lib,
                         a.twin_lib, quiet=True)
        failed = ["%s: %s (%s)" % (n, w, d) for n, ok, checks, lsd, dt in res for w, g, d in checks if not g]
        if name == "control":
            verdict = "PASS" if not failed else "FAIL"
        else:
            verdict = "caught" if failed else "MISSED"
        rows.append((name, verdict, what, failed))
        print("%-28s %-7s %s" % (name, verdict, what), flush=True)
        for f in failed:
            print("%-36s by %s" % ("", f), flush=True)
    bad = [r for r in rows if r[1] in ("MISSED", "FAIL")]
    print("pil-defects: %d seeded defects, %d caught, %d missed; control %s"
          % (len(rows) - 1, sum(1 for r in rows if r[1] == "caught"), sum(1 for r in rows if r[1] == "MISSED"),
             next((r[1] for r in rows if r[0] == "control"), "-")))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
