"""Processor-in-the-loop run of the S32K144 image (port_s32k/pil/README.md)."""
