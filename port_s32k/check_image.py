#!/usr/bin/env python3
"""check_image.py -- build-time check of an S32K144 binary image (port_s32k).

Usage: check_image.py IMAGE.bin

The flash configuration field at 0x400..0x40F is read by the chip at every reset
(S32K1xx Reference Manual Rev. 13, "Flash configuration field"); FSEC at 0x40C decides
whether the part is secured.  A wrong value can lock a real part for good, so the
image is refused unless the 16 bytes are exactly:

    0x400..0x407  backdoor comparison key   FF FF FF FF FF FF FF FF
    0x408..0x40B  FPROT3..FPROT0            FF FF FF FF  (no program-flash protection)
    0x40C         FSEC                      FE  (SEC = 10 unsecured, KEYEN = 11 disabled)
    0x40D         FOPT                      7F
    0x40E         FEPROT                    FF
    0x40F         FDPROT                    FF

It also checks the first two vector-table words: the initial stack pointer lies in
SRAM (0x1FFF8000 .. 0x20007000, 8-byte aligned) and the reset vector is a Thumb address
(odd) inside the 512 KiB program flash, above the flash configuration field.
Exit status 0 when the image passes, 1 otherwise (with the reason).
"""
import struct
import sys

EXPECTED = bytes([0xFF] * 8 + [0xFF] * 4 + [0xFE, 0x7F, 0xFF, 0xFF])
FLASH_SIZE = 0x80000
SRAM_START = 0x1FFF8000
SRAM_END = 0x20007000


def check(path):
    with open(path, "rb") as f:
        image = f.read()
    if len(image) < 0x410:
        return "image shorter than 0x410 bytes: no flash configuration field"
    if len(image) > FLASH_SIZE:
        return "image larger than the 512 KiB program flash"
    field = image[0x400:0x410]
    if field[0x0C] != 0xFE:
        return "FSEC at 0x40C is 0x%02X, not 0xFE: the part would be secured" % field[0x0C]
    if field != EXPECTED:
        return "flash configuration field is %s, expected %s" % (field.hex(" "), EXPECTED.hex(" "))
    sp, reset = struct.unpack_from("<II", image, 0)
    if not (SRAM_START < sp <= SRAM_END) or (sp % 8) != 0:
        return "initial stack pointer 0x%08X outside SRAM or not 8-byte aligned" % sp
    if (reset & 1) == 0 or not (0x410 <= (reset & ~1) < FLASH_SIZE):
        return "reset vector 0x%08X is not a Thumb address in program flash" % reset
    return None


def main(argv):
    if len(argv) != 2:
        print(__doc__.strip().splitlines()[2])
        return 2
    err = check(argv[1])
    if err is not None:
        print("check_image: %s: %s" % (argv[1], err))
        return 1
    print("check_image: %s: flash configuration field FF x12 FE 7F FF FF (FSEC 0xFE, unsecured), "
          "vectors ok" % argv[1])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
