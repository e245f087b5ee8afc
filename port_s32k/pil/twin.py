"""twin.py -- lock-step of the image with the host build of the same drive.

The host twin is the library (src/*.c) compiled for the host with the image's parameter
table (tables/reference_params.c: main.c's table of the 8 kHz image, mk/port.mk) and the
flat interface of pil_twin.c, called with ctypes.  It is driven from what the image's code
actually passes, read from the image's memory by Unicorn code hooks on the entries of the
image's functions:

- qfoc_drive_init (main.c): the twin is initialised (again after a watchdog reset);
- qfoc_drive_fast_step (called by qfoc_s32k_adc_isr, isr.c): r0 = the result's address
  (qfoc_pwm_t, 8 bytes, returned in memory, AAPCS), r1 = the drive, r2 = &adc; the twin's
  fast step is called with the three codes the image's ADC read delivered (qfoc_adc_t:
  iu, iv, vdc, uint16 each);
- qfoc_drive_tick (called by qfoc_s32k_tick_isr): r0 = the result's address
  (qfoc_tick_out_t), r2 = &in (qfoc_tick_in_t: t_ipm, t_pcb int16 at 0 and 2, rx pointer
  at 4, rx_len at 8): the inputs are read at the entry (the same temperatures, the same
  received bytes: the frame the UART receive path assembled); the twin's tick runs at
  the return address (a code hook on the caller's instruction after the call); then the image's qfoc_tick_out_t is read from the result's
  address and compared field by field with the twin's (tx_len, tx[0..tx_len), the CAN
  frame id, dlc, data, can_send, pwm_off).  Without pre-emption the order is the image's
  exactly.  A fast step that pre-empts the image's tick (a tick pending at its entry) is
  run in the twin in both orders, from saved copies of the twin's state: before the tick
  and after it (the tick then done at that point).  The twin keeps a set of candidate
  states (normally one): every fast step's result (qfoc_pwm_t at r0, read at its
  return) and every tick's output keep the candidates that produced them; no candidate
  left is a divergence (a fast step that read part of the tick's writes, which drive.h
  allows, shows as one: the twin's limit under pre-emption).

The calls reach the twin in the image's order, with the image's inputs.  At each FTM3
reload point the compare values in effect (C0V..C5V, as loaded from the buffers with
LDOK) and the enable (OUTMASK = 0) are compared with what the twin's last fast step
implies for the port's qfoc_hal_pwm_write (hal_s32k.c, two current sensors): C(2k)V =
min(cmp[k], MOD), the odd channels as the initialisation set them (the even channel's CnV
sets both edges), OUTMASK = 0 exactly when enable (and the port's fault latch is not
set).  A tick's pwm_off also writes {0, 0, 0, off}, which the next fast step overwrites
before the next reload point; the twin applies it at the image's tick return.  The first
divergence stops the comparison and is reported (period, field, image value, host
value).  compare_until (core clock) ends the comparison at an injected port-level fault
(a stalled interrupt, a stuck converter), after which the image and the drive are meant
to differ.

Requirement: REQ-PIL-003 (specs/requirements/pil.md).
"""
import ctypes
import os
import struct
import subprocess

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))


def sources():
    src = sorted(os.path.join(ROOT, "src", f) for f in os.listdir(os.path.join(ROOT, "src"))
                 if f.endswith(".c"))
    return [os.path.join(HERE, "pil_twin.c"), os.path.join(ROOT, "tables", "reference_params.c")] + src


def build(out):
    srcs = sources()
    hdr_dirs = [os.path.join(ROOT, "include", "qfoc"), os.path.join(ROOT, "src"), os.path.join(ROOT, "tables")]
    deps = srcs + [os.path.join(d, f) for d in hdr_dirs for f in os.listdir(d) if f.endswith(".h")]
    if os.path.exists(out) and all(os.path.getmtime(out) >= os.path.getmtime(s) for s in deps):
        return out
    os.makedirs(os.path.dirname(out), exist_ok=True)
    subprocess.check_call(["gcc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-O2", "-shared", "-fPIC",
                           "-I" + os.path.join(ROOT, "include"), "-I" + os.path.join(ROOT, "tables")]
                          + srcs + ["-o", out])
    return out


def dt_comp_field(lib_path):
    """(offset of svpwm.dt_comp in qfoc_param_table_t, the host table's dt_comp), from the
    twin's library (pil_twin.c)."""
    lib = ctypes.CDLL(lib_path)
    lib.pil_twin_dt_comp_offset.restype = ctypes.c_uint32
    lib.pil_twin_dt_comp.restype = ctypes.c_uint32
    return lib.pil_twin_dt_comp_offset(), lib.pil_twin_dt_comp()


def f_pwm_offset(lib_path):
    """The offset of f_pwm_hz in qfoc_param_table_t (pil_twin.c)."""
    lib = ctypes.CDLL(lib_path)
    lib.pil_twin_f_pwm_offset.restype = ctypes.c_uint32
    return lib.pil_twin_f_pwm_offset()


class Twin:
    def __init__(self, lib_path):
        lib = ctypes.CDLL(lib_path)
        lib.pil_twin_init.restype = ctypes.c_int32
        lib.pil_twin_fast.argtypes = [ctypes.c_uint16] * 3 + [ctypes.POINTER(ctypes.c_uint16)]
        lib.pil_twin_tick.argtypes = [ctypes.c_int16, ctypes.c_int16, ctypes.c_char_p, ctypes.c_uint8,
                                      ctypes.POINTER(ctypes.c_uint8)]
        lib.pil_twin_size.restype = ctypes.c_uint32
        lib.pil_twin_save.argtypes = [ctypes.c_char_p]
        lib.pil_twin_restore.argtypes = [ctypes.c_char_p]
        self.lib = lib
        self.size = lib.pil_twin_size()

    def save(self):
        b = ctypes.create_string_buffer(self.size)
        self.lib.pil_twin_save(b)
        return b.raw

    def restore(self, raw):
        self.lib.pil_twin_restore(raw)

    def init(self):
        return self.lib.pil_twin_init()

    def fast(self, iu, iv, vdc):
        o = (ctypes.c_uint16 * 4)()
        self.lib.pil_twin_fast(iu, iv, vdc, o)
        return [o[0], o[1], o[2]], bool(o[3])

    def tick(self, t_ipm, t_pcb, rx):
        o = (ctypes.c_uint8 * 32)()
        self.lib.pil_twin_tick(t_ipm, t_pcb, bytes(rx), len(rx), o)
        b = bytes(o)
        return {"tx_len": b[11], "tx": b[:b[11]], "can_id": b[12] | (b[13] << 8), "can_dlc": b[14],
                "can_data": b[15:23], "can_send": b[23], "pwm_off": b[24]}


def image_tick_out(mem):
    """qfoc_tick_out_t in the image (arm-none-eabi layout: tx[11], tx_len 11, can 12..23
    (id 12, dlc 14, data 15..22), can_send 24, pwm_off 25)."""
    n = mem[11]
    return {"tx_len": n, "tx": bytes(mem[:min(n, 11)]), "can_id": mem[12] | (mem[13] << 8),
            "can_dlc": mem[14], "can_data": bytes(mem[15:23]), "can_send": mem[24], "pwm_off": mem[25]}


class LockStep:
    """Attach to a run.PIL instance before boot."""
    def __init__(self, pil, lib_path):
        from unicorn import UC_HOOK_CODE
        from unicorn.arm_const import UC_ARM_REG_R0, UC_ARM_REG_R2, UC_ARM_REG_LR, UC_ARM_REG_SP
        self.R0, self.R2, self.LR, self.SP = UC_ARM_REG_R0, UC_ARM_REG_R2, UC_ARM_REG_LR, UC_ARM_REG_SP
        self.HOOK = UC_HOOK_CODE
        self.pil = pil
        self.core = pil.core
        self.twin = Twin(lib_path)
        self.inits = 0
        self.fast_calls = 0
        self.tick_calls = 0
        self.ticks_compared = 0
        self.periods = 0               # reload points compared
        self.divergence = None         # (period, field, image, host)
        self.compare_until = None
        self.expect = None             # ([C0V..C5V], enable) the twin implies
        self.odd = None                # odd channels as initialised
        self.pending_tick = {}         # sp -> (out address, host out)
        self.ret_hooked = set()
        self.frames_rx = 0
        syms = self.core.syms
        mu = self.core.mu
        for name, fn in (("qfoc_drive_init", self._on_init), ("qfoc_drive_fast_step", self._on_fast),
                         ("qfoc_drive_tick", self._on_tick)):
            a = syms[name] & ~1
            mu.hook_add(UC_HOOK_CODE, fn, begin=a, end=a)
        self.last_entry = {}
        self.fresh = None              # the candidates of a fast step, until its return
        self.cands = None
        self.max_cands = 1
        self.fast_ret_hooked = set()
        self.order_before = 0          # pre-empting fast steps the image ran before the tick's effect
        self.order_after = 0           # ... after it
        self.order_same = 0            # ... where both orders give the same output

    def active(self):
        return self.divergence is None and (self.compare_until is None or self.core.now() < self.compare_until)

    def _dup(self, name, sp):
        # a code hook may fire again at a restarted instruction: one call per (function, sp, time)
        key = (sp, self.core.now(), self.core.insns)
        if self.last_entry.get(name) == key:
            return True
        self.last_entry[name] = key
        return False

    # The twin's candidate states: normally one.  A fast step that pre-empts the image's
    # tick (a tick pending at its entry) is run in both orders, before the tick's effect and
    # after it, from saved copies of the state; the image's own results (each fast step's
    # qfoc_pwm_t read at its return, each tick's qfoc_tick_out_t) keep the candidates that
    # produced them.  No candidate left is a divergence.
    MAX_CANDS = 16

    def _on_init(self, mu, addr, size, data):
        if self._dup("init", mu.reg_read(self.SP)):
            return
        self.inits += 1
        self.twin.init()
        self.cands = [{"state": self.twin.save(), "applied": {}, "expect": None}]
        self.expect = None
        self.pending_tick = {}

    def _hook_ret(self, mu, fn, hooked):
        ret = mu.reg_read(self.LR) & ~1
        if ret not in hooked:
            hooked.add(ret)
            mu.hook_add(self.HOOK, fn, begin=ret, end=ret)

    def _on_fast(self, mu, addr, size, data):
        if self._dup("fast", mu.reg_read(self.SP)) or not getattr(self, "cands", None):
            return
        p = mu.reg_read(self.R2)
        iu, iv, vdc = struct.unpack("<HHH", bytes(mu.mem_read(p, 6)))
        self.fast_calls += 1
        new = []
        preempting = False
        for c in self.cands:
            self.twin.restore(c["state"])
            out = self.twin.fast(iu, iv, vdc)
            new.append({"state": self.twin.save(), "applied": dict(c["applied"]), "expect": out,
                        "order": "before"})
            for tk, (outp, inputs) in self.pending_tick.items():
                if tk in c["applied"]:
                    continue
                preempting = True
                self.twin.restore(c["state"])
                tick_out = self.twin.tick(*inputs)
                out = self.twin.fast(iu, iv, vdc)
                ap = dict(c["applied"])
                ap[tk] = tick_out
                new.append({"state": self.twin.save(), "applied": ap, "expect": out, "order": "after"})
        self.fresh = (mu.reg_read(self.R0), new, preempting)
        self._hook_ret(mu, self._on_fast_ret, self.fast_ret_hooked)

    def _on_fast_ret(self, mu, addr, size, data):
        if getattr(self, "fresh", None) is None:
            return
        resp, new, preempting = self.fresh
        self.fresh = None
        c0, c1, c2, en = struct.unpack("<HHHB", bytes(mu.mem_read(resp, 7)))
        img = ([c0, c1, c2], bool(en))
        keep = [c for c in new if c["expect"] == img]
        if preempting:
            orders = {c["order"] for c in keep}
            if orders == {"before"}:
                self.order_before += 1
            elif orders == {"after"}:
                self.order_after += 1
            elif orders:
                self.order_same += 1
        if not keep:
            if self.active():
                self._diverge("fast step %d result%s" % (self.fast_calls, " (pre-empting a tick, either order)"
                                                         if preempting else ""), img, new[0]["expect"])
            keep = new[:1]
        self.cands = self._merge(keep)
        self.expect = self.cands[0]["expect"]

    def _merge(self, cands):
        out, seen = [], set()
        for c in cands:
            key = (c["state"], tuple(sorted(c["applied"])))
            if key not in seen:
                seen.add(key)
                out.append(c)
        self.max_cands = max(getattr(self, "max_cands", 1), len(out))
        return out[:self.MAX_CANDS]

    def _on_tick(self, mu, addr, size, data):
        sp = mu.reg_read(self.SP)
        if self._dup("tick", sp):
            return
        outp = mu.reg_read(self.R0)
        p = mu.reg_read(self.R2)
        t_ipm, t_pcb, rxp, n = struct.unpack("<hhIB", bytes(mu.mem_read(p, 9)))
        rx = bytes(mu.mem_read(rxp, n)) if n else b""
        self.frames_rx += 1 if n else 0
        self.tick_calls += 1
        self._hook_ret(mu, self._on_tick_ret, self.ret_hooked)
        self.pending_tick[sp] = (outp, (t_ipm, t_pcb, rx))

    def _on_tick_ret(self, mu, addr, size, data):
        sp = mu.reg_read(self.SP)
        item = self.pending_tick.pop(sp, None)
        if item is None or not getattr(self, "cands", None):
            return
        outp, inputs = item
        img = image_tick_out(bytes(mu.mem_read(outp, 26)))
        keep, first_bad = [], None
        for c in self.cands:
            if sp in c["applied"]:
                host = c["applied"].pop(sp)
                state = c["state"]
            else:
                self.twin.restore(c["state"])
                host = self.twin.tick(*inputs)
                state = self.twin.save()
            bad = self._tick_diff(img, host)
            c2 = {"state": state, "applied": c["applied"],
                  "expect": ([0, 0, 0], False) if host["pwm_off"] else c["expect"]}
            if bad is None:
                keep.append(c2)
            elif first_bad is None:
                first_bad = bad + (c2,)
        if self.active():
            self.ticks_compared += 1
        if not keep:
            if self.active():
                f, a, b, _ = first_bad
                self._diverge("tick %d: %s" % (self.tick_calls, f), a, b)
            keep = [first_bad[3]]
        self.cands = self._merge(keep)
        self.expect = self.cands[0]["expect"]

    @staticmethod
    def _tick_diff(img, host):
        for f in ("tx_len", "tx", "can_send", "pwm_off"):
            if img[f] != host[f]:
                return (f, img[f], host[f])
        if host["can_send"]:
            for f in ("can_id", "can_dlc", "can_data"):
                if img[f] != host[f]:
                    return (f, img[f], host[f])
        return None

    def _diverge(self, field, img, host):
        fmt = lambda v: v.hex() if isinstance(v, bytes) else v  # noqa: E731
        self.divergence = (self.periods, field, fmt(img), fmt(host), self.core.now())

    def on_reload(self, ftm, fault_latched=False):
        """At an FTM3 reload point, after the buffers loaded."""
        if self.expect is None:
            return
        if self.odd is None:
            self.odd = [ftm.r["C%dV" % (2 * k + 1)] for k in range(3)]
        if not self.active():
            return
        self.periods += 1
        cmp_, en = self.expect
        mod = ftm.r["MOD"]
        for k in range(3):
            want = min(cmp_[k], mod)
            if ftm.r["C%dV" % (2 * k)] != want:
                self._diverge("C%dV" % (2 * k), ftm.r["C%dV" % (2 * k)], want)
                return
            if ftm.r["C%dV" % (2 * k + 1)] != self.odd[k]:
                self._diverge("C%dV" % (2 * k + 1), ftm.r["C%dV" % (2 * k + 1)], self.odd[k])
                return
        img_en = (ftm.r["OUTMASK"] & 0x3F) == 0
        if img_en != (en and not fault_latched):
            self._diverge("enable (OUTMASK = 0)", img_en, en)

    def report(self):
        s = ("lock-step with the host build: %d PWM periods compared (C0V..C5V, enable), %d ticks "
             "compared (LIN tx, CAN frame, pwm_off); calls: fast step %d, tick %d (%d with a received "
             "frame), drive inits %d; fast steps pre-empting a tick: %d saw the tick's effect, %d did not, %d "
             "either" % (self.periods, self.ticks_compared, self.fast_calls, self.tick_calls,
                         self.frames_rx, self.inits, self.order_after, self.order_before, self.order_same))
        if self.divergence:
            p, f, a, b, t = self.divergence
            s += "\nlock-step FIRST DIVERGENCE at period %d (%.3f ms): %s image %s host %s" % (
                p, t / 80000.0, f, a, b)
        return s
