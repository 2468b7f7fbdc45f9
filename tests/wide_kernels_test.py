#!/usr/bin/python3
"""The AVX2 build of the kernels (reference_cpu/wide.h) stays inside lpir::RunAvx2: in the
disassembly of lpir-gseg every function with an AVX instruction (VEX-encoded: a ymm register, or
an instruction named v... on xmm registers) is an instantiation of lpir::RunAvx2, and there is at
least one. An AVX instruction anywhere else would run on CPUs without AVX2 and stop the program
there (SIGILL): an inline function or template compiled inside the AVX2 build and shared, by the
linker's choice of one copy, with the baseline code. Exits 77 (skipped) off x86-64.

usage: wide_kernels_test.py LPIR_GSEG"""
import platform
import re
import subprocess
import sys

FUNCTION = re.compile(r"^[0-9a-f]+ <(.*)>:$")
AVX = re.compile(r"%ymm|\tv[a-z0-9]+\s.*%xmm")


def avx_functions(binary):
    """Names of the functions of `binary` (objdump -d, demangled) with an AVX instruction."""
    out = subprocess.run(["objdump", "-d", "--no-show-raw-insn", "-C", binary],
                         check=True, capture_output=True, text=True).stdout
    found, name = set(), None
    for line in out.splitlines():
        m = FUNCTION.match(line)
        if m:
            name = m.group(1)
        elif name is not None and AVX.search(line):
            found.add(name)
    return found


def main():
    if platform.machine() != "x86_64":
        print("not x86-64: one build of the kernels, nothing to check")
        return 77
    found = avx_functions(sys.argv[1])
    outside = sorted(f for f in found if not f.startswith("void lpir::RunAvx2<"))
    for f in outside:
        print("AVX code outside lpir::RunAvx2: " + f)
    inside = len(found) - len(outside)
    print(f"{inside} RunAvx2 functions with AVX code, {len(outside)} other functions with AVX code")
    return 1 if outside or inside == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
