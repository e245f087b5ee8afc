"""plant.py -- the simulated motor of sim/ (sim/plant.c, sim/motor.c through the shim
pil_plant.c) as a shared library called with ctypes: a period at a time, sampled at the
period's start (sample) or at an instant inside it (sample_at), with the inverter's dead
time from the FTM3 registers (set_dead_time).

Requirements: REQ-PIL-007, REQ-PIL-009 (specs/requirements/pil.md).

build() compiles it with `gcc -O2 -shared -fPIC` (mk/pil.mk does the same) when the
library is missing or older than its sources.
"""
import ctypes
import os
import subprocess

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
SOURCES = [os.path.join(HERE, "pil_plant.c"), os.path.join(ROOT, "sim", "plant.c"),
           os.path.join(ROOT, "sim", "motor.c")]


def build(out):
    if os.path.exists(out) and all(os.path.getmtime(out) >= os.path.getmtime(s)
                                   for s in SOURCES + [os.path.join(ROOT, "sim", "sim.h")]):
        return out
    os.makedirs(os.path.dirname(out), exist_ok=True)
    subprocess.check_call(["gcc", "-O2", "-shared", "-fPIC", "-I" + os.path.join(ROOT, "sim")]
                          + SOURCES + ["-lm", "-o", out])
    return out


class Plant:
    def __init__(self, lib_path, motor_file, vdc_v, substeps=20):
        lib = ctypes.CDLL(lib_path)
        lib.pil_plant_new.restype = ctypes.c_void_p
        lib.pil_plant_new.argtypes = [ctypes.c_char_p, ctypes.c_double, ctypes.c_int]
        lib.pil_plant_step.argtypes = [ctypes.c_void_p, ctypes.c_uint, ctypes.c_uint,
                                       ctypes.c_uint, ctypes.c_int]
        lib.pil_plant_sample.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_uint)]
        lib.pil_plant_state.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_double)]
        lib.pil_plant_period.argtypes = [ctypes.c_void_p]
        lib.pil_plant_free.argtypes = [ctypes.c_void_p]
        lib.pil_plant_set_dead_time.argtypes = [ctypes.c_void_p, ctypes.c_double]
        lib.pil_plant_sample_at.argtypes = [ctypes.c_void_p, ctypes.c_double,
                                            ctypes.POINTER(ctypes.c_uint)]
        self.lib = lib
        self.p = lib.pil_plant_new(motor_file.encode(), vdc_v, substeps)
        if not self.p:
            raise RuntimeError("pil_plant_new: cannot load %s" % motor_file)
        self.period = lib.pil_plant_period(self.p)
        self.steps = 0
        self.dead_time_s = None       # None: the motor file's, until set from the registers

    def step(self, cmp3, enable):
        self.lib.pil_plant_step(self.p, cmp3[0], cmp3[1], cmp3[2], 1 if enable else 0)
        self.steps += 1

    def set_dead_time(self, td_s):
        """The inverter's dead time from now on (the FTM3 registers'), s."""
        self.lib.pil_plant_set_dead_time(self.p, td_s)
        self.dead_time_s = td_s

    def sample(self):
        out = (ctypes.c_uint * 3)()
        self.lib.pil_plant_sample(self.p, out)
        return list(out)

    def sample_at(self, tau_s):
        """The ADC codes tau_s after the start of the current period (sim_sample_at), the
        plant unchanged."""
        out = (ctypes.c_uint * 3)()
        self.lib.pil_plant_sample_at(self.p, tau_s, out)
        return list(out)

    def state(self):
        out = (ctypes.c_double * 6)()
        self.lib.pil_plant_state(self.p, out)
        return {"t": out[0], "w_e": out[1], "theta_e": out[2], "id": out[3], "iq": out[4],
                "enabled": bool(out[5])}

    def __del__(self):
        try:
            self.lib.pil_plant_free(self.p)
        except Exception:
            pass
