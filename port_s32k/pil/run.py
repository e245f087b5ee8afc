#!/usr/bin/env python3
"""run.py -- processor in the loop: the unchanged S32K144 image from its reset vector on
the emulated Cortex-M4 (core.py) with register-level peripherals (periph.py) and real
interrupts, driving the simulated motor of sim/ (plant.py).

Usage: run.py IMAGE.elf [--ms 300] [--motor specs/motors/reference.toml] [--vdc 320]
              [--lib build/pil/libpilplant.so] [--lin-period-ms 20] [--power-on-ms T]
              [--rpm 1500] [--fault-ms T]

Coupling, at each reload point of FTM3 (counter at MOD, SYNC[CNTMAX]; the centre of the
all-low-side zero vector and the sampling instant of the port, port_s32k/README.md):
the compare values C0V, C2V, C4V in effect from that point and the enable (all six outputs
switching, PTD5 high) go to the plant, which integrates the period that has just ended
(sim_step_period) and is then sampled (sim_sample): the ADC model converts these codes
when the PDB pre-triggers start its conversions (i_u on ADC0_SE3, i_v on ADC1_SE2, V_dc on
ADC1_SE8).  The plant samples only at period starts: a conversion that does not start at
the reload instant (T_PCB, T_IPM and V_dc, back to back after it) converts the values of
that instant (counted as `off-instant` conversions; the bus is constant here).  The NTC
inputs read 2048 (25 degC: no thermal model).

Commands (optional): the LIN master sends a command frame (SYNC, PID(0x10), 4 data bytes,
enhanced checksum; include/qfoc/link.h, specs/link-frames.md) every --lin-period-ms on
the LPUART1 receive line, break first; power_on is set from --power-on-ms on.

Fault (optional, --fault-ms): the over-current comparator asserts FTM3_FLT0 from that time
on; the bridge must be off from the next reload point and the drive must end in ERROR.

Expectations checked (exit status 1 when one fails): no stop of the run and no
watchdog reset; FTM3 period interrupts at the PWM frequency and one ADC1 interrupt per
PWM period once the PWM runs (+-2); one LPIT0 interrupt per ms (+-1); the watchdog
refreshed at every tick; the compare values written (LDOK) before the next reload point
after their samples; the drive state reported on CAN reaches STOP (ready) after PRECHARGE
(or RUN with --power-on-ms).
"""
import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import core as core_mod  # noqa: E402
import periph  # noqa: E402
import plant as plant_mod  # noqa: E402

ROOT = plant_mod.ROOT
STATES = {0: "PRECHARGE", 1: "STOP", 2: "RUN", 3: "ERROR"}
IRQS = {122: "FTM3 period", 40: "ADC1 complete", 48: "LPIT0 1 ms", 33: "LPUART1"}


def lin_pid(i):
    i &= 0x3F
    b = [(i >> k) & 1 for k in range(6)]
    p0 = b[0] ^ b[1] ^ b[2] ^ b[4]
    p1 = 1 - (b[1] ^ b[3] ^ b[4] ^ b[5])
    return i | (p0 << 6) | (p1 << 7)


def lin_checksum(data):
    s = 0
    for x in data:
        s += x
        if s > 255:
            s -= 255
    return 255 - s


def command_frame(power_on, rpm, fault_clear=False, id_cmd=0x10):
    pid = lin_pid(id_cmd)
    data = [(1 if power_on else 0) | (2 if fault_clear else 0), rpm & 0xFF, (rpm >> 8) & 0xFF, 0]
    return bytes([0x55, pid] + data + [lin_checksum([pid] + data)])


class PIL:
    def __init__(self, elf, motor, vdc, lib):
        self.core = core_mod.Core(elf)
        self.dev = periph.build(self.core)
        self.plant = plant_mod.Plant(lib, motor, vdc)
        ftm = self.dev["FTM3"]
        ftm.on_reload = self.on_reload
        self.dev["ADC0"].analog = self.analog
        self.dev["ADC1"].analog = self.analog
        self.codes = [2048, 2048, 0]
        self.t_sample = None
        self.off_instant = 0
        self.latencies = []          # PDB1 pre-trigger 0 -> LDOK write, core clocks
        self.late_writes = 0
        self.enabled_periods = 0
        self.t_first_reload = None
        self.t_fault = None          # FTM3_FLT0 asserted from this core clock
        self.on_after_fault = 0      # periods that started with the bridge on after it

    def gate_on(self):
        return self.dev["GPIOD"].pin_high(5)

    def on_reload(self, t):
        ftm = self.dev["FTM3"]
        if self.t_first_reload is None:
            self.t_first_reload = t
        pre = self.dev["PDB1"].pretrig_times
        if pre:
            tp = pre[-1]
            after = [w for w in ftm.ldok_writes if w > tp]
            if after:
                self.latencies.append(after[0] - tp)     # the first write after the samples
            elif len(pre) > 1:
                self.late_writes += 1
        ftm.ldok_writes = []
        on = ftm.outputs_on() and self.gate_on()
        self.enabled_periods += 1 if on else 0
        if self.t_fault is not None and t > self.t_fault and on:
            self.on_after_fault += 1
        self.plant.step([ftm.r["C0V"], ftm.r["C2V"], ftm.r["C4V"]], on)
        self.codes = self.plant.sample()
        self.t_sample = t

    def analog(self, adc, ch, t):
        table = {(0, 3): 0, (1, 2): 1, (1, 8): 2}
        k = table.get((adc, ch))
        if k is None:
            if (adc, ch) in ((0, 12), (1, 7)):
                return 2048                          # NTC at 25 degC
            raise core_mod.Stop("ADC%d channel %d has no input in the plant" % (adc, ch))
        if t != self.t_sample:
            self.off_instant += 1
        return self.codes[k]


def stats(xs):
    if not xs:
        return "-"
    return "%d / %.1f / %d" % (min(xs), sum(xs) / len(xs), max(xs))


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("elf")
    ap.add_argument("--ms", type=float, default=300.0)
    ap.add_argument("--motor", default=os.path.join(ROOT, "specs", "motors", "reference.toml"))
    ap.add_argument("--vdc", type=float, default=320.0)
    ap.add_argument("--lib", default=os.path.join(ROOT, "build", "pil", "libpilplant.so"))
    ap.add_argument("--lin-period-ms", type=float, default=0.0,
                    help="send a LIN command frame this often (0: no LIN traffic)")
    ap.add_argument("--power-on-ms", type=float, default=None,
                    help="from this time on the command requests RUN")
    ap.add_argument("--rpm", type=int, default=1500)
    ap.add_argument("--fault-ms", type=float, default=None,
                    help="assert the over-current input FTM3_FLT0 (PTE7 low) from this time on")
    args = ap.parse_args(argv[1:])

    plant_mod.build(args.lib)
    pil = PIL(args.elf, args.motor, args.vdc, args.lib)
    c, d = pil.core, pil.dev
    hz = core_mod.CORE_HZ
    c.boot()
    t_end = int(args.ms * hz / 1000)
    state_log = []
    next_lin = int(args.lin_period_ms * hz / 1000) if args.lin_period_ms > 0 else None
    t = 0
    step = hz // 1000
    lin_sent = 0
    while t < t_end and c.stopped is None:
        t = min(t + step, t_end)
        if next_lin is not None and c.cycles >= next_lin and d["LPUART1"].r["CTRL"] & (1 << 18):
            on = args.power_on_ms is not None and c.cycles >= args.power_on_ms * hz / 1000
            d["LPUART1"].inject(c.cycles, command_frame(on, args.rpm))
            lin_sent += 1
            next_lin += int(args.lin_period_ms * hz / 1000)
        if args.fault_ms is not None and pil.t_fault is None and c.cycles >= args.fault_ms * hz / 1000:
            pil.t_fault = c.cycles
            d["FTM3"].set_fault(True)
        c.run_until(t)
        for (tc, ident, dlc, data) in d["CAN0"].frames[len(state_log):]:
            state_log.append((tc, data[0] & 0xF, data[0] >> 4, data))
    ms = c.cycles * 1000.0 / hz

    # ------------------------------------------------------------------ report
    print("pil: %s, %.1f ms simulated (%d core clocks at 80 MHz), %d instructions executed"
          % (os.path.basename(args.elf), ms, c.cycles, c.insns))
    if c.stopped:
        print("pil: RUN STOPPED: %s" % c.stopped)
    ftm_hz = None
    per = d["FTM3"].r["MOD"]
    if per:
        ftm_hz = hz / (2.0 * per)
    print("\n%-16s %7s %10s %24s %26s %22s" % ("interrupt", "count", "rate", "instructions min/mean/max",
                                                "clocks w. entry+return", "latency clk min/mean/max"))
    counts = {}
    for irq, name in IRQS.items():
        st = c.irq_stats.get(irq, [])
        counts[irq] = len(st)
        rate = ""
        if name.startswith("FTM") or name.startswith("ADC"):
            span = (c.cycles - (pil.t_first_reload or 0)) / hz
            rate = "%.0f Hz" % (len(st) / span) if span > 0 and st else "-"
        elif name.startswith("LPIT"):
            rate = "%.0f Hz" % (len(st) / (c.cycles / hz)) if st else "-"
        print("%-16s %7d %10s %24s %26s %22s" % (name, len(st), rate, stats([s[0] for s in st]),
                                                 stats([s[1] for s in st]), stats([s[2] for s in st])))
    busy = sum(s[1] for st in c.irq_stats.values() for s in st)
    print("pre-emptions (nested entries) %d, tail chains %d; clocks in handlers %.1f %% of the run"
          % (c.preemptions, c.tailchains, 100.0 * busy / max(1, c.cycles)))
    print("(instructions: the handler's own, nested handlers excluded; clocks: with the entry, %d "
          "(%d tail-chained), and the return, %d (none when it tail-chains); latency: request to "
          "the handler's first instruction, entry included)"
          % (core_mod.ENTRY_CYCLES, core_mod.TAILCHAIN_CYCLES, core_mod.RETURN_CYCLES))
    lat = pil.latencies
    if lat:
        print("\nPDB pre-trigger (sampling instant) -> compare values loaded (PWMLOAD[LDOK] write): "
              "%s clocks = %.2f / %.2f / %.2f us (deadline: the next reload point, %d clocks)"
              % (stats(lat), min(lat) / 80.0, sum(lat) / len(lat) / 80.0, max(lat) / 80.0, 2 * per))
        dly = d["PDB1"].r["CH0DLY0"]
        print("PDB trigger input (FTM3 init trigger, counter at CNTIN) -> LDOK write: %s clocks "
              "(CH0DLY0 = %d plus the above)" % (stats([x + dly for x in lat]), dly))
    print("ADC conversions: ADC0 %d, ADC1 %d; PDB sequence errors ADC0 0x%02X ADC1 0x%02X; "
          "conversions off the reload instant %d; trigger conflicts %d/%d"
          % (d["ADC0"].conversions, d["ADC1"].conversions, d["PDB0"].r["CH0S"] & 0xFF,
             d["PDB1"].r["CH0S"] & 0xFF, pil.off_instant, d["ADC0"].conflicts, d["ADC1"].conflicts))
    print("watchdog refreshes %d, timeouts (resets) %d; LPIT timeouts %d; plant periods %d (%d with "
          "the bridge switching); CAN frames %d; LIN frames sent to the drive %d, bytes from it %d"
          % (d["WDOG"].refreshes, getattr(c, "wdog_timeouts", 0), d["LPIT0"].timeouts, pil.plant.steps,
             pil.enabled_periods, len(d["CAN0"].frames), lin_sent, len(d["LPUART1"].tx_log)))
    # LIN status frames from the drive: break, SYNC, PID(0x11), 8 data bytes, checksum
    frames, cur = [], None
    for tc, item in d["LPUART1"].tx_log:
        if item == "BRK":
            cur = [tc]
            frames.append(cur)
        elif cur is not None:
            cur.append(item)
    good = [f for f in frames if len(f) == 12 and f[1] == 0x55 and f[2] == lin_pid(0x11)
            and f[11] == lin_checksum(f[2:11])]
    lin_states = sorted(set(STATES.get(f[3] & 0xF, "?") for f in good))
    print("LIN status frames from the drive: %d, %d well-formed (PID, checksum), states %s"
          % (len(frames), len(good), ", ".join(lin_states) or "-"))
    trig = d["PDB1"].trigger_times
    offs = []
    k = 0
    for st in c.irq_stats.get(40, []):
        while k + 1 < len(trig) and trig[k + 1] <= st[3]:
            k += 1
        if trig and trig[k] <= st[3]:
            offs.append(st[3] - trig[k])
    if offs:
        print("ADC1 interrupt request after the period's FTM3 init trigger (PDB1 CH0DLY0 = %d, then "
              "3 conversions): %s clocks" % (d["PDB1"].r["CH0DLY0"], stats(offs)))
    ph = []
    k = 0
    for st in c.irq_stats.get(48, []):
        while k + 1 < len(trig) and trig[k + 1] <= st[3]:
            k += 1
        if trig and trig[k] <= st[3]:
            ph.append(st[3] - trig[k])
    if ph:
        print("LPIT0 request after the period's FTM3 init trigger: %s clocks: a fixed phase (the tick "
              "and the PWM both come from the 8 MHz crystal)" % stats(ph))
    if c.preempt_pairs:
        print("pre-emptions: " + ", ".join("%s by %s %d" % (IRQS.get(a, a), IRQS.get(b, b), n)
                                            for (a, b), n in sorted(c.preempt_pairs.items())))
    final = state_log[-1] if state_log else None
    seen = []
    for tc, s, sub, _ in state_log:
        if not seen or seen[-1][1:] != (s, sub):
            seen.append((tc, s, sub))
    print("drive states (CAN status frame, byte 0): " +
          ", ".join("%s/%d at %.1f ms" % (STATES.get(s, s), sub, tc * 1000.0 / hz) for tc, s, sub in seen))
    ps = pil.plant.state()
    print("plant: t %.4f s, w_e %.1f rad/s, id %.2f A, iq %.2f A" % (ps["t"], ps["w_e"], ps["id"], ps["iq"]))

    # ------------------------------------------------------------------ verdict
    checks = []
    checks.append(("the run completes without a stop", c.stopped is None, c.stopped or ""))
    checks.append(("no watchdog reset", c.resets == 0, "%d" % c.resets))
    n_per = d["FTM3"].reloads
    checks.append(("FTM3 period interrupt once per PWM period (%d periods, %.0f Hz)" % (n_per, ftm_hz or 0),
                   abs(counts[122] - n_per) <= 2 and n_per > 0, "%d" % counts[122]))
    checks.append(("ADC1 interrupt once per PWM period", abs(counts[40] - n_per) <= 2 and n_per > 0,
                   "%d" % counts[40]))
    n_ms = d["LPIT0"].timeouts
    checks.append(("LPIT0 tick every 1 ms (%d timeouts)" % n_ms,
                   abs(counts[48] - n_ms) <= 1 and abs(n_ms - (c.cycles - 0) / 80000.0) <= 2,
                   "%d" % counts[48]))
    checks.append(("watchdog refreshed by every tick", abs(d["WDOG"].refreshes - counts[48]) <= 1,
                   "%d" % d["WDOG"].refreshes))
    checks.append(("compare values written before the next reload point",
                   bool(lat) and max(lat) < 2 * per and pil.late_writes <= 1,
                   "late %d" % pil.late_writes))
    if pil.t_fault is not None:
        checks.append(("bridge off from the reload point after the fault input (%.1f ms)"
                       % (pil.t_fault * 1000.0 / hz), pil.on_after_fault == 0,
                       "%d periods on" % pil.on_after_fault))
    want = 2 if args.power_on_ms is not None else 1
    if args.fault_ms is not None:
        want = 3
    checks.append(("drive reaches %s" % STATES[want], final is not None and final[1] == want,
                   STATES.get(final[1], "?") if final else "no CAN frame"))
    print()
    ok = True
    for what, good, detail in checks:
        ok &= bool(good)
        print("%-4s %s (%s)" % ("PASS" if good else "FAIL", what, detail))
    print("pil: %s" % ("PASS" if ok else "FAIL"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
