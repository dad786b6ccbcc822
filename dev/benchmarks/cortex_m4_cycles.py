#!/usr/bin/env python3
"""Cycles per call of a function on a Cortex-M4 (with FPU), estimated from
the instructions the function really executes: qemu-system-arm runs the
firmware one instruction per translation block and logs every executed
address (-singlestep -d exec,nochain); each address is looked up in the
firmware's disassembly and charged the cycles the Cortex-M4 Technical
Reference Manual gives for it (r0p1: section 3.3.1 for the integer core,
Table 7-1 for the FPU; zero-wait-state memory).

qemu models no pipeline, so what the manual leaves to the pipeline is given
as a range rather than guessed: taken branches cost 1 + P with P = 1 (low)
to 3 (high) for the refill; a single load or store right after another
pipelines to 1 cycle (low) or takes its full 2 (high); IT folds to 0 (low)
or 1 (high); SDIV/UDIV 2 (low) to 12 (high). Stalls for using an FPU result
the next cycle are not modelled (the manual gives issue cycles).

usage: cortex_m4_cycles.py ELF BOARD FUNCTION CALLER [--first K] [--calls M] [--top N]
  Runs ELF on qemu-system-arm -M BOARD with semihosting and prints, per call
  of FUNCTION from CALLER: instructions, and cycles low..high; only calls
  K..K+M-1 (counted from 0) with --first/--calls; --top N also lists the N
  instruction kinds that cost the most cycles."""
import collections
import os
import re
import subprocess
import sys
import tempfile

# (low, high) cycles per instruction kind, before the branch and pipelining rules below.
ONE = (1, 1)
FPU = {"vdiv": (14, 14), "vsqrt": (14, 14), "vmla": (3, 3), "vmls": (3, 3), "vnmla": (3, 3), "vnmls": (3, 3),
       "vfma": (3, 3), "vfms": (3, 3), "vfnma": (3, 3), "vfnms": (3, 3)}
SINGLE_LOADS_STORES = re.compile(r"^(ldr|str)(b|h|sb|sh|ex|exb|exh)?(\.w|\.n)?$")


def disassembly(elf):
    """address -> (mnemonic, operands, size in bytes) for every instruction in ELF's code."""
    out = subprocess.run(["arm-none-eabi-objdump", "-d", "--no-show-raw-insn", elf], capture_output=True, text=True,
                         check=True).stdout
    rows = []
    for line in out.splitlines():
        m = re.match(r"^\s+([0-9a-f]+):\t(\S+)\s*(.*)$", line)
        if m and not m.group(2).startswith("."):
            rows.append((int(m.group(1), 16), m.group(2), m.group(3)))
    table = {}
    for (address, mnemonic, operands), following in zip(rows, rows[1:] + [(None, None, None)]):
        size = following[0] - address if following[0] is not None and following[0] - address in (2, 4) else 4
        table[address] = (mnemonic, operands, size)
    return table


def function_ranges(elf):
    out = subprocess.run(["arm-none-eabi-nm", "-S", elf], capture_output=True, text=True, check=True).stdout
    ranges = {}
    for line in out.splitlines():
        fields = line.split()
        if len(fields) == 4 and fields[2].lower() == "t":
            start = int(fields[0], 16) & ~1
            ranges[fields[3]] = (start, start + int(fields[1], 16))
            ranges.setdefault(fields[3].split(".")[0], ranges[fields[3]])  # GCC's clones: f.constprop.0
    return ranges


def base_cost(mnemonic, operands):
    """(low, high) cycles of one instruction, not counting a taken branch's refill."""
    m = mnemonic.split(".")[0]
    core = re.sub(r"(eq|ne|cs|cc|hs|lo|mi|pl|vs|vc|hi|ls|ge|lt|gt|le|al)$", "", m) if len(m) > 3 else m
    if m.startswith("v"):
        for name, cost in FPU.items():
            if m.startswith(name):
                return cost
        if m.startswith(("vpush", "vpop", "vldm", "vstm")):
            registers = re.findall(r"([sd])(\d+)(?:-[sd](\d+))?", operands)
            words = sum((int(hi or lo) - int(lo) + 1) * (2 if kind == "d" else 1) for kind, lo, hi in registers)
            return (1 + words, 1 + words)
        if m.startswith(("vldr", "vstr")):
            return (3, 3) if re.match(r"d\d", operands) else (2, 2)
        if m.startswith("vmov") and operands.count(",") == 2:  # two core registers <-> a double
            return (2, 2)
        return ONE
    if core in ("push", "pop", "ldm", "ldmia", "ldmfd", "stm", "stmia", "stmdb", "stmfd"):
        words = 0
        for lo, hi in re.findall(r"r(\d+)(?:-r(\d+))?", operands):
            words += int(hi or lo) - int(lo) + 1
        words += len(re.findall(r"\b(lr|pc|sp|ip|fp|sl|sb)\b", operands))
        return (1 + words, 1 + words)
    if core in ("ldrd", "strd"):
        return (3, 3)
    if core in ("sdiv", "udiv"):
        return (2, 12)
    if core in ("mla", "mls"):
        return (2, 2)
    if core == "it" or core.startswith("it"):
        return (0, 1)
    if SINGLE_LOADS_STORES.match(m) or SINGLE_LOADS_STORES.match(core):
        return (2, 2)
    return ONE


def trace(elf, board):
    """Executed addresses, in order, of one run of ELF on qemu."""
    with tempfile.TemporaryDirectory() as work:
        log = os.path.join(work, "exec.log")
        subprocess.run(["qemu-system-arm", "-M", board, "-nographic", "-monitor", "none", "-serial", "none",
                        "-semihosting-config", "enable=on,target=native", "-singlestep", "-d", "exec,nochain",
                        "-D", log, "-kernel", elf], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                       timeout=600, check=False)
        pattern = re.compile(r"\[[0-9a-f]+/([0-9a-f]+)/")
        with open(log) as lines:
            return [int(m.group(1), 16) for m in map(pattern.search, lines) if m]


def cycles_per_call(elf, board, function, caller, first=0, count=None):
    code = disassembly(elf)
    ranges = function_ranges(elf)
    entry, (caller_start, caller_end) = ranges[function][0], ranges[caller]
    addresses = trace(elf, board)
    calls, seen, instructions, low, high = 0, 0, 0, 0, 0
    kinds = collections.Counter()
    inside, counted, previous_single_memory = False, False, False
    for pc, following in zip(addresses, addresses[1:] + [None]):
        if pc == entry and not inside:
            inside, seen = True, seen + 1
            counted = seen > first and (count is None or seen <= first + count)
            calls += counted
        elif inside and caller_start <= pc < caller_end:
            inside = False
        if not inside or not counted:
            continue
        mnemonic, operands, size = code.get(pc, ("?", "", 2))
        lo, hi = base_cost(mnemonic, operands)
        single_memory = bool(SINGLE_LOADS_STORES.match(mnemonic.split(".")[0])) or mnemonic.startswith(("vldr", "vstr"))
        if single_memory and previous_single_memory:
            lo -= 1  # address and data phases of neighbouring loads and stores overlap
        previous_single_memory = single_memory
        if following is not None and following != pc + size and not mnemonic.startswith("bkpt"):
            lo, hi = lo + 1, hi + 3  # a taken branch (or a write to pc): pipeline refill P = 1..3
        instructions += 1
        low += lo
        high += hi
        kinds[re.sub(r"\.(f32|f64|w|n|s32\.f32|f32\.s32)$", "", mnemonic)] += hi
    if calls == 0:
        raise SystemExit(f"cortex_m4_cycles: {function} was never called from {caller}")
    return calls, instructions / calls, low / calls, high / calls, {k: v / calls for k, v in kinds.items()}


def main():
    options, args, rest = {}, [], sys.argv[1:]
    while rest:
        word = rest.pop(0)
        if word in ("--first", "--calls", "--top") and rest and rest[0].isdigit():
            options[word] = int(rest.pop(0))
        elif word.startswith("-"):
            print(__doc__)
            sys.exit(0 if word in ("-h", "--help") else 2)
        else:
            args.append(word)
    if len(args) != 4:
        print(__doc__)
        sys.exit(2)
    top = options.get("--top", 0)
    if not os.path.isfile(args[0]):
        sys.exit(f"cortex_m4_cycles: no firmware {args[0]}")
    calls, instructions, low, high, kinds = cycles_per_call(*args, options.get("--first", 0), options.get("--calls"))
    print(f"{args[2]}: {calls} calls, {instructions:.1f} instructions, {low:.1f}..{high:.1f} cycles per call "
          f"(Cortex-M4 TRM timings)")
    for kind, cycles in sorted(kinds.items(), key=lambda kv: -kv[1])[:top]:
        print(f"  {kind:10s} {cycles:7.1f} cycles (high)")


if __name__ == "__main__":
    main()
