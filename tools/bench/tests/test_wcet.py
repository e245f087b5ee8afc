"""Tests of tools/bench/wcet.py, the static worst-case bound of the bench (run by make bench,
or python3 -m pytest tools/bench/tests).

Small functions are compiled with arm-none-eabi-gcc for the Cortex-M4 and linked at a fixed
address; each bound is checked against references that share no code with the tool: the
instructions `arm-none-eabi-objdump` lists for a function without branches, and the
instructions Unicorn executes from the function's entry to its return over inputs that take
every branch (REQ-BENCH-008).  What the tool cannot bound (a loop without a bound, a call
through a register, recursion) must be refused, not counted short.
"""
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

import wcet  # noqa: E402

ARM_CC = "arm-none-eabi-gcc"
FLAGS = ["-mcpu=cortex-m4", "-mthumb", "-mfloat-abi=hard", "-mfpu=fpv4-sp-d16", "-O2",
         "-ffreestanding", "-nostdlib", "-Wl,-e,0", "-Wl,-Ttext=0x1000", "-Wl,--no-warnings"]
TEXT = 0x1000

SRC = r"""
#include <stdint.h>
int32_t straight(int32_t a, int32_t b) { return (a * b) + (a >> 3) - b; }
__attribute__((noinline)) int32_t leaf(int32_t x) { return (x * 7) + 1; }
int32_t branches(int32_t x, int32_t y)
{
    int32_t r = 0;
    if (x > 100) { r = leaf(x) + leaf(y); }
    else if (x < -100) { r = (x / (y | 1)) - 5; }
    else { r = x + y; }
    if (y == 3) { r += leaf(r); }
    return r;
}
__attribute__((noinline)) int32_t loop4(const volatile int32_t *p)
{
    int32_t s = 0;
    for (int32_t i = 0; i < 4; i++) { s += p[i] * (i + 1); }
    return s;
}
int32_t unbounded(int32_t n) { int32_t s = 0; while (n > 0) { s += n; n -= 3; } return s; }
int32_t (*volatile hook)(int32_t);
int32_t indirect(int32_t x) { return hook(x) + 1; }
__attribute__((noinline)) int32_t rec(int32_t n) { return (n <= 0) ? 0 : (n + rec(n - 1) * 3); }
"""


@pytest.fixture(scope="module")
def elf(tmp_path_factory):
    if shutil.which(ARM_CC) is None:
        pytest.fail(f"{ARM_CC} not found: run make deps")
    d = tmp_path_factory.mktemp("wcet")
    (d / "t.c").write_text(SRC)
    out = d / "t.elf"
    subprocess.run([ARM_CC, *FLAGS, str(d / "t.c"), "-o", str(out)], check=True)
    return out


def objdump_count(elf_path, name):
    """Instructions objdump lists in the function."""
    text = subprocess.run(["arm-none-eabi-objdump", "-d", f"--disassemble={name}", str(elf_path)],
                          check=True, capture_output=True, text=True).stdout
    body = text.split(f"<{name}>:", 1)[1]
    return sum(1 for ln in body.splitlines() if ln.strip() and ":\t" in ln)


def executed(elf_path, name, args, mem=None):
    """Instructions Unicorn executes from the entry of the function to its return."""
    from elftools.elf.elffile import ELFFile
    from unicorn import UC_ARCH_ARM, UC_HOOK_CODE, UC_MODE_MCLASS, UC_MODE_THUMB, Uc
    from unicorn import arm_const as A
    img = wcet.Image(str(elf_path))
    uc = Uc(UC_ARCH_ARM, UC_MODE_THUMB | UC_MODE_MCLASS)
    uc.mem_map(0, 0x100000)
    uc.mem_map(0x20000000, 0x10000)
    with open(elf_path, "rb") as fh:
        for seg in ELFFile(fh).iter_segments():
            if seg["p_type"] == "PT_LOAD" and seg["p_filesz"]:
                uc.mem_write(seg["p_paddr"], seg.data())
    halt = 0xFFF00
    uc.mem_write(halt, b"\xfe\xe7")                   # b .
    for addr, data in (mem or {}).items():
        uc.mem_write(addr, data)
    count = [0]

    def hook(_uc, address, _size, _data):
        if address != halt:
            count[0] += 1
    uc.hook_add(UC_HOOK_CODE, hook)
    for reg, v in zip((A.UC_ARM_REG_R0, A.UC_ARM_REG_R1, A.UC_ARM_REG_R2), args):
        uc.reg_write(reg, v & 0xFFFFFFFF)
    uc.reg_write(A.UC_ARM_REG_SP, 0x20008000)
    uc.reg_write(A.UC_ARM_REG_LR, halt | 1)
    start, _ = img.funcs[name]
    uc.emu_start(start | 1, halt, count=100000)
    return count[0]


def bound(elf_path, name, metric="instructions"):
    return wcet.Analysis(wcet.Image(str(elf_path)), metric).of(name)


# Methods: 1n the bound against the instructions objdump lists and Unicorn executes in a
# function without branches, and its cycle bound at least its instructions (REQ-BENCH-008)
def test_straight_line_equals_its_instructions(elf):
    n = objdump_count(elf, "straight")
    assert bound(elf, "straight") == n
    assert executed(elf, "straight", [1234, -77]) == n
    assert bound(elf, "straight", "cycles") >= n


# Methods: 1b inputs that take every branch of a function with calls; 1n the bound at or
# above every count Unicorn executes, within what an IT block may skip (REQ-BENCH-008)
def test_branches_and_calls_bound_every_input(elf):
    b = bound(elf, "branches")
    counts = [executed(elf, "branches", [x, y])
              for x in (-1000, -101, -100, 0, 100, 101, 1000)
              for y in (-7, 0, 3, 4, 99)]
    assert max(counts) <= b
    assert b - max(counts) <= 8, (b, max(counts))
    assert bound(elf, "leaf") == objdump_count(elf, "leaf")


# Methods: 1c a loop bound equal to the loop's count and one below it, and no bound at all
# (REQ-BENCH-008)
def test_loop_bounds(elf, monkeypatch):
    mem = {0x20000100: b"".join(v.to_bytes(4, "little", signed=True) for v in (5, -6, 7, -8))}
    n = executed(elf, "loop4", [0x20000100], mem)
    with pytest.raises(wcet.Refused, match="LOOP_BOUNDS"):
        bound(elf, "loop4")
    monkeypatch.setitem(wcet.LOOP_BOUNDS, "loop4", (4, "the test's loop of 4 iterations"))
    assert bound(elf, "loop4") >= n
    monkeypatch.setitem(wcet.LOOP_BOUNDS, "loop4", (0, "a bound below the loop's count"))
    assert bound(elf, "loop4") < n        # the bound is only as good as LOOP_BOUNDS


# Methods: 1d the constructs the tool cannot bound (a loop whose count depends on an input, a
# call through a register, recursion) refused with the reason (REQ-BENCH-008)
def test_refused(elf):
    with pytest.raises(wcet.Refused, match="LOOP_BOUNDS"):
        bound(elf, "unbounded")
    with pytest.raises(wcet.Refused, match="register"):
        bound(elf, "indirect")
    with pytest.raises(wcet.Refused, match="recursion|LOOP_BOUNDS"):
        bound(elf, "rec")
    assert wcet.main(["--elf", str(elf), "--function", "unbounded"]) == 1
    assert wcet.main(["--elf", str(elf), "--function", "straight"]) == 0


# Methods: 1a every entry point of the library's bench image bounded, a caller's bound at
# least each callee's (REQ-BENCH-008)
def test_library_image_bounded():
    img = HERE.parents[2] / "build" / "bench" / "bench.elf"
    if not img.exists():
        pytest.skip("build/bench/bench.elf not built (make bench builds it first)")
    an = wcet.Analysis(wcet.Image(str(img)))
    fast = an.of("qfoc_drive_fast_step")
    for callee, b in an.path["qfoc_drive_fast_step"]:
        assert b <= fast
    assert an.of("qfoc_drive_tick") > 0 and an.of("qfoc_drive_init") > 0
