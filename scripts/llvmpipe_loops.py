#!/usr/bin/env python3
"""What llvmpipe made of a running render's shader loops (docs/BENCH.md "What llvmpipe makes of the loops").

Runs COMMAND (a volrender or benchmark run long enough to be sampled), samples it with perf while it renders, dumps
the code that llvmpipe compiled (its anonymous executable mappings) with gdb, disassembles it with objdump and prints,
per mapping that took a share of the samples, its hottest loops (a backward jump and its target): the share of the
samples in each, its instructions per trip (one trip runs all of a SIMD batch of 8 invocations: llvmpipe runs both
sides of every branch under a mask), how many of them touch the stack (spills), the gathers, the loads of single lanes,
the divisions and the masked blends. The counts are exact and the same on every run, where a frame's time is not.

  scripts/llvmpipe_loops.py [--wait S] [--sample S] [--loops N] -- COMMAND...

Needs perf (linux-perf), gdb and objdump (binutils), and the right to attach to the process (root, or
kernel.yama.ptrace_scope 0 and kernel.perf_event_paranoid <= 1).
"""
import argparse
import collections
import os
import re
import signal
import subprocess
import sys
import tempfile
import time


def executable_mappings(pid):
    """The anonymous executable mappings of `pid` (llvmpipe's JIT code) as (start, end)."""
    out = []
    with open(f'/proc/{pid}/maps') as maps:
        for line in maps:
            fields = line.split()
            if fields[1] == 'r-xp' and len(fields) == 5:
                start, end = (int(x, 16) for x in fields[0].split('-'))
                out.append((start, end))
    return out


def sample_shares(perf_data):
    """Per sampled address of code perf could not name (the JIT's), its share of all samples in percent."""
    report = subprocess.run(['perf', 'report', '-i', perf_data, '--no-children', '--sort', 'sym'],
                            capture_output=True, text=True, check=True).stdout
    shares = collections.Counter()
    for line in report.splitlines():
        m = re.match(r'\s*([\d.]+)%.*\[\.\] 0x([0-9a-f]+)\s*$', line)
        if m:
            shares[int(m.group(2), 16)] += float(m.group(1))
    return shares


def disassemble(path, start):
    """(address, instruction text) of the raw code in `path`, loaded at `start`."""
    text = subprocess.run(['objdump', '-D', '-b', 'binary', '-mi386:x86-64', f'--adjust-vma={start:#x}', path],
                          capture_output=True, text=True, check=True).stdout
    code = []
    for line in text.splitlines():
        m = re.match(r'\s+([0-9a-f]+):\t(?:[0-9a-f]{2} )+\s*\t(.*)', line)
        if m:
            code.append((int(m.group(1), 16), m.group(2)))
    return code


def loop_mix(body):
    ops = collections.Counter(text.split()[0] for text in body)
    return {
        'stack': sum('(%rsp)' in text for text in body),
        'gathers': ops['vpgatherdd'] + ops['vgatherdps'] + ops['vpgatherdq'] + ops['vgatherdpd'],
        'lane loads': ops['vpinsrd'] + ops['vpinsrw'] + ops['vpinsrb'] + ops['vpinsrq'],
        'divisions': ops['vdivps'] + ops['vdivss'],
        'blends': ops['vblendvps'] + ops['vpblendmd'] + ops['vblendmps'] + ops['vpblendvb'] + ops['vpblendmb'],
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--wait', type=float, default=6, help='seconds to let COMMAND start rendering (default 6)')
    parser.add_argument('--sample', type=float, default=3, help='seconds to sample it (default 3)')
    parser.add_argument('--loops', type=int, default=4, help='hottest loops printed per mapping (default 4)')
    parser.add_argument('command', nargs=argparse.REMAINDER)
    args = parser.parse_args()
    command = args.command[1:] if args.command[:1] == ['--'] else args.command
    if not command:
        parser.error('no COMMAND')

    with tempfile.TemporaryDirectory(prefix='llvmpipe_loops.') as work:
        process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        try:
            time.sleep(args.wait)
            if process.poll() is not None:
                sys.exit(f'llvmpipe_loops: COMMAND ended within --wait {args.wait} s: give it more views')
            perf_data = os.path.join(work, 'perf.data')
            subprocess.run(['perf', 'record', '-q', '-F', '4000', '-p', str(process.pid), '-o', perf_data, '--',
                            'sleep', str(args.sample)], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                           check=True)
            mappings = executable_mappings(process.pid)
            dumps = [f'-ex=dump memory {work}/{start:x}.bin {start:#x} {end:#x}' for start, end in mappings]
            subprocess.run(['gdb', '-p', str(process.pid), '-batch'] + dumps, stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL, check=True)
        finally:
            process.send_signal(signal.SIGKILL)
            process.wait()
        shares = sample_shares(perf_data)

        print(f'{"loop":>31} {"samples":>8} {"instr/trip":>10} {"stack":>6} {"gathers":>7} {"lane loads":>10} '
              f'{"div":>4} {"blends":>6}')
        for start, end in mappings:
            share = sum(v for a, v in shares.items() if start <= a < end)
            if share < 1 or not os.path.exists(f'{work}/{start:x}.bin'):
                continue
            code = disassemble(f'{work}/{start:x}.bin', start)
            print(f'mapping {start:#x}: {share:.1f} % of the samples, {len(code)} instructions')
            loops = set()
            for address, text in code:
                m = re.match(r'j\w+\s+0x([0-9a-f]+)', text)
                if m and int(m.group(1), 16) < address:
                    loops.add((int(m.group(1), 16), address))

            def loop_share(loop):
                return sum(v for a, v in shares.items() if loop[0] <= a <= loop[1])

            for first, last in sorted(loops, key=loop_share, reverse=True)[:args.loops]:
                body = [text for address, text in code if first <= address <= last]
                mix = loop_mix(body)
                print(f'  {first:#x}-{last:#x} {loop_share((first, last)):7.1f}% {len(body):10d} {mix["stack"]:6d} '
                      f'{mix["gathers"]:7d} {mix["lane loads"]:10d} {mix["divisions"]:4d} {mix["blends"]:6d}')


if __name__ == '__main__':
    main()
