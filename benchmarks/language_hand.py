"""The hand-written Python twins of bench_language.py's ST programs: what a
Python developer writes for the same logic, with the helpers such a
developer writes for PLC data types. bench_language.py checks that each
ends in the same state as the generated code and times both."""

from __future__ import annotations

import math
import struct

# =====================================================================
# Helpers a Python developer writes for PLC data types
# =====================================================================

_F32 = struct.Struct("f")
_f32_pack, _f32_unpack = _F32.pack, _F32.unpack


def f32(x: float, _pack=_f32_pack, _unpack=_f32_unpack) -> float:
    """Round to IEEE binary32 (after each REAL operation); beyond FLT_MAX -> inf."""
    try:
        return _unpack(_pack(x))[0]
    except OverflowError:
        return math.inf if x > 0 else -math.inf


def s32(x: int) -> int:
    """Wrap to DINT (and TIME, which is a DINT of milliseconds)."""
    return ((x + 0x8000_0000) & 0xFFFF_FFFF) - 0x8000_0000


def s16(x: int) -> int:
    """Wrap to INT."""
    return ((x + 0x8000) & 0xFFFF) - 0x8000


# =====================================================================
# a. Loop-heavy numeric program
# =====================================================================


K_0_01 = f32(0.01)  # REAL literals, as stored in 32 bits


class NumericHand:
    """benchmarks/numeric.st by hand. VAR_TEMP (i, sum, err, u) are locals.
    Wraps: counts and checksum wrap to DINT; cycle * 7 + i and the MOD/DIV
    results provably fit. MOD and / truncate toward zero (IEC), written
    inline for the constant positive divisors."""

    __slots__ = (
        "counts",
        "samples",
        "avg",
        "integ",
        "last_err",
        "outp",
        "kp",
        "ki",
        "kd",
        "cycle",
        "checksum",
        "min_avg",
        "max_avg",
    )

    def __init__(self) -> None:
        self.counts = [0] * 1000
        self.samples = [0.0] * 1000
        self.avg = [0.0] * 1000
        self.integ = [0.0] * 100
        self.last_err = [0.0] * 100
        self.outp = [0.0] * 100
        self.kp, self.ki, self.kd = f32(0.8), f32(0.05), K_0_01
        self.cycle = 0
        self.checksum = 0
        self.min_avg = 0.0
        self.max_avg = 0.0

    def __call__(self) -> None:
        self.cycle = cycle = s32(self.cycle + 1)
        counts, samples, avg = self.counts, self.samples, self.avg

        base = cycle * 7
        for i in range(1000):
            x = base + i
            m = x % 1000 if x >= 0 else -(-x % 1000)
            c = ((counts[i] * 3 + m + 0x8000_0000) & 0xFFFF_FFFF) - 0x8000_0000
            counts[i] = c
            m = c % 4096 if c >= 0 else -(-c % 4096)
            samples[i] = f32(m * K_0_01)

        s = 0.0
        lo, hi = f32(1.0e30), f32(-1.0e30)
        for i in range(1000):
            s = f32(s + samples[i])
            if i >= 8:
                s = f32(s - samples[i - 8])
            a = f32(s / 8.0)
            avg[i] = a
            if a < lo:
                lo = a
            if a > hi:
                hi = a
        self.min_avg, self.max_avg = lo, hi

        chk = 0
        for c in counts:
            if c >= 0:
                q, r = c // 3, c % 7
            else:
                q, r = -(-c // 3), -(-c % 7)
            chk = ((chk * 31 + q + r + 0x8000_0000) & 0xFFFF_FFFF) - 0x8000_0000
        self.checksum = chk

        integ, last_err, outp = self.integ, self.last_err, self.outp
        kp, ki, kd = self.kp, self.ki, self.kd
        for i in range(100):
            err = f32(avg[i * 10] - 20.0)
            g = f32(integ[i] + f32(ki * err))  # REAL: binary32 after every operation
            if g > 100.0:
                g = 100.0
            elif g < -100.0:
                g = -100.0
            integ[i] = g
            u = f32(f32(f32(kp * err) + g) + f32(kd * f32(err - last_err[i])))
            outp[i] = min(max(u, -100.0), 100.0)
            last_err[i] = err

    def state(self) -> dict:
        return {
            "counts": self.counts,
            "samples": self.samples,
            "avg": self.avg,
            "integ": self.integ,
            "lastErr": self.last_err,
            "outp": self.outp,
            "cycle": self.cycle,
            "checksum": self.checksum,
            "minAvg": self.min_avg,
            "maxAvg": self.max_avg,
        }


# =====================================================================
# b. Bit / word manipulation
# =====================================================================


class BitsHand:
    """benchmarks/bits.st by hand. WORD/DWORD results are masked where a
    shift or rotation can leave the width; AND/OR/XOR of in-range words
    cannot, and INT_TO_WORD(i) is i for the loop's 0..255. The bit count
    is kept in a local and wrapped to INT once (wrapping commutes with +)."""

    __slots__ = ("words", "masks", "flags", "packed", "cycle", "and_acc", "or_acc", "xor_acc", "crc", "ones", "status")

    def __init__(self) -> None:
        self.words = [0] * 256
        self.masks = [0] * 256
        self.flags = [False] * 256
        self.packed = [0] * 16
        self.cycle = 0
        self.and_acc = self.or_acc = self.xor_acc = 0
        self.crc = 0
        self.ones = 0
        self.status = 0

    def __call__(self) -> None:
        self.cycle = cycle = (self.cycle + 1) & 0xFFFF
        words, masks, flags, packed = self.words, self.masks, self.flags, self.packed

        for i in range(256):
            w = words[i]
            w = ((w << 3 | w >> 13) & 0xFFFF) ^ i ^ cycle
            words[i] = w
            flags[i] = (w >> 3 ^ w >> 12) & 1 == 1
            masks[i] = (w & 0x0FF0) | (w >> 12) | ((w & 0x000F) << 12)

        and_acc, or_acc, xor_acc = 0xFFFF, 0, 0
        for m, w in zip(masks, words):
            and_acc &= m
            or_acc |= m
            xor_acc ^= w
        self.and_acc, self.or_acc, self.xor_acc = and_acc, or_acc, xor_acc

        for i in range(16):
            w = 0
            base = i * 16
            for j in range(16):
                if flags[base + j]:
                    w |= 1 << j
            packed[i] = w

        crc = self.crc
        for i in range(16):
            dw = packed[i] << 16 | masks[i]
            crc = ((crc << 5 | crc >> 27) & 0xFFFF_FFFF) ^ dw
            crc = (crc & ~1) | ((crc >> 31 ^ crc >> 7) & 1)
        self.crc = crc

        ones = 0
        w = xor_acc
        while w:
            w &= w - 1
            ones += 1
        self.ones = s16(ones)

        st = self.status & ~0x0007
        st |= (and_acc != 0) | (or_acc == 0xFFFF) << 1 | (crc & 1) << 2
        self.status = st ^ 0x8000

    def state(self) -> dict:
        return {
            "words": self.words,
            "masks": self.masks,
            "flags": self.flags,
            "packed": self.packed,
            "cycle": self.cycle,
            "andAcc": self.and_acc,
            "orAcc": self.or_acc,
            "xorAcc": self.xor_acc,
            "crc": self.crc,
            "ones": self.ones,
            "status": self.status,
        }


# =====================================================================
# c. 100 FB instances: 50 TON + 50 CTU
# =====================================================================
# benchmarks/timers.st: channel k = 1..50 has an input that is on for k + 2
# cycles out of 2k + 5, a TON with PT = 10k ms on it and a CTU counting the
# TON's rising Q (reset at 1000, preset 40 + k).

CHANNELS = 50


class TON:
    """IEC on-delay timer (the logic of fblocks/iec/standard_fbs.st)."""

    __slots__ = ("Q", "ET", "running", "start")

    def __init__(self) -> None:
        self.Q = self.running = False
        self.ET = self.start = 0

    def __call__(self, IN: bool, PT: int, now: int) -> None:
        if IN:
            if not self.running:
                self.running = True
                self.start = now
            if not self.Q:
                elapsed = s32(now - self.start)  # TIME wraps after 24.8 days
                if elapsed >= PT:
                    self.Q = True
                    self.ET = PT
                else:
                    self.ET = elapsed
        else:
            self.running = self.Q = False
            self.ET = 0


class CTU:
    """IEC up counter; CV stops at the INT maximum (so CV + 1 never wraps)."""

    __slots__ = ("Q", "CV", "last_cu")

    def __init__(self) -> None:
        self.Q = self.last_cu = False
        self.CV = 0

    def __call__(self, CU: bool, R: bool, PV: int) -> None:
        if R:
            self.CV = 0
        elif CU and not self.last_cu and self.CV < 32767:
            self.CV += 1
        self.last_cu = CU
        self.Q = self.CV >= PV


class TimersHand:
    """The timer program by hand: a loop over (timer, counter, parameters).
    Inputs are call arguments, not stored in the instances (the program never
    reads them back). running/full/total are counted in locals without
    wraps: they are bounded by 50 and 50 * 32767."""

    __slots__ = ("channels", "cycle", "running", "full", "total")

    def __init__(self) -> None:
        self.channels = [(TON(), CTU(), k, 2 * k + 5, k + 2, 10 * k, 40 + k) for k in range(1, CHANNELS + 1)]
        self.cycle = self.running = self.full = self.total = 0

    def __call__(self, now: int) -> None:
        self.cycle = cycle = s32(self.cycle + 1)
        running = full = total = 0
        for ton, ctu, k, period, on, pt, pv in self.channels:
            x = cycle + k
            phase = x % period if x >= 0 else -(-x % period)
            ton(phase < on, pt, now)
            ctu(ton.Q, ctu.CV >= 1000, pv)
            if ton.Q:
                running += 1
            if ctu.Q:
                full += 1
            total += ctu.CV
        self.running, self.full, self.total = running, full, total

    def state(self) -> dict:
        st = {"cycle": self.cycle, "running": self.running, "full": self.full, "total": self.total}
        for ton, ctu, k, *_ in self.channels:
            st.update({f"t{k}.Q": ton.Q, f"t{k}.ET": ton.ET, f"c{k}.Q": ctu.Q, f"c{k}.CV": ctu.CV})
        return st


# =====================================================================
# d. Methods dispatched through an interface
# =====================================================================


class AccAdd:
    __slots__ = ("sum",)

    def __init__(self) -> None:
        self.sum = 0

    def step(self, x: int) -> int:
        self.sum = s = ((self.sum + x + 0x8000_0000) & 0xFFFF_FFFF) - 0x8000_0000
        return s

    @property
    def total(self) -> int:
        return self.sum


class AccMax:
    __slots__ = ("sum",)

    def __init__(self) -> None:
        self.sum = 0

    def step(self, x: int) -> int:
        if x > self.sum:
            self.sum = x
        return self.sum

    @property
    def total(self) -> int:
        return self.sum


class OopHand:
    """benchmarks/oop.st by hand: two classes with the same method and
    property in one list (Python's own dispatch); the DINT sums wrap where
    the ST's do (the compiler cannot prove them in range)."""

    __slots__ = ("accs", "cycle", "check", "last")

    def __init__(self) -> None:
        self.accs = [acc for _ in range(50) for acc in (AccAdd(), AccMax())]
        self.cycle = self.check = self.last = 0

    def __call__(self) -> None:
        self.cycle = cycle = s32(self.cycle + 1)
        check = last = 0
        for i, acc in enumerate(self.accs, start=1):
            last = acc.step(((cycle + i + 0x8000_0000) & 0xFFFF_FFFF) - 0x8000_0000)
            check = ((check + last - acc.total + 0x8000_0000) & 0xFFFF_FFFF) - 0x8000_0000
        self.check, self.last = check, last

    def state(self) -> dict:
        return {"cycle": self.cycle, "check": self.check, "last": self.last}
