"""What NVIDIA's driver compiled each stage of a ray tracing pipeline into, read from the
pipeline cache twinray writes (`--pipeline-cache DIR`: one `*.pipelines` file per device).

The driver's cache data is undocumented. On driver 580 (H200) it holds zstd frames, each
holding a cubin (an ELF for the GPU) with one `.text._rtx_<KIND>_...` section per stage
function, a ray generation split at its traces (`_ss_0`, `_ss_1`, ...). From each cubin this
prints the function's kind, its size in instructions (16 bytes each on sm_90, padding
included) and its registers (the `.nv.info` attribute EIATTR_REGCOUNT). With
`--sass DIR` it also writes each cubin's disassembly there (`nvdisasm`, from PyPI's
`nvidia-cuda-nvdisasm`) and prints each function's count of every opcode.
    python3 bench/sass.py FILE_OR_DIR... [--sass DIR --nvdisasm PATH]
Needs the `zstd` program (Debian's zstd)."""
import argparse
import collections
import os
import re
import struct
import subprocess

ZSTD_MAGIC = b"\x28\xb5\x2f\xfd"
REGCOUNT = 0x2F


def cubins(data):
    """Every cubin in the cache data: each zstd frame decompressed, from its ELF header on."""
    start = data.find(ZSTD_MAGIC)
    while start >= 0:
        out = subprocess.run(["zstd", "-d", "-c"], input=data[start:], capture_output=True).stdout
        elf = out.find(b"\x7fELF")
        if elf >= 0:
            yield out[elf:]
        start = data.find(ZSTD_MAGIC, start + 1)


def sections(elf):
    """(name, offset, size, info) of every section."""
    shoff = struct.unpack_from("<Q", elf, 0x28)[0]
    entsize, count, names = struct.unpack_from("<HHH", elf, 0x3A)
    raw = [struct.unpack_from("<IIQQQQIIQQ", elf, shoff + k * entsize) for k in range(count)]
    table = raw[names][4]
    for name, _, _, _, offset, size, _, info, _, _ in raw:
        end = elf.index(b"\0", table + name)
        yield elf[table + name : end].decode(), offset, size, info


def attributes(elf, secs):
    """{(attribute, symbol index): value} of the cubin's `.nv.info` sections."""
    found = {}
    for name, offset, size, _ in secs:
        if not name.startswith(".nv.info"):
            continue
        at = offset
        while at + 4 <= offset + size:
            fmt, attr, length = struct.unpack_from("<BBH", elf, at)
            if fmt == 0x04 and length == 8 and attr == REGCOUNT:
                symbol, value = struct.unpack_from("<II", elf, at + 4)
                found[(attr, symbol)] = value
            at += 4 + (length if fmt == 0x04 else 0)
    return found


def functions(elf):
    """(kind, instructions, registers) of every stage function in a cubin."""
    secs = list(sections(elf))
    attrs = attributes(elf, secs)
    for name, _, size, info in secs:
        if name.startswith(".text._rtx_"):
            # A text section's info holds its symbol's index in the low 24 bits.
            symbol = info & 0xFFFFFF
            kind = re.sub(r"_\d+___id\d+_\d+_[0-9a-f]{16}|_\d+_main_\d+_[0-9a-f]{16}", "", name[len(".text._rtx_") :])
            # The info's top byte holds the registers too: the fallback where no attribute says.
            yield kind, size // 16, attrs.get((REGCOUNT, symbol), info >> 24)


def opcodes(sass):
    """{function: Counter of opcodes} from nvdisasm's output."""
    counts, current = {}, None
    for line in sass.splitlines():
        if line.startswith(".text._rtx_"):
            current = counts.setdefault(line.rstrip(":")[len(".text._rtx_") :], collections.Counter())
        elif line.startswith("//-----"):
            current = None
        elif current is not None:
            m = re.match(r"\s+/\*[0-9a-f]{4}\*/\s+(?:@!?U?P[0-9T]\s+)?([A-Z][A-Z0-9_]*)", line)
            if m:
                current[m.group(1)] += 1
    return counts


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("paths", nargs="+")
    parser.add_argument("--sass", help="folder for each cubin's disassembly")
    parser.add_argument("--nvdisasm", default="nvdisasm")
    args = parser.parse_args()
    for path in args.paths:
        files = [os.path.join(path, f) for f in sorted(os.listdir(path))] if os.path.isdir(path) else [path]
        for file in files:
            for n, elf in enumerate(cubins(open(file, "rb").read())):
                for kind, instructions, registers in functions(elf):
                    print(f"{path:28} {kind:18} {instructions:5} instructions {registers:4} registers")
                if args.sass:
                    os.makedirs(args.sass, exist_ok=True)
                    cubin = os.path.join(args.sass, f"{os.path.basename(path.rstrip('/'))}-{n}.cubin")
                    open(cubin, "wb").write(elf)
                    sass = subprocess.run([args.nvdisasm, cubin], capture_output=True, text=True).stdout
                    open(cubin[:-6] + ".sass", "w").write(sass)
                    for function, counts in opcodes(sass).items():
                        print("   ", function[:40], " ".join(f"{op}:{c}" for op, c in sorted(counts.items())))


if __name__ == "__main__":
    main()
