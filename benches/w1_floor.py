"""W1's floor on this machine: its instruction mix, counted, run without dependencies.

Issue 27 asks for a floor for W1 "established by a counted-operation model checked against a
measured throughput of the kernel's instruction mix". This script does both halves:

1. **Counted.** It runs ``profile_w1`` (one block: 16 cases at avx512, 8 at avx2) under gdb,
   stops at the plant's period of one control period (the 50th, in steady state) and
   single-steps one whole period of the block, plant, integrator and law, to the next: every
   instruction executed is counted by mnemonic, operand width and whether it touches memory.
   (A sampling profile cannot count instructions; callgrind can, but only up to AVX2. At
   ``avx2`` this count agrees with callgrind's.)
2. **Run without dependencies.** It writes a loop of the same instructions, as many of each, in
   which no instruction waits for another (destinations rotate over 20 vector and 7 mask
   registers, divisions and square roots write 4 registers nothing reads, sources are fixed,
   memory operands hit a 4 kB buffer), compiles it with gcc, and
   times it. The loop's time is what this processor needs to issue and execute W1's
   instructions when nothing but their number and kind limits it: the floor of this code. Its
   distance from W1's measured time is what dependencies (latency chains), the front end and
   the real memory traffic cost.

The clock is measured alongside (a chain of dependent register additions, one cycle each), so
that both times are also given in cycles per block-period.

    cargo build --release -p landing_core --example profile_w1
    python benches/w1_floor.py --level avx512 --rounds 10

W3 and W5 (the small-body workloads, blocks of the same size) are counted and run the same
way from ``profile_small_body``, and W6 (the tethered satellite: blocks of 8 cases at every
level, one control period of six RK4 substeps) from ``profile_w6``:

    cargo build --release -p landing_core --example profile_small_body --example profile_w6
    python benches/w1_floor.py --workload W3 --profile target/release/examples/profile_small_body
    python benches/w1_floor.py --workload W6 --profile target/release/examples/profile_w6

``--kinds`` also times the loop with each kind of instruction alone and without it. Read it with
care: the loop's order changes with its content, and on Intel a loop without a kind sometimes
ran longer than the whole (its front end moves with its layout; BENCHMARKS.md, "The Intel
machine again").

``--json FILE`` also writes the counts per case-step, the clock, W1's time, the floors and W1 /
floor (``targets.py --floor`` reads them).

Needs gdb and gcc. Linux, x86-64 only. See BENCHMARKS.md, "W1's floor".
"""

from __future__ import annotations

import argparse
import collections
import json
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from _harness import WIDE_LANES, json_option, write_json

ROOT = Path(__file__).resolve().parents[1]
PROFILE = ROOT / "target" / "release" / "examples" / "profile_w1"


def prefix(workload: str) -> list[str]:
    """The profile binary's leading arguments: ``profile_w1`` and ``profile_w6`` take none, the
    small-body workloads' ``profile_small_body`` the workload's name."""
    return [] if workload in ("W1", "W6") else [workload]


def lanes(workload: str, level: str) -> int:
    """The cases of one block: the three-axis plants' wide blocks, or the tether's 8 at every
    level (``Wide`` and ``Narrow`` in ``kernel.rs``)."""
    return 8 if workload == "W6" else WIDE_LANES[level]


GDB_SCRIPT = r"""
import gdb, collections, json, os
cands = [int(a, 16) for a in os.environ['CANDS'].split(',')]
gdb.execute('set pagination off')
gdb.execute('set confirm off')
gdb.execute('starti ' + os.environ['ARGS'] + ' > /dev/null')
base = int(gdb.execute('info proc mappings', to_string=True).split('0x', 2)[1].split()[0], 16)
for a in cands:
    gdb.execute('break *' + hex(base + a), to_string=True)
for _ in range(50):
    gdb.execute('continue', to_string=True)
start = int(gdb.parse_and_eval('$pc'))
gdb.execute('delete')
WRAPPERS = ('lanes/x86.rs', 'lanes/mod.rs', 'lanes/axes.rs')
mix = collections.Counter()
n = 0
while True:
    frame = gdb.selected_frame()
    pc = frame.pc()
    if n and pc == start:
        break
    asm = frame.architecture().disassemble(pc)[0]['asm']
    name = frame.name() or ''
    part = 'law' if '::command' in name else 'period' if '::period' in name else 'loop'
    key = part + '\t' + asm
    if os.environ.get('BY_SOURCE'):
        # the innermost inlined frame in landing_core's own code, past the lane wrappers
        f, loc = frame, '?'
        while f is not None:
            sal = f.find_sal()
            path = sal.symtab.filename if sal.symtab else ''
            if 'landing_core' in path and not path.endswith(WRAPPERS):
                loc = path.split('src/')[-1] + ':' + str(sal.line)
                break
            f = f.older()
        key += '\t' + loc
    mix[key] += 1
    n += 1
    gdb.execute('stepi', to_string=True)
json.dump(mix, open(os.environ['OUT'], 'w'))
gdb.execute('kill')
"""


def count(level: str, profile: Path, by_source: bool = False, workload: str = "W1") -> collections.Counter[str]:
    """Every instruction one block-period of W1 executes at `level`, by its text (and, with
    `by_source`, the line of landing_core's code it was inlined from: needs a build with line
    tables)."""
    nm = subprocess.run(["nm", "-C", str(profile)], capture_output=True, text=True, check=True)
    # one control period to the next: the period's call, out of line once per plant and level (the
    # law's call is not always a call: a law with a memory may be inlined into the block's loop)
    cands = [
        line.split()[0]
        for line in nm.stdout.splitlines()
        if line.endswith(f"landing_core::kernel::{level}::period::out_of_line")
    ]
    with tempfile.TemporaryDirectory() as tmp:
        script, out = Path(tmp) / "mix.py", Path(tmp) / "mix.json"
        script.write_text(GDB_SCRIPT)
        env = {"CANDS": ",".join(cands), "ARGS": " ".join([*prefix(workload), str(lanes(workload, level)), level]), "OUT": str(out)}
        if by_source:
            env["BY_SOURCE"] = "1"
        subprocess.run(
            ["gdb", "-q", "-batch", "-x", str(script), str(profile)],
            env={**env, "PATH": "/usr/bin:/bin"},
            capture_output=True,
            check=True,
        )
        return collections.Counter(json.loads(out.read_text()))


def classify(asm: str) -> str:
    """`op.width.load|store|reg` for a line of gdb's AT&T disassembly."""
    op, _, args = asm.partition(" ")
    args = args.split("#")[0].strip()
    width = next((w for w in ("zmm", "ymm", "xmm") if w in args), "")
    if "(" not in args:
        kind = "reg"
    elif "," in args and "(" in args.rsplit(",", 1)[-1] and op.startswith(("vmov", "mov", "kmov", "vmaskmov")):
        # a move whose memory operand is last writes memory (AT&T: destination last)
        kind = "store"
    else:
        kind = "load"
    return f"{op}.{width or 'gpr'}.{kind}"


# Templates of dependency-free instructions, AT&T syntax: {d} a rotating destination vector
# register, {k} a rotating mask register, {g} a rotating general register; zmm0-7 (or
# ymm0-7) hold fixed sources, %rsi points at a 4 kB buffer.
def template(cls: str) -> str | None:
    op, width, kind = cls.split(".")
    v = width if width in ("zmm", "ymm", "xmm") else "zmm"
    if op.startswith(("j", "call", "ret", "push", "pop", "nop")):
        return None  # control flow: left out of the loop (counted in the report)
    if op.startswith("vcmp"):
        pred = op[4:-2]
        if v == "zmm":
            return f"vcmp{pred}pd %{v}0, %{v}1, %k{{k}}"
        return f"vcmp{pred}pd %{v}0, %{v}1, %{v}{{d}}"
    if op == "vmaskmovpd":
        if kind == "store":
            return f"vmaskmovpd %{v}0, %{v}2, {{m}}(%rdi)"
        return f"vmaskmovpd {{m}}(%rsi), %{v}2, %{v}{{d}}"
    if op in ("vtestpd", "vptest"):
        return f"{op} %{v}0, %{v}1"
    if op in ("movapd", "movaps", "vmovdqa64") and kind == "reg":
        return f"vmovapd %{v}1, %{v}{{d}}"
    if op in ("mulsd", "addsd", "subsd", "divsd"):
        return f"{op} %xmm0, %xmm{{d}}"
    if op.startswith("k"):
        return {
            "kandb": "kandb %k1, %k2, %k{k}",
            "korb": "korb %k1, %k2, %k{k}",
            "knotb": "knotb %k1, %k{k}",
            "kortestb": "kortestb %k1, %k2",
            "kmovd": "kmovd %k1, %eax" if kind == "reg" else "kmovd 64(%rsi), %k{k}",
            "kmovw": "kmovw 64(%rsi), %k{k}",
            "kunpckbw": "kunpckbw %k1, %k2, %k{k}",
            "kunpckwd": "kunpckwd %k1, %k2, %k{k}",
            "kshiftrd": "kshiftrd $1, %k1, %k{k}",
            "kshiftrw": "kshiftrw $1, %k1, %k{k}",
        }.get(op)
    if op in ("vmovapd", "vmovupd", "vmovaps", "vmovups", "vmovdqu64", "vmovdqu", "vmovdqa"):
        if kind == "load":
            return f"vmovupd {{m}}(%rsi), %{v}{{d}}"
        if kind == "store":
            return f"vmovupd %{v}0, {{m}}(%rdi)"
        return f"vmovapd %{v}1, %{v}{{d}}"
    if op in ("vmovsd", "movsd", "vmovq", "movq") and kind != "reg":
        return "vmovsd {m}(%rsi), %xmm{d}" if kind == "load" else "vmovsd %xmm0, {m}(%rdi)"
    if op == "vbroadcastsd":
        return f"vbroadcastsd {{m}}(%rsi), %{v}{{d}}" if kind == "load" else f"vbroadcastsd %xmm0, %{v}{{d}}"
    if op == "vpbroadcastq":
        return f"vpbroadcastq {{m}}(%rsi), %{v}{{d}}"
    if op in (
        "vmulpd",
        "vaddpd",
        "vsubpd",
        "vdivpd",
        "vmaxpd",
        "vminpd",
        "vandpd",
        "vorpd",
        "vxorpd",
        "vandnpd",
        "vpaddq",
        "vpandq",
        "vpand",
        "vpor",
        "vporq",
        "vpxord",
        "vpcmpgtq",
        "vfmadd213pd",
        "vfmadd231pd",
        "vfmadd132pd",
        "vfnmadd213pd",
        "vfnmadd231pd",
        "vfnmadd132pd",
        "vpermi2pd",
        "vblendvpd",
    ):
        src = "{m}(%rsi)" if kind == "load" else f"%{v}0"
        if op.startswith("vfn") or op.startswith("vfm") or op.startswith("vperm"):
            return f"{op} {src}, %{v}1, %{v}{{d}}"
        if op == "vblendvpd":
            return f"vblendvpd %{v}2, {src}, %{v}1, %{v}{{d}}"
        return f"{op} {src}, %{v}1, %{v}{{d}}"
    if op == "vpermt2pd":
        return f"vpermt2pd %{v}0, %{v}2, %{v}{{d}}"
    if op in ("vpsllq", "vpsrlq"):
        return f"{op} $52, %{v}1, %{v}{{d}}"
    if op == "vpternlogq":
        return f"vpternlogq $0x96, %{v}0, %{v}1, %{v}{{d}}"
    if op in ("vgetexppd", "vsqrtpd"):
        return f"{op} %{v}1, %{v}{{d}}"
    if op == "vgetmantpd":
        return f"vgetmantpd $0, %{v}1, %{v}{{d}}"
    if op in ("vmulsd", "vaddsd", "vsubsd", "vdivsd"):
        return f"{op} %xmm0, %xmm1, %xmm{{d}}"
    if op in ("vgatherqpd",):
        return "vpcmpeqd %ymm7, %ymm7, %ymm{d2}\n\tvgatherqpd %ymm{d2}, (%rsi,%ymm6,8), %ymm{d}"
    if op == "lea":
        return "lea {m}(%rsi), %{g}"
    if op in ("mov", "movl", "movzbl", "movzwl", "movslq", "movq") and kind == "load":
        return "mov {m}(%rsi), %{g}"
    if op in ("mov", "movl", "movq", "movb") and kind == "store":
        return "mov %rax, {m}(%rdi)"
    if op in (
        "mov",
        "movzbl",
        "movzwl",
        "xor",
        "and",
        "or",
        "add",
        "sub",
        "shr",
        "shl",
        "not",
        "inc",
        "cmove",
        "cmovne",
        "andn",
        "imul",
        "setne",
        "movslq",
    ):
        return "mov %rax, %{g}" if op.startswith("mov") else "add %rax, %{g}"
    if op in ("cmp", "test", "cmpb", "cmpq", "testb", "vucomisd"):
        return "cmp %rax, %rbx"
    return None


VREGS = 24  # destinations: 8 .. 31 (zmm) or 8 .. 15 (ymm: AVX2 has 16)
GREGS = ["r8", "r9", "r10", "r11", "r12", "r13", "r14", "r15"]


def loop_body(mix: dict[str, int], level: str) -> tuple[str, collections.Counter[str]]:
    """The loop's instructions, interleaved (so that no kind runs in a burst), and what was left
    out."""
    # Fused multiply-adds and two-table permutes read their destination, so a register's next
    # reader waits for its last writer; divisions and square roots (16 cycles and more per zmm
    # on Intel's divider) write registers of their own, which nothing reads, so that no reader
    # waits on the divider's queue.
    nvec, nslow = (VREGS - 4, 4) if level == "avx512" else (6, 2)
    lines: list[list[str]] = []
    left = collections.Counter()
    for cls, n in sorted(mix.items()):
        t = template(cls)
        if t is None:
            left[cls] += n
            continue
        lines.append([t] * n)
    # round-robin over the kinds, in proportion: an even spread through the loop
    total = sum(len(x) for x in lines)
    order = sorted(((i + 0.5) / len(x), j, i) for j, x in enumerate(lines) for i in range(len(x)))
    out = []
    slow = 0
    for idx, (_, j, i) in enumerate(order):
        t = lines[j][i]
        d = 8 + idx % nvec
        if t.startswith(("vdiv", "vsqrt")):
            d, slow = 8 + nvec + slow % nslow, slow + 1
        out.append(
            t.replace("{d2}", str(8 + (idx + nvec // 2) % nvec))
            .replace("{d}", str(d))
            .replace("{k}", str(1 + idx % 7) if "%k1, %k2, %k{k}" not in t else str(3 + idx % 5))
            .replace("{g}", GREGS[idx % len(GREGS)])
            .replace("{m}", str(64 * (idx % 32)))
        )
    assert len(out) == total
    return "\n\t".join(out), left


C_PROGRAM = r"""
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
static double now(void) {
    struct timespec t; clock_gettime(CLOCK_MONOTONIC, &t); return t.tv_sec + 1e-9 * t.tv_nsec;
}
/* loads read the first 2 kB, stores write 2 kB at an offset of 10 kB: never the same address
   modulo 4 kB, where a load would wait on an unrelated store (4K aliasing) */
static double buf[2048] __attribute__((aligned(4096)));
int main(int argc, char **argv) {
    long iters = atol(argv[1]);
    for (int i = 0; i < 2048; i++) buf[i] = 1.0 + i * 1e-3;
    /* the clock: dependent register additions, one cycle each (not additions of an immediate:
       Intel's Golden Cove executes chains of those at rename, several a cycle) */
    long adds = iters * 1000;
    long n = adds / 100;
    double t0 = now();
    __asm__ volatile(
        "xor %%rax, %%rax\n\tmov $1, %%rdx\n"
        "1:\n\t" ADDS "\n\tdec %%rcx\n\tjnz 1b\n"
        : "+c"(n) : : "rax", "rdx", "cc");
    double clock_s = now() - t0;
    double ghz = (adds / 100) * 100.0 / clock_s * 1e-9;
    /* denormals read as and flushed to zero: the loop's operands are whatever its instructions
       leave in the rotating registers, and on Intel cores an operation that reads or makes a
       denormal takes a microcode assist (the mix ran 2.7x slower), which W1, whose values are
       normal, does not; this costs nothing on normal operands (a second argument keeps them,
       --keep-denormals) */
    if (argc < 3) __builtin_ia32_ldmxcsr(__builtin_ia32_stmxcsr() | 0x8040);
    long m = iters;
    double *src = buf, *dst = buf + 1280;
    t0 = now();
    __asm__ volatile(
        "vbroadcastsd (%%rsi), %%zmm0\n\tvbroadcastsd 8(%%rsi), %%zmm1\n\t"
        "vbroadcastsd 16(%%rsi), %%zmm2\n\tvpxorq %%zmm6, %%zmm6, %%zmm6\n\t"
        "kxnorw %%k1, %%k1, %%k1\n\tkxnorw %%k2, %%k2, %%k2\n\txor %%rax, %%rax\n\txor %%rbx, %%rbx\n"
        "2:\n\t" BODY "\n\tdec %%rcx\n\tjnz 2b\n\tvzeroupper\n"
        : "+c"(m), "+S"(src), "+D"(dst)
        :
        : "rax", "rbx", "r8", "r9", "r10", "r11", "r12", "r13", "r14", "r15",
          "memory", "cc");
    double mix_s = now() - t0;
    printf("%.4f %.6e\n", ghz, mix_s / iters);
    return 0;
}
"""


def build(body: str, tmp: Path) -> Path:
    src, exe = tmp / "mix.c", tmp / "mix"
    adds = "\\n\\t".join(["add %%rdx, %%rax"] * 100)
    body_c = body.replace("%", "%%").replace("\n\t", "\\n\\t")
    src.write_text(f'#define ADDS "{adds}"\n#define BODY "{body_c}"\n' + C_PROGRAM)
    subprocess.run(
        [
            "gcc",
            "-O2",
            "-mavx512f",
            "-mavx512dq",
            "-mavx512bw",
            "-mavx512vl",
            "-mfma",
            "-mavx2",
            str(src),
            "-o",
            str(exe),
        ],
        check=True,
    )
    return exe


def groups_of(mix: collections.Counter[str]) -> collections.Counter[str]:
    """The mix in a few kinds, for the report."""
    groups: collections.Counter[str] = collections.Counter()
    for cls, n in mix.items():
        op, width, kind = cls.split(".")
        if op.startswith(("vmul", "vfm", "vfnm")) and width != "xmm":
            g = "vector multiply (fused or not)"
        elif op.startswith(("vadd", "vsub")) and width != "xmm":
            g = "vector add, subtract"
        elif op.startswith(("vdiv", "vsqrt")):
            g = "vector divide, square root"
        elif op.startswith(("vmov", "vbroadcast", "vpbroadcast")) and kind != "reg":
            g = f"vector {kind}"
        elif op.startswith("v") and width in ("zmm", "ymm"):
            g = "other vector (logic, compare, permute, shift)"
        elif op.startswith("k"):
            g = "mask register"
        elif op.startswith("j") or op in ("call", "ret"):
            g = "branch"
        else:
            g = "scalar and integer"
        groups[g] += n
    return groups


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--level", default="avx512", choices=["avx2", "avx512"])
    ap.add_argument(
        "--workload",
        default="W1",
        choices=["W1", "W3", "W5", "W6"],
        help="W3 or W5 count and time profile_small_body, W6 profile_w6 (give its path with --profile)",
    )
    ap.add_argument("--rounds", type=int, default=10)
    ap.add_argument("--cases", type=int, default=None, help="the timed runs' cases (W1 960, W3 and W5 480, W6 96)")
    ap.add_argument("--profile", type=Path, default=PROFILE, help="the profile_w1 binary")
    ap.add_argument("--mix", help="reuse a count saved by --save")
    ap.add_argument("--save", help="save the count to this JSON file")
    ap.add_argument(
        "--by-source",
        action="store_true",
        help="also count the vector arithmetic by the source line it was inlined from (a build with "
        "CARGO_PROFILE_RELEASE_DEBUG=line-tables-only; slower)",
    )
    ap.add_argument(
        "--keep-denormals",
        action="store_true",
        help="run the loop without flushing denormals (on Intel its operands' denormals then cost assists)",
    )
    ap.add_argument(
        "--kinds",
        action="store_true",
        help="also time the loop with each kind of instruction alone and without it",
    )
    json_option(ap)
    args = ap.parse_args()
    profile = args.profile
    if args.cases is None:
        args.cases = {"W1": 960, "W6": 96}.get(args.workload, 480)
    LANES = {level: lanes(args.workload, level) for level in WIDE_LANES}
    if not profile.exists():
        sys.exit("build it first: cargo build --release -p landing_core --example profile_w1")
    raw = (
        json.loads(Path(args.mix).read_text())
        if args.mix
        else count(args.level, profile, args.by_source, args.workload)
    )
    if args.save:
        Path(args.save).write_text(json.dumps(raw, indent=0))
    # the law's call, and the rest of the period (plant, integrator, checks, statistics, loop);
    # a law inlined into the block's loop (one with a memory may be) counts in the rest
    parts: dict[str, collections.Counter[str]] = {
        "whole": collections.Counter(),
        "law": collections.Counter(),
        "rest": collections.Counter(),
    }
    sources: collections.Counter[str] = collections.Counter()
    for key, n in raw.items():
        part, asm, *where = key.split("\t")
        cls = classify(asm)
        op, width, kind = cls.split(".")
        if where and width in ("zmm", "ymm") and not op.startswith(("vmov", "vbroadcast", "vpbroadcast")):
            sources[where[0]] += n
        parts["whole"][cls] += n
        parts["law" if part == "law" else "rest"][cls] += n
    for name, mix in parts.items():
        total = sum(mix.values())
        print(
            f"{args.workload} at {args.level}, {name}: {total} instructions per block-period ({LANES[args.level]} cases), "
            f"{total / LANES[args.level]:.1f} per case-step"
        )
        for g, n in groups_of(mix).most_common():
            print(f"  {n:6d}  {g}")
    if sources:
        vector = sum(sources.values())
        files: collections.Counter[str] = collections.Counter()
        for loc, n in sources.items():
            files[loc.rsplit(":", 1)[0]] += n
        print(f"vector arithmetic, logic and compares ({vector} per block-period) by source file:")
        for f, n in files.most_common():
            print(f"  {n:6d}  {100 * n / vector:5.1f} %  {f}")
        print("  the busiest lines:")
        for loc, n in sources.most_common(12):
            print(f"  {n:6d}  {loc}")
    with tempfile.TemporaryDirectory() as tmp:
        exes = {}
        for name, mix in parts.items():
            body, left = loop_body(mix, args.level)
            (Path(tmp) / name).mkdir()
            exes[name] = build(body, Path(tmp) / name)
            print(f"  {name}: left out of the loop: {sum(left.values())} ({', '.join(sorted(left))})")
        w1: list[float] = []
        floor: dict[str, list[float]] = {name: [] for name in parts}
        ghz: list[float] = []
        for _ in range(args.rounds):
            r = subprocess.run(
                [str(profile), *prefix(args.workload), str(args.cases), args.level],
                capture_output=True,
                text=True,
                check=True,
            ).stdout
            w1.append(float(r.split()[0]))
            for name, exe in exes.items():
                g, t = subprocess.run(
                    [str(exe), "200000", *(["denormals"] if args.keep_denormals else [])],
                    capture_output=True,
                    text=True,
                    check=True,
                ).stdout.split()
                ghz.append(float(g))
                floor[name].append(float(t) * 1e9 / LANES[args.level])
    g = statistics.median(ghz)
    w = statistics.median(w1)
    print(f"clock {g:.2f} GHz (median of {len(ghz)})")
    print(
        f"{args.workload} measured:                      {w:6.2f} ns per case-step, {w * g * LANES[args.level]:7.0f} cycles per block-period"
    )
    for name in parts:
        f = statistics.median(floor[name])
        print(
            f"its mix, no dependency ({name:5s}): {f:6.2f} ns per case-step, "
            f"{f * g * LANES[args.level]:7.0f} cycles per block-period"
        )
    ratio = statistics.median(a / b for a, b in zip(w1, floor["whole"]))
    print(f"{args.workload} / floor: {ratio:.2f} (median of the rounds' ratios)")
    width = LANES[args.level]
    write_json(args.json, {
        "workload": args.workload, "level": args.level, "lanes": width, "clock_ghz": g,
        "instructions_per_case_step": {name: sum(mix.values()) / width for name, mix in parts.items()},
        "measured_ns": w, "floor_ns": {name: statistics.median(v) for name, v in floor.items()}, "ratio": ratio,
    })
    if args.kinds:
        kinds(parts["whole"], args.level)
    return 0


def kinds(mix: collections.Counter[str], level: str) -> None:
    """The loop with each kind of instruction alone and without it, fastest of three runs each,
    ns per block-period. Each subset is interleaved anew, so its layout differs from the whole
    loop's as well as its content (see the module's note on ``--kinds``)."""

    def time_of(sub: collections.Counter[str]) -> float:
        with tempfile.TemporaryDirectory() as tmp:
            body, _ = loop_body(sub, level)
            exe = build(body, Path(tmp))
            runs = [subprocess.run([str(exe), "100000"], capture_output=True, text=True, check=True) for _ in range(3)]
            return min(float(r.stdout.split()[1]) for r in runs) * 1e9

    def kind(cls: str) -> str:
        return next(iter(groups_of(collections.Counter({cls: 1}))))

    print(f"the loop by kind of instruction, ns per block-period (all: {time_of(mix):.1f})")
    for g in sorted({kind(c) for c in mix if template(c)}):
        alone = collections.Counter({c: n for c, n in mix.items() if kind(c) == g})
        rest = collections.Counter({c: n for c, n in mix.items() if kind(c) != g})
        print(f"  {g:48s} {sum(alone.values()):5d}   alone {time_of(alone):7.1f}   without {time_of(rest):7.1f}")


if __name__ == "__main__":
    raise SystemExit(main())
