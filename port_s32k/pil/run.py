#!/usr/bin/env python3
"""run.py -- processor in the loop: the unchanged S32K144 image from its reset vector on
the emulated Cortex-M4 (core.py) with register-level peripherals (periph.py) and real
interrupts, driving the simulated motor of sim/ (plant.py).

Usage: run.py IMAGE.elf [--ms 300] [--motor specs/motors/reference.toml] [--vdc 320]
              [--lib build/pil/libpilplant.so] [--lin-period-ms 20] [--power-on-ms T]
              [--rpm 1500] [--fault-ms T]

Coupling, at each reload point of FTM3 (counter at MOD, SYNC[CNTMAX]; the centre of the
all-low-side zero vector and the sampling instant of the port, port_s32k/README.md):
the six gate signals of the period that starts there, computed from the FTM3 registers in
effect (periph.FTM.pin_on: complementary pairs, dead time, polarity, mask, fault; PTD5 low
holds every switch off), give the plant its compare values, its enable and its dead time
(periph.bridge), and the plant integrates the period that has just ended
(sim_step_period) and is then sampled (sim_sample): the ADC model converts these codes
when the PDB pre-triggers start its conversions at the reload instant (i_u on ADC0_SE3,
i_v on ADC1_SE2).  A conversion that starts later in the period (V_dc on ADC1_SE8, back to
back after i_v; counted as `off-instant` conversions) converts the plant at its own
instant: a copy of the plant integrated from the reload point to it with the period's
settings (sim_sample_at).  The NTC inputs (ADC0_SE12, ADC1_SE7) read 2048 (25 degC: the
plant has no thermal model, so their instant does not matter).

Commands (optional): the LIN master sends a command frame (SYNC, PID(0x10), 4 data bytes,
enhanced checksum; include/qfoc/link.h, specs/link-frames.md) every --lin-period-ms on
the LPUART1 receive line, break first; power_on is set from --power-on-ms on.

Fault (optional, --fault-ms): the over-current comparator asserts FTM3_FLT0 from that time
on; the bridge must be off from the next reload point and the drive must end in ERROR.

Expectations checked (exit status 1 when one fails): no stop of the run and no
watchdog reset; FTM3 period interrupts at the PWM frequency and one ADC1 interrupt per
PWM period once the PWM runs (+-2); one LPIT0 interrupt per ms (+-1); the rates from the
registers and the clock tree (periph.SCG.clock_tree): the PWM frequency against the
table's f_pwm_hz, the LPIT0 period against 1 ms, LIN 19200 baud +-1.5 %, CAN 500 kbit/s
+-0.5 %; the inverter's
dead time from the FTM3 registers equal to the table's dead-time compensation (2 dt_comp
FTM clocks); the library's instructions within their static bound (timing.py); the watchdog
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
import twin as twin_mod  # noqa: E402
import timing as timing_mod  # noqa: E402

ROOT = plant_mod.ROOT
STATES = {0: "PRECHARGE", 1: "STOP", 2: "RUN", 3: "ERROR"}
# the phase currents convert at the reload point (PDB delay CH0DLY0 = MOD) or, for the
# second converter's chain, within one conversion time after it
SAMPLE_TOL = 200
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
        self.iu_conv = 0             # phase-current conversions
        self.iu_off = 0              # ... started more than SAMPLE_TOL clocks after the reload point
        self.latencies = []          # PDB1 pre-trigger 0 -> LDOK write, core clocks
        self.late_writes = 0
        self.enabled_periods = 0
        self.t_first_reload = None
        self.t_fault = None          # FTM3_FLT0 asserted from this core clock
        self.on_after_fault = 0      # periods that started with the bridge on after it
        self.lockstep = None         # twin.LockStep when --lockstep
        self.bridge_log = []         # (core clock, bridge switching) at each change
        self.w_log = []              # (core clock, plant electrical speed rad/s) every 10 ms
        self.reset_times = []        # core clocks of the watchdog resets
        self.t_gate_off = None       # first reload point with PTD5 low after an injection
        self.inject = None
        self.lin_last = None         # core clock of the last command frame sent
        self.dead_ticks = {}         # dead time from the FTM3 registers (FTM clocks) -> periods
        self.at_cache = (None, None)  # (core clock, plant codes) of the last off-instant conversion
        self.tau_log = {}            # (adc, channel) -> largest clocks after the reload point
        self.ntc_conv = 0

    def attach_lockstep(self, lib):
        self.lockstep = twin_mod.LockStep(self, lib)

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
        if self.inject is not None and t >= self.inject and self.t_gate_off is None and \
                not self.gate_on() and ftm.r["OUTMASK"] & 0x3F == 0x3F:
            self.t_gate_off = t
        if not self.bridge_log or self.bridge_log[-1][1] != on:
            self.bridge_log.append((t, on))
        if self.lockstep is not None:
            self.lockstep.on_reload(ftm, fault_latched=not self.gate_on())
        # the six gate signals from the registers (complementary pairs, dead time, polarity,
        # mask, fault; PTD5 low: the gate driver holds every switch off), and from them the
        # plant's inverter: compare values, enable and dead time
        pins = ftm.pin_on() if self.gate_on() else [[] for _ in range(6)]
        cmp3, td, on_pins = periph.bridge(pins, ftm.r["MOD"])
        if on_pins != on:
            raise core_mod.Stop("FTM3 outputs: the gate signals (%s) disagree with the enable "
                                "(OUTMASK, PWMEN, fault flag, PTD5: %s)" % (on_pins, on))
        if td is not None:
            self.dead_ticks[td] = self.dead_ticks.get(td, 0) + 1
            td_s = td / float(core_mod.CORE_HZ // ftm.tick())
            if self.plant.dead_time_s != td_s:
                self.plant.set_dead_time(td_s)
        self.enabled_periods += 1 if on else 0
        if self.t_fault is not None and t > self.t_fault and on:
            self.on_after_fault += 1
        self.plant.step(cmp3, on)
        self.codes = self.plant.sample()
        self.t_sample = t

    def analog(self, adc, ch, t):
        """The code a conversion started at core clock t converts: the plant's value at that
        instant (sim_sample_at, tau = t - the last reload point), the NTC inputs 2048."""
        table = {(0, 3): 0, (1, 2): 1, (1, 8): 2}
        k = table.get((adc, ch))
        if k is None:
            if (adc, ch) in ((0, 12), (1, 7)):
                self.ntc_conv += 1
                return 2048                          # NTC at 25 degC: no thermal model
            raise core_mod.Stop("ADC%d channel %d has no input in the plant" % (adc, ch))
        codes = self.codes
        if self.t_sample is not None and t != self.t_sample:
            self.off_instant += 1
            tau = t - self.t_sample
            if tau >= 2 * self.dev["FTM3"].r["MOD"] * self.dev["FTM3"].tick():
                raise core_mod.Stop("ADC%d channel %d converted %d clocks after the last reload "
                                    "point: beyond the plant's period" % (adc, ch, tau))
            if self.at_cache[0] != t:
                self.at_cache = (t, self.plant.sample_at(tau / float(core_mod.CORE_HZ)))
            codes = self.at_cache[1]
            self.tau_log[(adc, ch)] = max(self.tau_log.get((adc, ch), 0), tau)
        if k < 2:
            self.iu_conv += 1
            if self.t_sample is None or t - self.t_sample > SAMPLE_TOL:
                self.iu_off += 1
        return codes[k]


def stats(xs):
    if not xs:
        return "-"
    return "%d / %.1f / %d" % (min(xs), sum(xs) / len(xs), max(xs))


def main(argv):
    return execute(parse_args(argv[1:]))["rc"]


def parse_args(argv):
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
    ap.add_argument("--lockstep", action="store_true",
                    help="lock-step with the host build of the drive (twin.py)")
    ap.add_argument("--twin-lib", default=os.path.join(ROOT, "build", "pil", "libpiltwin.so"))
    ap.add_argument("--rpm-step-ms", type=float, default=None, help="from this time on command --rpm2")
    ap.add_argument("--rpm2", type=int, default=2500)
    ap.add_argument("--power-off-ms", type=float, default=None, help="from this time on power_on is clear")
    ap.add_argument("--lin-stop-ms", type=float, default=None,
                    help="the LIN master stops sending command frames at this time (link loss)")
    ap.add_argument("--stall-adc-isr-ms", type=float, default=None,
                    help="from this time on the ADC1 handler spins (a stalled interrupt)")
    ap.add_argument("--stuck-adc-ms", type=float, default=None,
                    help="from this time on ADC1 converts nothing (no conversion complete)")
    ap.add_argument("--tick-phase-clk", type=int, default=0,
                    help="delay the first LPIT0 timeout by this many core clocks (the tick's phase "
                         "in the PWM period)")
    ap.add_argument("--adc-latency-max", type=int, default=None,
                    help="expect every ADC1 interrupt latency (request -> first handler "
                         "instruction) at most this many clocks")
    ap.add_argument("--timing-json", default=None,
                    help="write the run's timing figures (timing.summary) to this file")
    ap.add_argument("--expect", default=None,
                    help="expected final state: PRECHARGE, STOP, RUN, ERROR or RESET (a watchdog reset)")
    return ap.parse_args(argv)



def since_trigger(irq_stats, trig):
    """The clocks from the last FTM3 init trigger (PDB1's, time-sorted) to each request of
    an interrupt's statistics (its request time is field 3); requests before the first
    trigger are left out."""
    out = []
    k = 0
    for st in irq_stats:
        while k + 1 < len(trig) and trig[k + 1] <= st[3]:
            k += 1
        if trig and trig[k] <= st[3]:
            out.append(st[3] - trig[k])
    return out

def execute(args):
    """One run; prints the report and returns a dict with the verdict and the figures."""

    plant_mod.build(args.lib)
    pil = PIL(args.elf, args.motor, args.vdc, args.lib)
    c, d = pil.core, pil.dev
    hz = core_mod.CORE_HZ
    twin_mod.build(args.twin_lib)
    if args.lockstep:
        pil.attach_lockstep(args.twin_lib)
    lib = timing_mod.LibTiming(c)
    bounds = timing_mod.static_bounds(args.elf)
    d["LPIT0"].first_delay = args.tick_phase_clk
    inject = None
    if args.stall_adc_isr_ms is not None:
        inject = int(args.stall_adc_isr_ms * hz / 1000)
        stall_at(c, inject)
    if args.stuck_adc_ms is not None:
        inject = int(args.stuck_adc_ms * hz / 1000)
        stuck_adc(d["ADC1"], inject)
    pil.inject = inject
    core_reset = c.reset

    def reset():
        pil.reset_times.append(c.now())
        core_reset()
    c.reset = reset
    if pil.lockstep is not None and inject is not None:
        pil.lockstep.compare_until = inject
    c.boot()
    t_end = int(args.ms * hz / 1000)
    state_log = []
    can_seen = 0
    can_list = d["CAN0"].frames
    next_lin = int(args.lin_period_ms * hz / 1000) if args.lin_period_ms > 0 else None
    t = 0
    step = hz // 1000
    lin_sent = 0
    while t < t_end and c.stopped is None:
        t = min(t + step, t_end)
        lin_on = args.lin_stop_ms is None or c.cycles < args.lin_stop_ms * hz / 1000
        if next_lin is not None and c.cycles >= next_lin and d["LPUART1"].r["CTRL"] & (1 << 18) and lin_on:
            on = args.power_on_ms is not None and c.cycles >= args.power_on_ms * hz / 1000
            if args.power_off_ms is not None and c.cycles >= args.power_off_ms * hz / 1000:
                on = False
            rpm = args.rpm
            if args.rpm_step_ms is not None and c.cycles >= args.rpm_step_ms * hz / 1000:
                rpm = args.rpm2
            d["LPUART1"].inject(c.cycles, command_frame(on, rpm))
            pil.lin_last = c.cycles
            lin_sent += 1
            next_lin += int(args.lin_period_ms * hz / 1000)
        if args.fault_ms is not None and pil.t_fault is None and c.cycles >= args.fault_ms * hz / 1000:
            pil.t_fault = c.cycles
            d["FTM3"].set_fault(True)
        c.run_until(t)
        if (t // step) % 10 == 0:
            pil.w_log.append((c.cycles, pil.plant.state()["w_e"]))
        frames = d["CAN0"].frames
        if frames is not can_list:
            can_list, can_seen = frames, 0     # the controller's log restarted with a reset
        for (tc, ident, dlc, data) in frames[can_seen:]:
            can_seen += 1
            state_log.append((tc, data[0] & 0xF, data[0] >> 4, data))
    pil.state_log = state_log
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
          "conversions off the reload instant %d (the plant converted at their instant, "
          "clocks after the reload point at most: %s), NTC %d (2048); trigger conflicts %d/%d"
          % (d["ADC0"].conversions, d["ADC1"].conversions, d["PDB0"].r["CH0S"] & 0xFF,
             d["PDB1"].r["CH0S"] & 0xFF, pil.off_instant,
             ", ".join("ADC%d_SE%d %d" % (a, ch, v) for (a, ch), v in sorted(pil.tau_log.items())) or "-",
             pil.ntc_conv, d["ADC0"].conflicts, d["ADC1"].conflicts))
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
    offs = since_trigger(c.irq_stats.get(40, []), trig)
    if offs:
        print("ADC1 interrupt request after the period's FTM3 init trigger (PDB1 CH0DLY0 = %d, then "
              "3 conversions): %s clocks" % (d["PDB1"].r["CH0DLY0"], stats(offs)))
    ph = since_trigger(c.irq_stats.get(48, []), trig)
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

    print("library entry points in the image (instructions from the first to the return "
          "instruction, callees included, nested handlers excluded) against their static bound "
          "(tools/bench/wcet.py on this image):")
    for f in timing_mod.FUNCS:
        print("  %-22s %6d calls, %s instructions (the longest at %s ms); static bound %d"
              % (f, len(lib.calls[f]), stats(lib.calls[f]),
                 "%.3f" % (lib.max_at[f] * 1000.0 / hz) if lib.max_at[f] is not None else "-", bounds[f]))
    dt = dead_time_report(pil, args.twin_lib)
    print(dt["text"])
    clk = clock_report(pil, args.twin_lib)
    print(clk["text"])
    summ = timing_mod.summary(c, pil, lib)
    summ["static_bound"] = bounds
    if args.timing_json:
        timing_mod.write(args.timing_json, summ)

    # ------------------------------------------------------------------ verdict
    ls = pil.lockstep
    if ls is not None:
        print(ls.report())
    adc_lat = [st[2] for st in c.irq_stats.get(40, [])]
    iu_off = pil.iu_off
    print("phase-current conversions (ADC0_SE3, ADC1_SE2) started off the reload instant: %d of %d; "
          "ADC1 latency max %s clocks" % (iu_off, pil.iu_conv, max(adc_lat) if adc_lat else "-"))
    lat_ok = bool(lat) and max(lat) < 2 * per and pil.late_writes <= 1
    t_inj = inject
    checks = []
    checks.append(("the run completes without a stop", c.stopped is None, c.stopped or ""))
    n_per = d["FTM3"].reloads
    n_ms = d["LPIT0"].timeouts
    expect = args.expect
    if expect is None:
        want = 2 if args.power_on_ms is not None else 1
        if args.fault_ms is not None:
            want = 3
        expect = STATES[want]
    if t_inj is None:
        checks.append(("no watchdog reset", c.resets == 0, "%d" % c.resets))
        checks.append(("FTM3 period interrupt once per PWM period (%d periods, %.0f Hz)" % (n_per, ftm_hz or 0),
                       abs(counts[122] - n_per) <= 2 and n_per > 0, "%d" % counts[122]))
        checks.append(("ADC1 interrupt once per PWM period", abs(counts[40] - n_per) <= 2 and n_per > 0,
                       "%d" % counts[40]))
        checks.append(("LPIT0 tick every 1 ms (%d timeouts)" % n_ms,
                       abs(counts[48] - n_ms) <= 1 and abs(n_ms - (c.cycles - args.tick_phase_clk) / 80000.0) <= 2,
                       "%d" % counts[48]))
        checks.append(("watchdog refreshed by every tick", abs(d["WDOG"].refreshes - counts[48]) <= 1,
                       "%d" % d["WDOG"].refreshes))
        checks.append(("compare values written before the next reload point", lat_ok,
                       "late %d" % pil.late_writes))
        checks.append(("phase currents sampled at the reload instant (centre of the low-side zero vector)",
                       pil.iu_conv > 0 and iu_off == 0, "%d of %d off" % (iu_off, pil.iu_conv)))
    over = ["%s %d > %d" % (f, max(lib.calls[f]), bounds[f]) for f in timing_mod.FUNCS
            if lib.calls[f] and max(lib.calls[f]) > bounds[f]]
    checks.append(("the library's measured instructions within their static bound (fast step %d, "
                   "tick %d)" % (bounds["qfoc_drive_fast_step"], bounds["qfoc_drive_tick"]),
                   not over, "; ".join(over) or "max %s" % ", ".join(
                       str(max(lib.calls[f])) if lib.calls[f] else "-" for f in timing_mod.FUNCS)))
    for what, good, detail in clk["checks"]:
        checks.append((what, good, detail))
    checks.append(("the inverter's dead time from the FTM3 registers equals the table's dead-time "
                   "compensation (2 dt_comp FTM clocks); the plant switched with it", dt["ok"], dt["detail"]))
    if args.adc_latency_max is not None:
        checks.append(("ADC1 interrupt latency <= %d clocks (never delayed by a lower-priority handler)"
                       % args.adc_latency_max, bool(adc_lat) and max(adc_lat) <= args.adc_latency_max,
                       "max %s" % (max(adc_lat) if adc_lat else "-")))
    if pil.t_fault is not None:
        checks.append(("bridge off from the reload point after the fault input (%.1f ms)"
                       % (pil.t_fault * 1000.0 / hz), pil.on_after_fault == 0,
                       "%d periods on" % pil.on_after_fault))
    if ls is not None:
        checks.append(("lock-step with the host build: no divergence (%d periods, %d ticks)"
                       % (ls.periods, ls.ticks_compared), ls.divergence is None and ls.periods > 0,
                       "first divergence at period %d: %s image %s host %s" % ls.divergence[:4]
                       if ls.divergence else "none"))
    if expect == "ANY":
        pass
    elif expect == "RESET":
        checks.append(("watchdog reset of the image after %.1f ms" % (t_inj * 1000.0 / hz if t_inj else 0),
                       c.resets >= 1, "%d resets" % c.resets))
    else:
        checks.append(("drive reaches %s" % expect, final is not None and STATES.get(final[1]) == expect,
                       STATES.get(final[1], "?") if final else "no CAN frame"))
    for what, good, detail in getattr(args, "extra_checks", lambda r: [])(
            {"pil": pil, "seen": seen, "hz": hz, "inject": t_inj}):
        checks.append((what, good, detail))
    print()
    ok = True
    for what, good, detail in checks:
        ok &= bool(good)
        print("%-4s %s (%s)" % ("PASS" if good else "FAIL", what, detail))
    print("pil: %s" % ("PASS" if ok else "FAIL"))
    return {"rc": 0 if ok else 1, "ok": ok, "checks": checks, "pil": pil, "seen": seen,
            "lockstep": ls, "ms": ms, "timing": summ, "lib": lib, "adc_latency_max": max(adc_lat) if adc_lat else None}


LIN_BAUD = 19200            # the LIN network's bit rate (QFOC_S32K_LIN_BAUD; specs/link-frames.md)
LIN_TOL = 0.015             # LIN 2.x: a slave node without synchronisation, +-1.5 %
CAN_BPS = 500_000           # the CAN network's bit rate (s32k144_port.h, McuCANConfig)
CAN_TOL = 0.005


def clock_report(pil, twin_lib):
    """The clock tree from the SCG registers (periph.SCG.clock_tree) and the clock of each
    peripheral the models count with, and the checks of the rates they give against the
    system's: the PWM frequency (f_FTM / (2 MOD), up-down counting) against the table's
    f_pwm_hz in the image, the LIN and CAN bit rates against the networks', the LPIT0
    period against 1 ms.  A quantity whose clock is off or whose peripheral was never set up
    is reported as '-' and its check fails."""
    d, c = pil.dev, pil.core
    tree = d["SCG"].clock_tree()
    hz = core_mod.CORE_HZ

    def mhz(f):
        return "-" if not f else "%g" % (f / 1e6)
    lines = ["clock tree from the SCG registers (SOSC 8 MHz crystal assumed), MHz: " + ", ".join(
        "%s %s" % (k, mhz(tree.get(k))) for k in ("SOSC", "SPLL", "SOSCDIV1", "SOSCDIV2", "SPLLDIV1",
                                                  "SPLLDIV2", "CORE", "SYS", "BUS", "FLASH"))]
    checks = []

    def safe(fn):
        try:
            return fn()
        except core_mod.Stop as e:
            return "%s" % e
    ftm = d["FTM3"]
    t_ftm = safe(ftm.tick)
    f_pwm = None
    if isinstance(t_ftm, int) and ftm.r["MOD"]:
        f_pwm = hz / t_ftm / (2.0 * ftm.r["MOD"])
    a = c.syms.get("qfoc_params_reference")
    off = twin_mod.f_pwm_offset(twin_lib)
    f_tab = int.from_bytes(bytes(c.flash[a + off:a + off + 2]), "little") if a is not None else None
    lines.append("  FTM3: SC[CLKS] = %d (SYS_CLK), PS /%d: %s MHz; MOD %d, up-down: PWM %s Hz (table f_pwm_hz %s)"
                 % ((ftm.r["SC"] >> 3) & 3, 1 << (ftm.r["SC"] & 7),
                    mhz(hz / t_ftm) if isinstance(t_ftm, int) else t_ftm, ftm.r["MOD"],
                    "%.1f" % f_pwm if f_pwm else "-", f_tab))
    checks.append(("PWM frequency from the FTM3 registers and the clock tree equals the table's f_pwm_hz",
                   f_pwm is not None and f_tab is not None and abs(f_pwm - f_tab) < 1e-6 * f_tab,
                   "%s Hz, table %s Hz" % ("%.1f" % f_pwm if f_pwm else "-", f_tab)))
    for k in (0, 1):
        p = d["PDB%d" % k]
        lines.append("  PDB%d: SYS_CLK %s MHz, %d core clocks per count; CH0DLY0 %d counts = %d clocks"
                     % (k, mhz(tree.get("SYS")), safe(p.clk) if isinstance(safe(p.clk), int) else -1,
                        p.r["CH0DLY0"], p.r["CH0DLY0"] * (safe(p.clk) if isinstance(safe(p.clk), int) else 0)))
        adc = d["ADC%d" % k]
        f = safe(adc.adck_hz)
        lines.append("  ADC%d: PCC PCS %d (DIV2), ADIV %d: ADCK %s MHz; conversion %s ADCK (SMPLTS + 1 + %d, "
                     "the compare clocks an assumption)"
                     % (k, pil.core.pcc_dev.pcs(adc.pcc), (adc.r["CFG1"] >> 5) & 3,
                        mhz(f) if isinstance(f, int) else f, (adc.r["CFG2"] & 0xFF) + 1 + periph.ADC_COMPARE_CLOCKS,
                        periph.ADC_COMPARE_CLOCKS))
    lp = d["LPIT0"]
    t_l = safe(lp.clk)
    per = (lp.r["TVAL0"] + 1) * t_l if isinstance(t_l, int) else None
    lines.append("  LPIT0: PCC PCS %d (DIV2) %s MHz, TVAL0 %d: period %s clocks"
                 % (c.pcc_dev.pcs(lp.pcc), mhz(hz / t_l) if isinstance(t_l, int) else t_l, lp.r["TVAL0"], per))
    checks.append(("LPIT0 period from its registers and the clock tree: 1 ms", per == hz // 1000,
                   "%s clocks" % per))
    t_u = safe(d["LPUART1"].bit_cycles)
    baud = hz / t_u if isinstance(t_u, int) and t_u else None
    lines.append("  LPUART1: PCC PCS %d (DIV2), BAUD 0x%08X: %s baud (LIN %d)"
                 % (c.pcc_dev.pcs(d["LPUART1"].pcc), d["LPUART1"].r["BAUD"],
                    "%.1f" % baud if baud else t_u, LIN_BAUD))
    checks.append(("LIN bit rate from LPUART1's registers and the clock tree: %d baud +-%.1f %%"
                   % (LIN_BAUD, 100 * LIN_TOL), baud is not None and abs(baud / LIN_BAUD - 1) <= LIN_TOL,
                   "%s baud" % ("%.1f" % baud if baud else "-")))
    can = d["CAN0"]
    t_c = safe(can.bit_cycles) if can.r["CTRL1"] else "CAN0 not set up"
    bps = hz / t_c if isinstance(t_c, int) and t_c else None
    lines.append("  CAN0: CTRL1[CLKSRC] = 0 (SOSCDIV2 %s MHz): %s bit/s (network %d)"
                 % (mhz(tree.get("SOSCDIV2")), "%.0f" % bps if bps else t_c, CAN_BPS))
    checks.append(("CAN bit rate from CAN0's registers and the clock tree: %d bit/s +-%.1f %%"
                   % (CAN_BPS, 100 * CAN_TOL), bps is not None and abs(bps / CAN_BPS - 1) <= CAN_TOL,
                   "%s bit/s" % ("%.0f" % bps if bps else "-")))
    return {"text": "\n".join(lines), "checks": checks, "tree": tree, "f_pwm": f_pwm, "baud": baud,
            "bps": bps, "lpit_period": per}


def dead_time_report(pil, twin_lib):
    """The dead time the image's FTM3 set-up inserts (DEADTIME with DTEN of the three pairs:
    FTM.dead_ticks()) and the dead times of the periods the plant switched (from the gate
    signals, periph.bridge) against the table's dead-time compensation in the image
    (qfoc_params_reference.svpwm.dt_comp, one compare count = 2 FTM clocks of high time:
    tables/reference_params.c); the port derives its dead time from it
    (qfoc_s32k_pwm_cfg), so a difference is a compensation that does not match the
    inverter."""
    ftm = pil.dev["FTM3"]
    c = pil.core
    off, host = twin_mod.dt_comp_field(twin_lib)
    a = c.syms.get("qfoc_params_reference")
    if a is None:
        return {"ok": False, "detail": "no qfoc_params_reference in the image", "text": ""}
    dt_comp = int.from_bytes(bytes(c.flash[a + off:a + off + 2]), "little")
    want = 2 * dt_comp
    dten = [bool(ftm.r["COMBINE"] & (0x10 << (8 * k))) for k in range(3)]
    reg = ftm.dead_ticks() if all(dten) else (0 if not any(dten) else None)
    f_ftm = core_mod.CORE_HZ // ftm.tick() if ftm.r["SC"] & 0x18 else core_mod.CORE_HZ
    seen = dict(sorted(pil.dead_ticks.items()))
    ok = reg == want and all(k == want for k in seen) and dt_comp == host
    text = ("inverter dead time from FTM3: DEADTIME 0x%08X, DTEN %s -> %s FTM clocks (%s us at %.0f MHz); "
            "periods switched by dead time (FTM clocks: periods) %s; the table's compensation dt_comp %d "
            "(image; host table %d) = %d FTM clocks"
            % (ftm.r["DEADTIME"], "".join("1" if x else "0" for x in dten), reg,
               "%.3f" % (reg * 1e6 / f_ftm) if reg is not None else "-", f_ftm / 1e6,
               seen or "none", dt_comp, host, want))
    detail = "registers %s, periods %s, table %d" % (reg, ",".join(str(k) for k in seen) or "-", want)
    return {"ok": ok, "detail": detail, "text": text, "reg": reg, "seen": seen, "want": want}


def stall_at(c, t0):
    """From core clock t0 on, the ADC1 handler (qfoc_s32k_adc_isr) spins at its entry: a
    stalled interrupt (the PC is set to a `b .` found in the image)."""
    from unicorn import UC_HOOK_CODE
    from unicorn.arm_const import UC_ARM_REG_PC
    spins = list(c._find(0xE7FE))
    if not spins:
        raise core_mod.Stop("no `b .` in the image for the stall")
    target = spins[0]
    a = c.syms["qfoc_s32k_adc_isr"] & ~1

    done = []

    def hook(mu, addr, size, data):
        if c.now() >= t0 and not done:             # once: the image restarts after the reset
            done.append(c.now())
            mu.reg_write(UC_ARM_REG_PC, target | 1)
    c.mu.hook_add(UC_HOOK_CODE, hook, begin=a, end=a)


def stuck_adc(adc, t0):
    """From core clock t0 on, the converter starts no conversion (no COCO, no interrupt)."""
    orig = adc.pretrigger

    def pretrigger(n, t):
        if t >= t0:
            return
        orig(n, t)
    adc.pretrigger = pretrigger


if __name__ == "__main__":
    sys.exit(main(sys.argv))
