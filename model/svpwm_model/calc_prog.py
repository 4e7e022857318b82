# SPDX-License-Identifier: Apache-2.0
"""The program of rtl/svpwm_calc.sv (the core's one calculator) and a clock-exact model of its machine.

The calculator is a microcoded accumulator machine: one adder (ACC <- A + B + cin), a 32-word operand RAM
(block RAM), the sine ROM, one 16 x 16 multiplier (the UP5K's SB_MAC16 with its input and output registers,
or a serial shift-add unit where a device has no DSP), a handful of flags and a step counter that addresses
a microcode ROM.  This module *generates* that microcode from the arithmetic of fixed.py (scripts/gen_tables.py
writes rtl/svpwm_ucode.sv and the latencies in rtl/svpwm_pkg.sv from it) and runs it on a Python model of the
machine, clock by clock, so the program is checked against fixed.py before any RTL runs
(model/tests/test_calc_prog.py); the RTL is then checked against fixed.py too (tb/cocotb/svpwm_calc).

Machine, one step per clock (the RTL header repeats this):
  A    = en ? (sh ? ACC << 1 : ACC) : 0
  B    = (RAM_q | AUX_q) ^ {W{BINV_q}}          both registered: chosen by the word two steps before
  sum  = A + B + CIN_q  (W bits);  ACC <- sum | ACC (hold) | sum if cond
  AUX  <- 0 | ROM_q | product >> k | input | ACC >>> 9 | ACC >>> 1 | Q | ANG     (for the next step)
  RAM_q <- RAM[ra | condition bits]; RAM[wa] <- ACC (the value before this step)
  MA, MB <- sat16(B) (MB also <- the angle fraction); product <- MA * MB (registered: ready 2 steps after
  the last load with the DSP, 17 with the serial unit); ROM_q <- ROM[f(ANG of the clock before)];
  Q <- {Q, !sign}; flags <- sign
Every word k holds the own controls of step k, the operand selection of step k + 2 (registered in step k,
so the operand multiplexers of step k + 1 select from registers, not from the microcode ROM's output) and
the condition selection of step k + 3 (registered in step k; in step k + 1 the condition bits -- c[cond], the
sector / snap / DPWM read-address bits -- are computed from the flags into registers, which step k + 2 ORs
into the read address). Step 1 is empty: its operand would come from the word before the start.
"""
from __future__ import annotations

import random
from dataclasses import dataclass, field

from . import config, fixed

W_MIN = 26                     # adder width floor: the V/f candidate boost + fa slope / 2^8 (25 bits) + sign


def acc_width(cnt_width: int) -> int:
    """Adder width: (P + 1) 2^8 +- 2^(CntWidth+8) needs CntWidth + 10 bits, projections 22."""
    return max(cnt_width + 10, W_MIN)


RAM_WORDS = 32
SINE = tuple(fixed.sine_table())           # the sine ROM, built once (run() reads it every clock)
SIN60 = SINE[fixed.ROM_SIZE]

# ---- microcode fields --------------------------------------------------------------------------------------
# The builder and the machine work with logical fields (own fields act in their step, next fields choose the
# next step's B operand); the word packs them into 42 bits (three 16-bit block RAMs), sharing bits between
# fields no step uses together (encode() asserts that):
OWN_FIELDS = (
    ("acc", 1), ("we", 1), ("wa", 5), ("pred", 3), ("fset", 1), ("fidx", 5),
    ("mla", 1), ("mas", 1), ("mlb", 1), ("mbs", 2), ("qsh", 1), ("ald", 1), ("sec", 2), ("rsel", 3),
    ("out", 2), ("done", 1),
)
# the A operand of step k + 1 (word k: registered, so that the adder's A input comes from registers)
A_FIELDS = (("aen", 1), ("ash", 1))
# the operand selection of step k + 2 (word k)
NEXT_FIELDS = (("ra", 5), ("asrc", 3), ("isel", 4), ("psh", 2), ("binv", 2), ("cin", 2))
# the condition selection of step k + 3 (word k): the read-address bits and c[cond] (rc C: ci, binv C: bci)
COND_FIELDS = (("rc", 3), ("cond", 5))
LOGICAL = OWN_FIELDS + A_FIELDS + NEXT_FIELDS + COND_FIELDS
# packed word, LSB first:
#   aen ash                                                                                          (step k + 1)
#   hold | wr (0 -, 1 RAM write, 2 flag set) | dst (wa or fidx) | pred | mop | misc | done           (step k)
#   src (asrc: 0 = the RAM word) | opnd (ra, isel or psh) | binv | cin                               (step k + 2)
#   rc | cond (ci or bci)                                                                            (step k + 3)
FIELDS = (
    ("aen", 1), ("ash", 1), ("hold", 1), ("wr", 2), ("dst", 5), ("pred", 3), ("mop", 4), ("misc", 4),
    ("done", 1), ("src", 3), ("opnd", 5), ("rc", 3), ("cond", 5), ("binv", 2), ("cin", 2),
)
WR_NONE, WR_RAM, WR_FLAG = range(3)
# mop: the multiplier operand loads (mla, mas, mlb, mbs)
MOP = {(0, 0, 0, 0): 0, (1, 0, 0, 0): 1, (1, 1, 0, 0): 2, (0, 0, 1, 0): 3, (0, 0, 1, 1): 4, (0, 0, 1, 2): 5,
       (1, 1, 1, 0): 6, (1, 1, 1, 1): 7, (1, 0, 1, 1): 8, (1, 0, 1, 2): 9, (1, 1, 1, 2): 10}
# misc: the rare single-step actions (qsh, ald, sec, rsel, out)
MISC = {(0, 0, 0, 0, 0): 0, (1, 0, 0, 0, 0): 1, (0, 1, 0, 0, 0): 2, (0, 1, 1, 0, 0): 3, (0, 0, 2, 0, 0): 4,
        (0, 0, 3, 0, 0): 5, (0, 0, 0, 1, 0): 6, (0, 0, 0, 2, 0): 7, (0, 0, 0, 3, 0): 8, (0, 0, 0, 4, 0): 9,
        (0, 0, 0, 0, 1): 10, (0, 0, 0, 0, 2): 11, (0, 0, 0, 0, 3): 12}
(MISC_NONE, MISC_QSH, MISC_ALD, MISC_ALD_SEC, MISC_SEC_XYZ, MISC_SEC_ERR, MISC_ROM_I, MISC_ROM_I1, MISC_ROM_N,
 MISC_ROM_N1, MISC_OUT_HI, MISC_OUT_LO, MISC_OUT_MID) = range(13)

# acc: ACC <- sum, or held (compares)
ACC_SUM, ACC_HOLD = 0, 1
# pred: which modes a step's RAM write, sector and angle loads apply to
PRED_ALL, PRED_TH, PRED_AB, PRED_DQ, PRED_XY = range(5)
# sec
SEC_NONE, SEC_THETA, SEC_XYZ, SEC_ERR = range(4)
# rsel: ROM address from ANG[15:8] = i
ROM_OFF, ROM_I, ROM_I1, ROM_N, ROM_N1 = range(5)        # 0, i, i + 1, 256 - i, 255 - i
# out: load the compare values of the phases whose Table 4-3 code is of this class
OUT_NONE, OUT_HI, OUT_LO, OUT_MID = range(4)
# mbs: MB source
MB_B, MB_FR, MB_ACC = range(3)
# rc: condition bits ORed into the read address
RC_NONE, RC_C, RC_SW, RC_SW1, RC_SNAP, RC_DPWM, RC_MERGE = range(7)
# asrc
AS_NONE, AS_ROM, AS_PROD, AS_IN, AS_SHR9, AS_SHR1, AS_Q, AS_ANG = range(8)
# isel: the calculator's held inputs
IN_M, IN_THETA, IN_V1, IN_V2, IN_BOOST, IN_SLOPE, IN_MMAX, IN_FABS, IN_PERIOD, IN_THR, IN_DHI, IN_DLO, IN_DMID, \
    IN_MV = range(14)
# IN_DHI / IN_DLO / IN_DMID: the dead-time compensation of the phase of class OUT_HI / OUT_LO / OUT_MID (its current
# sign: + hdf if negative, else - hdr; signed); IN_MV: the overmodulation threshold, fixed.M_VERTEX with om_i in
# the angle-driven modes, else 0xFFFF
IN_SIGNED = (IN_V1, IN_V2, IN_DHI, IN_DLO, IN_DMID)
# psh: product shift (rounding: cin mode CIN_RND adds bit k - 1)
PSH = (8, 14, 15, 0)
PSH8, PSH14, PSH15, PSH0 = range(4)
# binv / cin
BINV_NO, BINV_YES, BINV_C, BINV_NSIGN = range(4)
CIN_0, CIN_1, CIN_BINV, CIN_RND = range(4)

# flags (the sign of the sum when set) and derived conditions: the condition vector c[0..31]
(F_FIRST, F_SATN, F_NX, F_PX, F_NY, F_PY, F_NZ, F_PZ, F_V1N, F_V2N, F_VF, F_HALF, F_CAP, F_DP60,
 F_S1, F_S2, F_S3, F_S4) = range(18)
N_FLAGS = 18
C_VF, C_XY, C_ERR, C_MIDSGN, C_DQ, C_NV1N, C_NHALF = range(24, 31)

# RAM map (32 words; the ZERO words read 0 and are never written; pairs / blocks are read with condition bits
# ORed into the address)
R_ZERO = 0
R_K64 = 1            # 2^16
R_K32 = 2            # 2^15
R_SQ3 = 3            # sqrt(3)/2, UQ0.16
R_K256 = 5           # 256
R_P2H = 6            # 2P - hthr; before: the overmodulation gain g (R_G), then the base (P + 1) 2^8
R_G = 6
R_S = 7              # T1 + T2
R_T1 = 8             # {T1 polar, T1 xyz, 0, 0}; after the merge {P - hi, -lo, 0, 0} (R_DP)
R_DP = 8
R_T2 = 12            # {T2 polar, T2 xyz, 0, 0}
R_ABS = 16           # {|X|, |Z|, |Y|, -}
R_X, R_Y, R_Z = 19, 20, 21
R_GH = 22            # {0xFFFF, g + h}
R_SNAP = 24          # {c, 0, thr, P, P - hthr}
R_MIN = 28           # {q, min}        read | !sat
R_MAX = 30           # {2^16 - q, max}
ZERO_WORDS = (R_ZERO, R_T1 + 2, R_T1 + 3, R_T2 + 2, R_T2 + 3, R_SNAP + 1)
# scratch words, each used before the block it sits in
R_A = 4
S_SB, S_SA, S_M, S_VF0, S_VF1, S_G, S_H = 26, 27, 28, 30, 31, 16, 17

RAM_INIT = {R_K64: 1 << 16, R_K32: 0x8000, R_SQ3: fixed.SQRT3_2, R_K256: 256, R_GH: 0xFFFF}


def _sx(v: int, w: int) -> int:
    v &= (1 << w) - 1
    return v - (1 << w) if v >> (w - 1) else v


@dataclass
class Program:
    """Steps 1..n of the calculator (index 0 is the idle word: it only selects step 1's operand).
    features: the build's feature mask (config.py; only its calculator bits, config.CALC, shape the program)."""
    features: int
    tiny: bool = False
    steps: list = field(default_factory=lambda: [dict()])

    @property
    def dsp(self) -> bool:
        return config.has(self.features, "dsp")

    @property
    def compact(self) -> bool:
        """The tiny configuration's program (TRANSITIONAL: the tiny core runs rtl/svpwm_duty_lite.sv, which
        reads no mode; this program, FREQ without an error path, is the model's only)."""
        return self.tiny

    @property
    def latency(self) -> int:
        """Clocks from start_i to done_o: steps 1 .. n - 1 run in the clocks after start_i, done_o follows."""
        return len(self.steps)

    def words(self) -> list[dict]:
        """Per microcode word k: the own fields of step k, the A selection of step k + 1, the B selection of
        step k + 2 and the condition selection of step k + 3 (logical fields)."""
        own_names, next_names = dict(OWN_FIELDS), dict(NEXT_FIELDS)
        n = len(self.steps)
        # step 1 has no operand (it would come from the word before the start: junk after a done or an abort)
        st1 = self.steps[1] if n > 1 else {}
        assert not any(f in next_names or f in ("mla", "mlb", "we", "fset", "qsh") for f in st1), "step 1: B used"
        for k in (1, 2):
            st = self.steps[k] if k < n else {}
            # step 2's condition bits would be computed in the start clock (idle: gated off)
            assert st.get("rc", RC_NONE) == RC_NONE and st.get("binv") != BINV_C, f"step {k}: a condition"
        out = []
        for k, st in enumerate(self.steps):
            w = {f: v for f, v in st.items() if f in own_names}
            if k + 1 < n:
                w.update({f: v for f, v in self.steps[k + 1].items() if f in dict(A_FIELDS)})
            if k + 2 < n:
                nx = self.steps[k + 2]
                if nx.get("asrc", AS_NONE) != AS_NONE:
                    assert not (nx.get("ra") or nx.get("rc")), f"step {k + 2}: a RAM operand with an AUX source"
                w.update({f: v for f, v in nx.items() if f in next_names})
            if k + 3 < n:
                cs = self.steps[k + 3]
                rc, binv = cs.get("rc", RC_NONE), cs.get("binv", BINV_NO)
                assert not (rc == RC_C and binv == BINV_C), f"step {k + 3}: two conditions"
                assert binv != BINV_NSIGN or cs.get("cin") == CIN_BINV, f"step {k + 3}: BINV_NSIGN needs CIN_BINV"
                cond = cs.get("ci", 0) if rc == RC_C else cs.get("bci", 0) if binv == BINV_C else 0
                assert cs.get("ci", 0) in (0, cond) and cs.get("bci", 0) in (0, cond), k + 3
                w.update(rc=rc, cond=cond)
            out.append(w)
        return out

    def encode(self) -> list[int]:
        return [pack(w, k) for k, w in enumerate(self.words())]


WORD_BITS = sum(w for _, w in FIELDS)


def field_pos() -> dict[str, tuple[int, int]]:
    """Packed field -> (lowest bit, width)."""
    pos, out = 0, {}
    for name, width in FIELDS:
        out[name] = (pos, width)
        pos += width
    return out


def pack(w: dict, k: int = -1) -> int:
    """Logical fields -> the packed word (asserting that fields sharing bits are not used together)."""
    g = {n: w.get(n, 0) for n, _ in LOGICAL}
    assert not (g["we"] and g["fset"]), f"word {k}: a RAM write and a flag set"
    assert g["we"] or g["fset"] or not (g["wa"] or g["fidx"]), k
    kmisc = (g["qsh"], g["ald"], g["sec"], g["rsel"], g["out"])
    assert kmisc in MISC, f"word {k}: misc actions {kmisc} together"
    kmop = (g["mla"], g["mas"], g["mlb"], g["mbs"])
    assert kmop in MOP, f"word {k}: multiplier loads {kmop}"
    if g["asrc"] == AS_NONE:
        assert not (g["isel"] or g["psh"]), k
        opnd = g["ra"]
    else:
        assert not g["ra"], f"word {k}: a RAM operand with an AUX source"
        opnd = g["isel"] if g["asrc"] == AS_IN else g["psh"] if g["asrc"] == AS_PROD else 0
        assert g["asrc"] in (AS_IN, AS_PROD) or not (g["isel"] or g["psh"]), k
    cond = g["cond"]
    f = dict(aen=g["aen"], ash=g["ash"], hold=g["acc"], wr=WR_RAM if g["we"] else WR_FLAG if g["fset"] else 0,
             dst=g["wa"] if g["we"] else g["fidx"], pred=g["pred"], mop=MOP[kmop], misc=MISC[kmisc],
             done=g["done"], src=g["asrc"], opnd=opnd, rc=g["rc"], cond=cond, binv=g["binv"], cin=g["cin"])
    v = 0
    for name, (p, width) in field_pos().items():
        assert 0 <= f[name] < (1 << width), (k, name, f[name])
        v |= f[name] << p
    return v


_MOP_INV = {v: k for k, v in MOP.items()}
_MISC_INV = {v: k for k, v in MISC.items()}


def decode(word: int) -> dict:
    """The packed word -> logical fields (what the RTL's decoder does)."""
    f = {n: (word >> p) & ((1 << w) - 1) for n, (p, w) in field_pos().items()}
    g = dict(aen=f["aen"], ash=f["ash"], acc=f["hold"], we=int(f["wr"] == WR_RAM), fset=int(f["wr"] == WR_FLAG),
             wa=f["dst"], fidx=f["dst"], pred=f["pred"], done=f["done"], asrc=f["src"], rc=f["rc"],
             cond=f["cond"], binv=f["binv"], cin=f["cin"])
    g["mla"], g["mas"], g["mlb"], g["mbs"] = _MOP_INV[f["mop"]]
    g["qsh"], g["ald"], g["sec"], g["rsel"], g["out"] = _MISC_INV[f["misc"]]
    g["ra"] = f["opnd"] if f["src"] == AS_NONE else 0
    g["isel"] = f["opnd"] if f["src"] == AS_IN else 0
    g["psh"] = f["opnd"] & 3 if f["src"] == AS_PROD else 0
    return g


# ---- building the program --------------------------------------------------------------------------------
def _invert(inv: bool, cin, binv, bci) -> dict:
    """The B operand's inversion and carry: inv gives - B (binv, cin 1); binv / cin override (cin 0: ~B)."""
    return dict(binv=(BINV_YES if inv else BINV_NO) if binv is None else binv, bci=bci,
                cin=(CIN_1 if inv else CIN_0) if cin is None else cin)


def ram(addr, rc=RC_NONE, ci=0, inv=False, cin=None, binv=None, bci=0):
    """B = RAM word (| condition bits), optionally inverted (inv: - B with cin 1, or ~B with cin=0)."""
    return dict(ra=addr, rc=rc, ci=ci, **_invert(inv, cin, binv, bci))


def aux(asrc, isel=0, psh=0, inv=False, cin=None, binv=None, bci=0):
    """B = AUX (asrc: ROM, product, input, shifted ACC, Q, ANG), inverted as ram()."""
    return dict(asrc=asrc, isel=isel, psh=psh, **_invert(inv, cin, binv, bci))


def inp(isel, **kw):
    return aux(AS_IN, isel=isel, **kw)


def prod(psh, sign=None, rnd=True):
    """B = the product >> k, rounded (bit k - 1 into the carry), negated when condition `sign` (a c index) is
    set (sign-magnitude: the rounding is then towards -infinity of the magnitude, i.e. ties away from zero)."""
    if sign is None:
        return aux(AS_PROD, psh=psh, binv=BINV_NO, cin=CIN_RND if rnd else CIN_0)
    if sign == "neg":
        return aux(AS_PROD, psh=psh, binv=BINV_YES, cin=CIN_RND)
    return aux(AS_PROD, psh=psh, binv=BINV_C, bci=sign, cin=CIN_RND)


def rom(sel, inv=False):
    """B = the sine ROM at address f(ANG, sel) (the builder issues the read two steps before)."""
    b = aux(AS_ROM, inv=inv)
    b["rom"] = sel
    return b


# flags each address-condition mode reads
_RC_FLAGS = {RC_SW: (F_NX, F_PX, F_NY, F_PY, F_NZ, F_PZ), RC_SW1: (F_NX, F_PX, F_NY, F_PY, F_NZ, F_PZ),
             RC_SNAP: (F_S1, F_S2, F_S3, F_S4), RC_DPWM: (F_DP60,), RC_MERGE: ()}
_RC_SPAN = {RC_NONE: 1, RC_C: 2, RC_SW: 3, RC_SW1: 3, RC_SNAP: 5, RC_DPWM: 4, RC_MERGE: 4}
_DERIVED = {C_MIDSGN: (F_FIRST,), C_NV1N: (F_V1N,), C_NHALF: (F_HALF,)}


class Builder:
    """Places steps at a cursor and waits by itself for what a step reads: a RAM word written by an earlier
    step (readable as B two steps after the write), a flag (as a condition of B three steps after it is set:
    the condition bits are registered), a product, a ROM word (four steps after the angle it is addressed by),
    the sector's Table 4-3 codes (registered from the sector: an out step two steps after the sector's load)."""

    def __init__(self, features: int, tiny: bool = False):
        self.p = Program(features=features, tiny=tiny)
        self.t = 2                            # step 1 is empty (Program.words)
        self.dsp = dsp = self.p.dsp
        self.mul_lat = 2 if dsp else 17
        self.wt: dict[int, int] = {}          # RAM address -> step that writes it
        self.ft: dict[int, int] = {}          # flag -> step that sets it
        self.busy_until = 0                   # serial multiplier: MA / MB must hold until this step
        self.acc_t = self.q_t = -9            # last steps that changed ACC, Q, ANG, the sector
        self.ang_t = self.sec_t = 0           # (the start clock loads ANG and the sector)

    def _flags_of(self, c: int):
        if c < N_FLAGS:
            return (c,)
        return _DERIVED.get(c, ())

    def _ready(self, b: dict) -> int:
        need = 1
        if b.get("binv") == BINV_NSIGN:                   # the sign of the step two before (registered)
            assert self.p.steps[self.t - 1].get("acc") == ACC_HOLD and self.acc_t == self.t - 2, self.t
        if "rom" in b:
            need = max(need, 3, self.ang_t + 4)           # the read (two steps before) sees the new ANG
            #                                               (the ROM addresses are registered from ANG)
        asrc = b.get("asrc")
        if asrc in (AS_SHR9, AS_SHR1):                    # AUX takes ACC in the step before B
            need = max(need, self.acc_t + 2)
        if asrc == AS_Q:                                  # (the Q shift takes the sign one clock later)
            need = max(need, self.q_t + 3)
        if asrc == AS_ANG:
            need = max(need, self.ang_t + 2)
        if asrc == AS_IN and b.get("isel") in (IN_DHI, IN_DLO, IN_DMID):
            need = max(need, self.sec_t + 5)              # (by the Table 4-3 codes, sel, and registered)
        if b.get("ra") is not None and "ra" in b:
            rc = b.get("rc", RC_NONE)
            for a in range(b["ra"], b["ra"] + _RC_SPAN[rc]):
                if a in self.wt:
                    need = max(need, self.wt[a] + 2)
            fl = _RC_FLAGS.get(rc, ()) + (self._flags_of(b.get("ci", 0)) if rc == RC_C else ())
            for f in fl:                                  # flags: set one clock after their step
                if f in self.ft:
                    need = max(need, self.ft[f] + (5 if rc in (RC_SW, RC_SW1) else 4))   # (sw_q: one more)
            if rc == RC_C and b.get("ci") == C_MIDSGN:
                need = max(need, self.sec_t + 4)
        if b.get("binv") == BINV_C:
            for f in self._flags_of(b["bci"]):
                if f in self.ft:
                    need = max(need, self.ft[f] + 4)
            if b["bci"] == C_MIDSGN:                      # the Table 4-3 codes of the sector (sel) are
                need = max(need, self.sec_t + 4)          # registered from it: c[] one step later still
        return need

    def put(self, t: int, b: dict | None = None, **own) -> None:
        b = dict(b or {})
        if "rom" in b:
            self.put(t - 2, rsel=b.pop("rom"))
        while len(self.p.steps) <= t:
            self.p.steps.append(dict())
        s = self.p.steps[t]
        for k, v in list(b.items()) + list(own.items()):
            assert k not in s or s[k] == v, f"step {t}: field {k} set twice ({s[k]} / {v})"
            s[k] = v

    def e(self, b=None, **own) -> int:
        if b:
            self.wait(self._ready(b))
        if own.get("mla") or own.get("mlb"):
            self.wait(self.busy_until)
        if "rom" in (b or {}):
            # the read two steps before must be free (it shares the word's misc field with qsh, ald, sec, out)
            while len(self.p.steps) > self.t - 2 and (
                    self.p.steps[self.t - 2].get("rsel", ROM_OFF) not in (ROM_OFF, b["rom"])
                    or any(self.p.steps[self.t - 2].get(f) for f in ("qsh", "ald", "sec", "out"))):
                self.hold()
        if own.get("fset") and len(self.p.steps) > self.t and self.p.steps[self.t].get("we"):
            # a flag set and a RAM write share the word's dst field: a compare holds ACC, so the write (of ACC
            # at the start of the step) moves to the next step
            # (a load with a flag set changes ACC: then a hold step takes the write)
            if own.get("acc") == ACC_HOLD:
                st = self.p.steps[self.t]
                mv = {f: st.pop(f) for f in ("we", "wa", "pred") if f in st}
                self.put(self.t + 1, **mv)
                self.wt[mv["wa"]] = self.t + 1
            else:
                self.hold()
        if own.get("mbs") == MB_FR:
            self.wait(self.ang_t + 1)
        t = self.t
        self.put(t, b, **own)
        s = self.p.steps[t]
        if s.get("acc", ACC_SUM) == ACC_SUM:
            self.acc_t = t
        if s.get("qsh"):
            self.q_t = t
        if s.get("ald"):
            self.ang_t = t
        if s.get("sec") == SEC_XYZ:                       # the sector of the signs comes from a register
            sgn = [self.ft.get(f, -9) for f in _RC_FLAGS[RC_SW]]
            assert t >= max(sgn) + 3, f"step {t}: sector from flags set in step {max(sgn)}"
        if s.get("out"):
            assert t >= self.sec_t + 2, f"step {t}: out with the sector of step {self.sec_t}"
        if s.get("sec"):
            self.sec_t = t
        if own.get("fset"):
            self.ft[own["fidx"]] = t
        if own.get("we"):
            self.wt[own["wa"]] = t
        self.t += 1
        return t

    def wait(self, t: int) -> None:
        while self.t < t:
            self.hold()

    def load(self, b, **own):                      # ACC <- B
        return self.e(b, aen=0, **own)

    def add(self, b, **own):                       # ACC <- ACC + B
        return self.e(b, aen=1, **own)

    def add2(self, b, **own):                      # ACC <- 2 ACC + B
        return self.e(b, aen=1, ash=1, **own)

    def cmp(self, b, flag, shift=False, **own):    # flag <- sign(ACC (or 2 ACC) + B); ACC held
        return self.e(b, aen=1, ash=int(shift), acc=ACC_HOLD, fset=1, fidx=flag, **own)

    def hold(self, b=None, **own):
        return self.e(b, aen=1, acc=ACC_HOLD, **own)

    def write(self, addr, pred=PRED_ALL):
        """RAM[addr] <- ACC as it is at the start of the current step (the result of the step before)."""
        assert addr not in ZERO_WORDS
        self.put(self.t, we=1, wa=addr, pred=pred)
        self.wt[addr] = self.t

    def mul(self, ma, mb, **own) -> int:
        """MA <- ma, MB <- mb; each 'acc' (ACC at the step), 'fr' (MB only: the angle fraction) or a B selection.
        Returns the first step whose B may be the product (AUX takes it in the step before)."""
        ma_own = dict(mla=1, mas=1) if ma == "acc" else dict(mla=1, mas=0)
        if mb in ("acc", "fr"):
            t = self.e(None if ma == "acc" else ma, **ma_own, mlb=1, mbs=MB_ACC if mb == "acc" else MB_FR,
                       **{"acc": ACC_HOLD, "aen": 1, **own})
        elif ma == "acc":
            t = self.e(mb, **ma_own, mlb=1, mbs=MB_B, **{"acc": ACC_HOLD, "aen": 1, **own})
        else:
            self.e(ma, **ma_own, acc=ACC_HOLD, aen=1)
            t = self.e(mb, mlb=1, mbs=MB_B, **{"acc": ACC_HOLD, "aen": 1, **own})
        if not self.dsp:
            self.busy_until = t + 17
        return t + self.mul_lat + 1

    def mb(self, mb, **own) -> int:
        """MB <- mb only (MA kept)."""
        t = self.e(None if mb in ("acc", "fr") else mb, mlb=1,
                   mbs={"acc": MB_ACC, "fr": MB_FR}.get(mb, MB_B) if isinstance(mb, str) else MB_B,
                   **{"acc": ACC_HOLD, "aen": 1, **own})
        if not self.dsp:
            self.busy_until = t + 17
        return t + self.mul_lat + 1


# ---- the machine, clock by clock (what rtl/svpwm_calc.sv does) -------------------------------------------
def sat16(x: int) -> int:
    """A multiplier operand: 16 bits, 2^16 (a dwell time of the whole period) capped at 0xFFFF (fixed.T_CAP)."""
    return 0xFFFF if (x >> 16) & 1 else x & 0xFFFF


def sector_of_flags(f: list[int]) -> int:
    """fixed.xyz_sector from the signs: q = (X, Z, -Y, -X, -Z, Y); neg[k] = q_k < 0; the first s with
    q_s >= 0 > q_{s+1} (none: the zero vector, sector 0)."""
    neg = (f[F_NX], f[F_NZ], f[F_PY], f[F_PX], f[F_PZ], f[F_NY])
    for s in range(6):
        if not neg[s] and neg[(s + 1) % 6]:
            return s
    return 0


def snap_bits(f: list[int]) -> int:
    """RAM word of the minimum-pulse result in {c, 0, thr, P, P - hthr} (fixed.snap_min_pulse)."""
    f1, f2, f3, f4 = f[F_S1], f[F_S2], not f[F_S3], not f[F_S4]
    if f1:
        return 1 if f2 else 2
    if f3:
        return 3 if f4 else 4
    return 0


def sel_class(code: int) -> int:
    """Table 4-3 code -> OUT class: 0 +(A+B) is the highest C, 1 -(A+B) the lowest, 2 / 3 the middle one."""
    return (OUT_HI, OUT_LO, OUT_MID, OUT_MID)[code]


# per sector (fixed.SECTOR_SEL row): the phase of the OUT class IN_DHI / IN_DLO / IN_DMID reads (the first
# phase of that class), computed once
_DPH = tuple(tuple(next(p for p in range(3) if sel_class(sel[p]) == cls) for cls in (OUT_HI, OUT_LO, OUT_MID))
             for sel in fixed.SECTOR_SEL)
_MIDNEG = tuple(any(c == 3 for c in sel) for sel in fixed.SECTOR_SEL)   # the middle class negated (code 3)


class Machine:
    def __init__(self, prog: Program, cnt_width: int = fixed.CNT_WIDTH):
        self.prog = prog
        self.words = [decode(w) for w in prog.encode()]
        # each word's A, next and condition fields, split once (run() registers them every clock)
        self.split = [({n: w[n] for n, _ in A_FIELDS}, {n: w[n] for n, _ in NEXT_FIELDS},
                       {n: w[n] for n, _ in COND_FIELDS}) for w in self.words]
        self.cw = cnt_width
        self.W = acc_width(cnt_width)
        self.mask = (1 << self.W) - 1

    def run(self, inp: dict, trace: list | None = None, junk: random.Random | None = None
            ) -> tuple[int, tuple[int, int, int], bool, bool]:
        """Start with inputs `inp` (fixed.modulate's names + thr), run to done; (sector, C, sat, err).
        junk: start from random state (registers, flags, the RAM's working words) as the RTL does after an
        earlier or aborted computation; the result must not depend on it."""
        W, mask = self.W, self.mask
        f = self.prog.features
        mode = inp_mode(inp, config.TINY if self.prog.tiny else f)
        is_vf, is_ab, is_dq, is_th = mode == fixed.MODE_VF, mode == fixed.MODE_AB, mode == fixed.MODE_DQ, \
            mode in (fixed.MODE_POLAR, fixed.MODE_DQ)
        is_err = mode > fixed.MODE_DQ
        dpwm = inp.get("dpwm", 0) if config.has(f, "dpwm") else 0
        # the inputs of features the build lacks are not read (the RTL's input multiplexer has 0 there)
        has = lambda n: config.has(f, n)                   # noqa: E731
        th_in, xy_in, vf_in = config.has_theta(f), config.has_xy(f), has("vf")
        ins = [inp.get("m", 0), inp.get("theta", 0) if th_in else 0, inp.get("v1", 0) if xy_in else 0,
               inp.get("v2", 0) if xy_in else 0] + \
            [inp.get(n, 0) if vf_in else 0 for n in ("vf_boost", "vf_slope", "vf_mmax", "fabs")] + \
            [inp["period"], inp["thr"], 0, 0, 0,
             fixed.M_VERTEX if has("sixstep") and inp.get("om", 0) and not (is_ab or is_dq) else 0xFFFF]
        hdr, hdf = (inp.get("hdr", 0), inp.get("hdf", 0)) if has("dtc") else (0, 0)
        carry = tuple(inp.get("carry", (0, 0, 0))) if has("carry") else (0, 0, 0)
        isign = inp.get("isign", 0) & 7 if has("dtc") else 0
        ins += [0] * 2
        ram = [0] * RAM_WORDS
        for a, v in RAM_INIT.items():
            ram[a] = v
        acc, aux_q, ram_q, rom_q, binv_q, cin_q = 0, 0, 0, 0, 0, 0
        ang, sec = inp.get("a16", 0) & 0xFFFF, inp.get("sector", 0)
        flags = [0] * 32
        q = 0
        ma = mb = 0
        p = 0
        if junk is not None:
            ram = [v if a in RAM_INIT or a in ZERO_WORDS else junk.getrandbits(W) for a, v in enumerate(ram)]
            acc, rom_q = junk.getrandbits(W), junk.getrandbits(16)
            flags = [junk.getrandbits(1) for _ in range(32)]
            q, ma, mb = junk.getrandbits(16), junk.getrandbits(16), junk.getrandbits(16)
            p = ma * mb
        # registers of the operand selection (the word before: NEXT_FIELDS), the condition selection and its
        # bits, the selected input, the sector's sign code and Table 4-3 codes, the ROM address's angle
        a_q = {n: 0 for n, _ in A_FIELDS}
        nx = {n: 0 for n, _ in NEXT_FIELDS}
        cx = {n: 0 for n, _ in COND_FIELDS}
        rbits_q = cbit_q = 0
        in_q = 0
        sec_p = sec                       # the sector of the clock before (sel)
        sw_q = 0
        ang_p = ang                       # the angle of the clock before (ROM address)
        if junk is not None:
            nx = {n: junk.getrandbits(w) for n, w in NEXT_FIELDS}
            nx["asrc"], nx["psh"], nx["isel"] = AS_NONE, 0, 0     # (B of step 1 is not used: any RAM word)
            cx = {n: junk.getrandbits(w) for n, w in COND_FIELDS}
            rbits_q, cbit_q, in_q = junk.getrandbits(3), junk.getrandbits(1), junk.getrandbits(16)
            sec_p, sw_q, ang_p = junk.randrange(6), junk.randrange(6), junk.getrandbits(16)
        pend_f, pend_q, sign_q = None, 0, 0     # the flag set / Q shift of the clock before, its sign
        ser_left = 0
        ser_prod = None
        cmp = [0, 0, 0] if junk is None else [junk.getrandbits(self.cw) for _ in range(3)]
        e_out = [0, 0, 0] if junk is None else [junk.randint(-1000, 1000) for _ in range(3)]
        cmd = 0 if junk is None else junk.randint(-(1 << 20), 1 << 20)
        table = SINE
        out = None
        for k, w in enumerate(self.words):
            busy = k > 0
            # conditions (registered flags, the held mode / dpwm inputs, the Table 4-3 codes registered from
            # the sector of the clock before)
            sel = fixed.SECTOR_SEL[sec_p if sec_p < 6 else 5]
            midneg = _MIDNEG[sec_p if sec_p < 6 else 5]
            c = flags[:N_FLAGS] + [0] * (32 - N_FLAGS)
            c[C_VF], c[C_XY], c[C_ERR], c[C_DQ] = int(is_vf), int(is_ab or is_dq), int(is_err), int(is_dq)
            c[C_MIDSGN] = int(midneg) ^ flags[F_FIRST]
            c[C_NV1N], c[C_NHALF] = 1 - flags[F_V1N], 1 - flags[F_HALF]
            for isel_d, ph in zip((IN_DHI, IN_DLO, IN_DMID), _DPH[sec_p if sec_p < 6 else 5]):
                ins[isel_d] = ((hdf if (isign >> ph) & 1 else -hdr) + carry[ph]) & 0xFFFF
            if k == 0:
                # idle word: only its next fields matter
                a_val, b_val, s = 0, 0, 0
            else:
                a_val = ((acc << 1) if a_q["ash"] else acc) & mask if a_q["aen"] else 0
                b_val = ((ram_q | aux_q) ^ (mask if binv_q else 0)) & mask
                s = (a_val + b_val + cin_q) & mask
            sign = (s >> (W - 1)) & 1
            pred = {PRED_ALL: True, PRED_TH: is_th, PRED_AB: is_ab, PRED_DQ: is_dq, PRED_XY: is_ab or is_dq}[w["pred"]]
            # ---- condition bits of the step after next (cx: registered from the word before) ----
            sw = sector_of_flags(flags)
            bits = {RC_NONE: 0, RC_C: c[cx["cond"]], RC_SW: sw_q % 3, RC_SW1: (sw_q + 1) % 3,
                    RC_SNAP: snap_bits(flags),
                    RC_DPWM: (int(dpwm == fixed.DPWM_OFF) << 1) | int(dpwm == fixed.DPWM_MAX or
                                                                      (dpwm == fixed.DPWM_60 and not flags[F_DP60])),
                    RC_MERGE: (int(is_err) << 1) | int(is_ab or is_dq)}.get(cx["rc"], 0)
            n_rbits = bits if busy else 0
            n_cbit = c[cx["cond"]] if busy else 0
            # ---- next-step operand selection (nx: registered from the word before) ----
            ra = nx["ra"] | rbits_q
            assert ra < RAM_WORDS
            n_ram_q = ram[ra]
            if k and w["we"] and pred:
                assert w["wa"] != ra or not w["we"], f"step {k}: read and write of word {ra} together"
            asrc = nx["asrc"]
            sh = PSH[nx["psh"]]
            pv = p if self.prog.dsp else ser_prod
            if asrc == AS_PROD and k:
                assert pv is not None, f"step {k}: product read while the serial multiplier runs"
            n_aux = {AS_NONE: 0, AS_ROM: rom_q, AS_PROD: ((pv or 0) >> sh),
                     AS_IN: in_q, AS_SHR9: _sx(acc, W) >> 9, AS_SHR1: _sx(acc, W) >> 1, AS_Q: q,
                     AS_ANG: ang}.get(asrc, 0) & mask
            n_binv = {BINV_NO: 0, BINV_YES: 1, BINV_C: cbit_q, BINV_NSIGN: 1 - sign_q}[nx["binv"]]
            rbit = (((pv or 0) >> (sh - 1)) & 1) if (asrc == AS_PROD and sh) else 0
            n_cin = {CIN_0: 0, CIN_1: 1, CIN_BINV: n_binv, CIN_RND: rbit ^ n_binv}[nx["cin"]]
            # the input the word selects (the operand of the step after next), registered
            isel = w["isel"]
            n_in = (_sx(ins[isel], 16) if isel in IN_SIGNED else ins[isel] & 0xFFFF) & mask
            # ---- own fields ----
            n_acc = acc
            if k:
                n_acc = s if w["acc"] == ACC_SUM else acc
                if w["we"] and pred:
                    assert w["wa"] not in ZERO_WORDS
                    ram[w["wa"]] = acc
                    if w["wa"] == R_SNAP:                 # the command the minimum-pulse rule snaps
                        cmd = _sx(acc, W)
                # a flag set / Q shift takes the sign registered in its step one clock later
                if pend_f is not None:
                    flags[pend_f] = sign_q
                if pend_q:
                    q = ((q << 1) | (1 - sign_q)) & 0xFFFF
                pend_f = w["fidx"] if w["fset"] else None
                pend_q = w["qsh"]
                n_ma, n_mb = ma, mb
                if w["mla"]:
                    n_ma = sat16(acc if w["mas"] else b_val)
                if w["mlb"]:
                    n_mb = sat16({MB_B: b_val, MB_FR: ang & 0xFF, MB_ACC: acc}[w["mbs"]])
                n_ang, n_sec = ang, sec
                if w["ald"] and pred:
                    n_ang = acc & 0xFFFF
                if w["sec"] == SEC_THETA and pred:
                    n_sec = (acc >> 16) & 7
                elif w["sec"] == SEC_XYZ and pred:
                    n_sec = (sw_q + sec) % 6 if is_dq else sw_q
                elif w["sec"] == SEC_ERR and is_err:
                    n_sec = 0
                if w["out"]:
                    for ph in range(3):
                        if sel_class(sel[ph]) == w["out"]:
                            cmp[ph] = acc & ((1 << self.cw) - 1)
                            # the volt-second carry (fixed.snap_carry): command - snapped, limited to +-hthr
                            hthr = (inp["thr"] + 1) >> 1
                            e_out[ph] = max(-hthr, min(hthr, cmd - _sx(acc, W)))
                i = (ang_p >> 8) & 0xFF
                addr = {ROM_OFF: 0, ROM_I: i, ROM_I1: i + 1, ROM_N: 256 - i, ROM_N1: 255 - i}[w["rsel"]]
                n_rom = table[addr]
                # multiplier
                if self.prog.dsp:
                    p = ma * mb
                else:
                    if ser_left:
                        ser_left -= 1
                        if ser_left == 0:
                            ser_prod = ma * mb
                    if w["mlb"]:
                        assert ser_left == 0, f"step {k}: serial multiplier restarted while busy"
                        ser_left, ser_prod = 16, None
                    elif w["mla"]:
                        assert ser_left == 0, f"step {k}: MA changed while the serial multiplier runs"
                if w["done"]:
                    out = (sec, tuple(cmp), not flags[F_SATN], is_err)
                    self.e_out = tuple(e_out)
                ma, mb, ang_p, ang, sec_p, sec, rom_q = n_ma, n_mb, ang, n_ang, sec, n_sec, n_rom
            # (the start clock: ANG and the sector load the inputs, which the model holds from the start on;
            # ang_p / sec_p keep the state from before the start)
            if trace is not None:
                trace.append((k, _sx(acc, W), _sx(n_acc, W), a_val, _sx(b_val, W), cin_q))
            acc, ram_q, aux_q, binv_q, cin_q = n_acc, n_ram_q, n_aux, n_binv, n_cin
            a_q, nx, cx = self.split[k]
            rbits_q, cbit_q, in_q, sw_q, sign_q = n_rbits, n_cbit, n_in, sw, sign
        assert out is not None, "the program never signalled done"
        return out


# ---- the program -------------------------------------------------------------------------------------------
MODE_NOT_BUILT = 7             # the mode code a build gives the calculator for a mode it does not have


def inp_mode(inp: dict, features: int) -> int:
    """The mode the calculator of a build computes for inp["mode"]: the mode, or MODE_NOT_BUILT (the zero
    vector and err, like an invalid code) when the build lacks it; the tiny build reads no mode (FREQ)."""
    if features == config.TINY:
        return fixed.MODE_FREQ
    mode = inp.get("mode", 0)
    return mode if mode > fixed.MODE_DQ or config.mode_built(features, mode) else MODE_NOT_BUILT


def build(features: int = config.FULL, tiny: bool | None = None) -> Program:
    """The calculator's program for a build (config.py): per phase fixed.snap_min_pulse of fixed.modulate(...)
    in every input mode the build has; the parts of features it lacks are left out (the tiny program: FREQ
    mode, continuous SVPWM, no error path). Each part names the fixed.py function it computes."""
    f = features & config.CALC
    has = lambda n: config.has(f, n)                      # noqa: E731
    compact = features == config.TINY if tiny is None else tiny
    g = Builder(features, compact)
    dsp = g.dsp
    th_modes = config.has_theta(f)                        # theta_i -> sector, angle
    ang_modes = has("freq") or has("vf") or has("polar")  # the polar dwell times T1, T2 of (m, angle)
    xy_modes = config.has_xy(f)                           # X, Y, Z -> sector, dwell times
    sixstep = has("sixstep") and ang_modes
    shifted = has("dpwm") or has("dtc") or has("carry")   # C + sh + the compensation / carry
    def sines(sb_addr, sa_addr, tmp):
        """fixed.sines of the angle in ANG (i = ANG[15:8], fr = ANG[7:0]): sb = R[i] + round(e1 fr / 2^8),
        sa = R[256-i] - round(e2 fr / 2^8), e1 = R[i+1] - R[i], e2 = R[256-i] - R[255-i] (both >= 0)."""
        g.load(rom(ROM_I1))
        g.add(rom(ROM_I, inv=True))                           # e1
        r1 = g.mul("acc", "fr")
        g.load(rom(ROM_N))
        g.add(rom(ROM_N1, inv=True))                          # e2
        if dsp:
            # MA <- e2 and ACC <- R[i] in one step; the e1 product stays selectable for one more step
            t = g.e(rom(ROM_I), aen=0, mla=1, mas=1, mlb=1, mbs=MB_FR)
            r2 = t + g.mul_lat + 1
            assert r1 <= t + 1
            g.add(prod(PSH8))                                 # sb = R[i] + round(e1 fr >> 8)
            g.write(sb_addr)
            g.load(rom(ROM_N))
            g.wait(r2)
            g.add(prod(PSH8, sign="neg"))                     # sa = R[256-i] - round(e2 fr >> 8)
        else:
            g.write(tmp)                                      # e2 waits in RAM (the serial unit has e1 fr)
            g.wait(r1 - 1)
            g.load(rom(ROM_I))
            g.add(prod(PSH8))                                 # sb
            g.write(sb_addr)
            r2 = g.mul(ram(tmp), "fr")
            g.wait(r2 - 1)
            g.load(rom(ROM_N))
            g.add(prod(PSH8, sign="neg"))                     # sa
        g.write(sa_addr)

    if th_modes:
        # ---- POLAR / DQ: 6 theta = sector . a16 (fixed.theta_split) -> sector, ANG ------------------------
        g.load(inp(IN_THETA))
        g.add2(inp(IN_THETA))                                 # 3 theta
        g.add2(ram(R_ZERO))                                   # 6 theta
        g.put(g.t, ald=1, sec=SEC_THETA, pred=PRED_TH)        # from ACC at the start of the step
    if has("vf"):
        # ---- VF: m = min(m_max, boost + round(fa slope / 2^8)) (fixed.vf_m) -> S_M + 1; m_i -> S_M --------
        g.wait(3)                                             # fabs_i is valid from step 1 (read in t - 2)
        rv = g.mul(inp(IN_FABS), inp(IN_SLOPE))
        g.load(inp(IN_MMAX))
        g.write(S_VF0)                                        # {m_max, cand}
        g.load(inp(IN_M))
        g.write(S_M)
        g.wait(rv - 1)
        g.load(inp(IN_BOOST))
        g.add(prod(PSH8))                                     # cand
        g.write(S_VF1)
        g.cmp(inp(IN_MMAX, inv=True), F_VF)                   # cand - m_max < 0: cand, else m_max
        g.load(ram(S_VF0, rc=RC_C, ci=F_VF))
        g.write(S_M + 1)
    elif ang_modes:
        g.load(inp(IN_M))
        g.write(S_M)
    m_sel = ram(S_M, rc=RC_C, ci=C_VF) if has("vf") else ram(S_M)
    if sixstep:
        # ---- overmodulation gain (fixed.om_gain): g = 2^8 + 2 max(0, m - MV) (MV = 0xFFFF: g = 2^8) -> R_G ----
        g.load(m_sel)
        g.add(inp(IN_MV, inv=True), fset=1, fidx=F_S1)       # m - MV (F_S1: free until the minimum pulse)
        g.add2(ram(R_K256))                                  # 2 (m - MV) + 2^8
        g.write(R_A)                                         # {candidate, 2^8} (R_K256 = R_A + 1)
        g.load(ram(R_A, rc=RC_C, ci=F_S1))
        g.write(R_G)
    # ---- FREQ / VF / POLAR (and DQ's trig): sb, sa of theta' -> S_SB, S_SA ------------------------------
    if ang_modes or has("dq"):
        sines(S_SB, S_SA, S_VF1)
    if ang_modes:
        # ---- T1 = round(m sa / 2^15), T2 = round(m sb / 2^15) (fixed.duties) -> polar slots of R_T1, R_T2 ---
        r1 = g.mul(m_sel, ram(S_SA))
        if dsp:
            r2 = g.mb(ram(S_SB))
            g.wait(r1)
            g.load(prod(PSH15))                               # T1
            assert g.t == r2
            g.write(R_T1)
            g.load(prod(PSH15))                               # T2
        else:
            g.wait(r1)
            g.load(prod(PSH15))
            g.write(R_T1)
            r2 = g.mb(ram(S_SB))
            g.wait(r2)
            g.load(prod(PSH15))
        g.write(R_T2)
        g.hold()

    if xy_modes:
        # ---- AB / DQ: the signs of v1, v2 and |v1| -> R_A ----------------------------------------------------
        g.load(inp(IN_V1), fset=1, fidx=F_V1N)
        g.load(inp(IN_V2), fset=1, fidx=F_V2N)
        g.load(inp(IN_V1, binv=BINV_C, bci=F_V1N, cin=CIN_BINV))   # |v_alpha| (|v_d|)
        g.write(R_A)
    if has("ab"):
        # ---- AB: X = v_beta, Y = a + v_beta / 2, Z = v_beta / 2 - a, a = sqrt3/2 v_alpha (fixed.ab_dwell) ----
        ra_ = g.mul("acc", ram(R_SQ3))                        # |v_alpha| sqrt3/2
        g.load(inp(IN_V2))
        g.add2(ram(R_ZERO))                                   # h = v_beta << 1 (dwell units / 2)
        g.write(S_VF0)
        g.add2(ram(R_ZERO))                                   # X = v_beta << 2
        g.write(R_X, pred=PRED_AB)
        g.load(ram(S_VF0))
        g.wait(ra_)
        g.add(prod(PSH14, sign=F_V1N))                        # Y = h + a (sign-magnitude, fixed._mul_v)
        g.write(R_Y, pred=PRED_AB)
        g.load(ram(S_VF0))
        g.add(prod(PSH14, sign=C_NV1N))                       # Z = h - a
        g.write(R_Z, pred=PRED_AB)
    if has("dq"):
        # ---- DQ: inverse Park in theta's sector frame (fixed.dq_trig, fixed.dq_dwell) ------------------------
        g.load(aux(AS_ANG))
        g.add(ram(R_K32, inv=True), fset=1, fidx=F_HALF)      # a16 - 2^15 (F_HALF: theta' < 30 deg)
        g.write(S_VF1)
        g.load(ram(S_VF1, binv=BINV_C, bci=F_HALF, cin=CIN_BINV))   # u = |a16 - 2^15|
        g.put(g.t, ald=1)                                     # ANG <- u
        g.load(inp(IN_V2, binv=BINV_C, bci=F_V2N, cin=CIN_BINV))    # |v_q|
        g.write(S_VF1)
        sines(S_H, S_G, S_M)                                  # h = sin u, g = sin(60 - u)
        g.load(ram(S_G))
        g.add(ram(S_H))                                       # g + h
        g.write(R_GH + 1)
        g.cmp(ram(R_GH, inv=True), F_CAP)                     # g + h - 0xFFFF < 0: keep, else 0xFFFF
        g.load(ram(R_GH, rc=RC_C, ci=F_CAP))                  # gh = min(g + h, T_CAP)
        g.write(S_H)                                          # {g, gh}: ct = {..}[theta' < 30], c60 the other
        rx1 = g.mul(ram(R_A), ram(S_SB))                      # |v_d| sin theta'
        rx2 = g.mul(ram(S_VF1), ram(S_G, rc=RC_C, ci=F_HALF))  # |v_q| cos theta'
        g.wait(rx1)
        g.load(prod(PSH14, sign=F_V1N))
        g.wait(rx2)
        g.add(prod(PSH14, sign=F_V2N))                        # X = v_d sin t' + v_q cos t'
        g.write(R_X, pred=PRED_DQ)
        rz1 = g.mb(ram(S_G, rc=RC_C, ci=C_NHALF))             # |v_q| cos(60 - theta')
        rz2 = g.mul(ram(R_A), ram(S_SA))                      # |v_d| sin(60 - theta')
        g.wait(rz1)
        g.load(prod(PSH14, sign=F_V2N))
        g.wait(rz2)
        g.add(prod(PSH14, sign=C_NV1N))                       # Z = v_q cos(60 - t') - v_d sin(60 - t')
        g.write(R_Z, pred=PRED_DQ)
        g.load(ram(R_X))
        g.add(ram(R_Z, inv=True))                             # Y = X - Z
        g.write(R_Y, pred=PRED_DQ)
        g.hold()
    if xy_modes:
        # ---- sector and dwell times from X, Y, Z (fixed.xyz_sector) -> xyz slots of R_T1, R_T2 ------------
        for v, fn, fp, slot in ((R_X, F_NX, F_PX, 0), (R_Z, F_NZ, F_PZ, 1), (R_Y, F_NY, F_PY, 2)):
            g.load(ram(v), fset=1, fidx=fn)
            g.load(ram(v, inv=True), fset=1, fidx=fp)
            g.load(ram(v, binv=BINV_C, bci=fn, cin=CIN_BINV))  # |v|
            g.write(R_ABS + slot)
        g.load(ram(R_ABS, rc=RC_SW))                          # T2 = |q_s|
        g.put(g.t, sec=SEC_XYZ, pred=PRED_XY)
        g.write(R_T2 + 1, pred=PRED_XY)
        g.load(ram(R_ABS, rc=RC_SW1))                         # T1 = |q_{s+1}|
        g.write(R_T1 + 1, pred=PRED_XY)
        g.hold()
    if not compact:
        g.put(g.t, sec=SEC_ERR)                           # an invalid mode: sector 0, T1 = T2 = 0
    merge = dict(rc=RC_MERGE) if not compact else {}

    # ---- hexagon clamp (fixed.hex_clamp): s = T1 + T2 > 2^16: q = floor(min 2^16 / s), the other 2^16 - q -----
    g.load(ram(R_T1, **merge))
    g.write(S_VF1)                                        # {T2, T1} at S_VF0, S_VF0 + 1
    g.cmp(ram(R_T2, **merge, inv=True, cin=CIN_0), F_FIRST)   # T1 - T2 - 1 < 0: T1 <= T2 (first)
    g.load(ram(R_T2, **merge))
    g.write(S_VF0)
    g.add(ram(S_VF1))                                     # s
    g.write(R_S)
    g.cmp(ram(R_K64, inv=True, cin=CIN_0), F_SATN)        # s - 2^16 - 1 < 0: not saturated
    g.load(ram(S_VF0, rc=RC_C, ci=F_FIRST))               # min: T1 if first
    g.write(R_MIN + 1)
    g.load(ram(R_S))
    g.add(ram(R_MIN + 1, inv=True))                       # max = s - min
    g.write(R_MAX + 1)
    g.load(ram(R_MIN + 1))                                # remainder = min (< s)
    # 16 non-restoring steps: rem <- 2 rem -+ s by the sign of rem, quotient bit = new rem >= 0 (BINV_NSIGN
    # inverts by the registered sign of the step two before: a hold between the steps)
    g.add2(ram(R_S, inv=True), qsh=1)
    for _ in range(15):
        g.hold()
        g.add2(ram(R_S, binv=BINV_NSIGN, cin=CIN_BINV), qsh=1)
    if not dsp:
        g.load(aux(AS_Q))                                 # q
        g.write(R_MIN)
        g.load(ram(R_K64))
        g.add(aux(AS_Q, inv=True))                        # 2^16 - q
        g.write(R_MAX)
        if sixstep:                                       # six-step law (below: the same on the DSP)
            g.load(ram(R_K32))
            g.add(aux(AS_Q, inv=True))                    # d = 2^15 - q
            rg = g.mul("acc", ram(R_G))
            g.wait(rg - 1)
            g.load(ram(R_K32))
            g.add(prod(PSH8, sign="neg"), fset=1, fidx=F_S1)   # 2^15 - round(g d / 2^8)
            g.write(R_SNAP)                               # {q', 0} (R_SNAP + 1 is a zero word)
            g.load(ram(R_SNAP, rc=RC_C, ci=F_S1))         # q' (0 if negative)
            g.write(R_MIN)
            g.load(ram(R_K64))
            g.add(ram(R_MIN, inv=True))                   # 2^16 - q'
            g.write(R_MAX)
    # ---- compare values (fixed.dwell_compare): A = (T1 P) >> 8, B = (T2 P) >> 8, C = ((P+1) 2^8 +- ..) >> 9 --
    # lo = min or q, hi = max or 2^16 - q (capped at 0xFFFF by sat16); S = lo8 + hi8, Dm = hi8 - lo8
    def sum_diff():                                       # ACC = hi8, R_Y = lo8 -> R_A = S, R_Z = Dm
        g.write(R_Z)
        g.add(ram(R_Y))                                   # S
        g.write(R_A)
        g.load(ram(R_Z))
        g.add(ram(R_Y, inv=True))                         # Dm
        g.write(R_Z)

    if dsp:
        # six-step law (fixed.hex_clamp): q' = max(0, 2^15 - round(g (2^15 - q) / 2^8)) (g = 2^8: q' = q); the
        # products 2^8 P (the base), lo P and hi P follow on the multiplier with MB = P
        if sixstep:
            g.load(ram(R_K32))
            g.add(aux(AS_Q, inv=True))                    # d = 2^15 - q
            rg = g.mul("acc", ram(R_G))
            g.load(ram(R_K32))
            g.wait(rg)
            g.add(prod(PSH8, sign="neg"), fset=1, fidx=F_S1)   # 2^15 - round(g d / 2^8)
            g.write(R_SNAP)                               # {q', 0} (R_SNAP + 1 is a zero word)
            rb = g.mul(ram(R_K256), inp(IN_PERIOD))       # 2^8 P (in the flag's wait)
            g.load(ram(R_SNAP, rc=RC_C, ci=F_S1))         # q' (0 if negative)
        else:
            rb = g.mul(ram(R_K256), inp(IN_PERIOD))       # 2^8 P
            g.load(aux(AS_Q))                             # q
        g.write(R_MIN)
        g.wait(rb)
        g.load(prod(PSH0, rnd=False))                     # 2^8 P
        g.add(ram(R_K256))                                # base = (P + 1) 2^8
        g.write(R_P2H)                                    # (R_G: g is used; R_P2H free until the minimum pulse)
        g.load(ram(R_K64))
        g.add(ram(R_MIN, inv=True))                       # 2^16 - q'
        g.write(R_MAX)
        tl = g.e(ram(R_MIN, rc=RC_C, ci=F_SATN), mla=1, mas=0, aen=1, acc=ACC_HOLD)
        th = g.e(ram(R_MAX, rc=RC_C, ci=F_SATN), mla=1, mas=0, aen=1, acc=ACC_HOLD)
        g.wait(tl + g.mul_lat + 1)
        g.load(prod(PSH8, rnd=False))                     # lo8
        g.write(R_Y)
        g.wait(th + g.mul_lat + 1)                        # (the lo product stays selectable until then)
        g.load(prod(PSH8, rnd=False))                     # hi8
        sum_diff()
        r_base = R_P2H
    else:
        rl = g.mul(ram(R_MIN, rc=RC_C, ci=F_SATN), inp(IN_PERIOD))
        g.wait(rl)
        g.load(prod(PSH8, rnd=False))
        g.write(R_Y)
        rh = g.mul(ram(R_MAX, rc=RC_C, ci=F_SATN), inp(IN_PERIOD))
        g.wait(rh)
        g.load(prod(PSH8, rnd=False))                     # hi8
        sum_diff()
        # (P + 1) 2^8
        g.load(inp(IN_PERIOD))
        for _ in range(8):
            g.add2(ram(R_ZERO))
        g.add(ram(R_K256))
        g.write(R_Y)                                      # base
        r_base = R_Y
    # hi = (base + S) >> 9, lo = (base - S) >> 9, mid = (base +- Dm) >> 9
    res = []
    for k, bb in ((OUT_HI, ram(R_A)), (OUT_LO, ram(R_A, inv=True)),
                  (OUT_MID, ram(R_Z, binv=BINV_C, bci=C_MIDSGN, cin=CIN_BINV))):
        g.load(ram(r_base))
        g.add(bb)
        g.load(aux(AS_SHR9))
        addr = {OUT_HI: R_ABS, OUT_LO: R_ABS + 1, OUT_MID: R_ABS + 2}[k]
        g.write(addr)
        res.append((k, addr))
    # ---- zero-vector placement (fixed.dpwm_shift): every C + sh, and the dead-time compensation
    # (fixed.dtc_shift): + hdf for a negative current, - hdr otherwise (the phase of each class by its sign) ---
    if has("dpwm"):
        g.cmp(inp(IN_PERIOD, inv=True, cin=CIN_0), F_DP60, shift=True)   # 2 mid - P - 1 < 0: 2 mid <= P
        g.load(inp(IN_PERIOD))
        g.add(ram(R_ABS, inv=True))                       # P - hi
        g.write(R_DP)
        g.load(ram(R_ABS + 1, inv=True))                  # -lo
        g.write(R_DP + 1)
        g.load(ram(R_DP, rc=RC_DPWM))                     # sh
        g.write(R_A)
    # ---- minimum pulse (fixed.snap_min_pulse), thr = dt + mp: 0 / thr below thr, P / P - hthr near P ------
    g.load(inp(IN_THR))
    g.write(R_SNAP + 2)                                   # thr
    g.add(ram(R_ZERO, cin=CIN_1))                         # thr + 1
    g.load(aux(AS_SHR1))                                  # hthr = (thr + 1) >> 1
    g.write(S_VF0)
    g.load(inp(IN_PERIOD))
    g.write(R_SNAP + 3)                                   # P
    g.add(ram(S_VF0, inv=True))                           # P - hthr
    g.write(R_SNAP + 4)
    g.add(inp(IN_PERIOD))                                 # 2P - hthr
    g.write(R_P2H)
    def shift(k, addr):                                   # C + sh + the compensation of class k -> ACC
        g.load(ram(addr))
        if has("dpwm"):
            g.add(ram(R_A))
        if has("dtc") or has("carry"):
            g.add(inp({OUT_HI: IN_DHI, OUT_LO: IN_DLO, OUT_MID: IN_DMID}[k]))

    if shifted:
        shift(*res[0])
    for i, (k, addr) in enumerate(res):
        if not shifted:
            g.load(ram(addr))
        g.write(R_SNAP)                                   # c
        g.cmp(inp(IN_THR, inv=True), F_S1)                # c - thr < 0
        g.cmp(inp(IN_THR, inv=True), F_S2, shift=True)    # 2c - thr < 0
        g.cmp(ram(R_SNAP + 4, inv=True, cin=CIN_0), F_S3)  # c - (P - hthr) - 1 < 0: not c > P - hthr
        g.cmp(ram(R_P2H, inv=True, cin=CIN_0), F_S4, shift=True)
        nxt = shifted and i + 1 < len(res)
        if nxt:                                           # the next class's shift while the flags settle
            shift(*res[i + 1])
            g.write(res[i + 1][1])
        g.load(ram(R_SNAP, rc=RC_SNAP))
        g.put(g.t, out=k)
        if nxt:
            g.load(ram(res[i + 1][1]))
    g.hold(done=1)
    return g.p


_CACHE: dict = {}


def program(features: int = config.FULL) -> Program:
    """The program of a build (its calculator features: config.CALC; the tiny build's own)."""
    key = (features == config.TINY, features & config.CALC)
    if key not in _CACHE:
        _CACHE[key] = build(features if key[0] else key[1], tiny=key[0])
    return _CACHE[key]


def program_key(features: int) -> int:
    """The calculator bits of a build (config.CALC): the builds of one key run one program (not the tiny
    build: TRANSITIONAL, its core runs rtl/svpwm_duty_lite.sv)."""
    return features & config.CALC


def calc_latency(features: int = config.FULL) -> int:
    """Clocks from svpwm_calc start_i to done_o of a build's program."""
    return program(features).latency


# the fields whose used values svpwm_pkg lists per program (svpwm_calc builds only those arms)
USED_FIELDS = ("src", "isel", "psh", "rc", "flag", "sec", "pred", "binv", "cin", "cond")


def used_values(features: int) -> dict[str, int]:
    """Per field of USED_FIELDS, a mask of the values the build's program uses: src (asrc), isel (of the
    steps whose B is an input), psh (of the product steps), rc, flag (the flags set), sec, pred, binv, cin,
    cond (the conditions read by RC_C or BINV_C). A value outside it never reaches svpwm_calc's decode."""
    st = program(features).steps
    vals: dict[str, set] = {
        "src": {s["asrc"] for s in st if "asrc" in s},
        "isel": {s["isel"] for s in st if s.get("asrc") == AS_IN},
        "psh": {s["psh"] for s in st if s.get("asrc") == AS_PROD},
        "rc": {s.get("rc", RC_NONE) for s in st},
        "flag": {s["fidx"] for s in st if s.get("fset")},
        "sec": {s["sec"] for s in st if s.get("sec")},
        "pred": {s.get("pred", PRED_ALL) for s in st},
        "binv": {s.get("binv", BINV_NO) for s in st},
        "cin": {s.get("cin", CIN_0) for s in st},
        "cond": {s["ci"] for s in st if s.get("rc") == RC_C} | {s["bci"] for s in st if s.get("binv") == BINV_C},
    }
    for k in ("src", "psh", "rc", "sec", "pred", "binv", "cin"):
        vals[k] |= {0}                      # the default arm (no operand selection, no condition)
    return {k: sum(1 << v for v in vs) for k, vs in vals.items()}


def expect(inp: dict, features: int = config.FULL) -> tuple[int, tuple[int, int, int], bool, bool]:
    """What the calculator must return: fixed.modulate + fixed.snap_min_pulse per phase."""
    return expect_carry(inp, features)[:4]


def expect_carry(inp: dict, features: int = config.FULL) -> tuple[int, tuple[int, int, int], bool, bool,
                                                                   tuple[int, int, int]]:
    """expect() and the volt-second carry out of each phase (fixed.snap_carry; inp["carry"]: the carry in).
    The inputs of features the build lacks are not read (a mode it lacks: the zero vector and err)."""
    P, thr = inp["period"], inp["thr"]
    has = lambda n: config.has(features, n)               # noqa: E731
    sector, c, sat, err = fixed.modulate(
        inp_mode(inp, features), inp.get("sector", 0), inp.get("a16", 0), P, freq=inp.get("freq", 0),
        m=inp.get("m", 0), theta=inp.get("theta", 0), v1=inp.get("v1", 0), v2=inp.get("v2", 0),
        vf_boost=inp.get("vf_boost", 0), vf_slope=inp.get("vf_slope", 0), vf_mmax=inp.get("vf_mmax", 0),
        dpwm=inp.get("dpwm", 0) if has("dpwm") else 0, isign=inp.get("isign", 0) & 7 if has("dtc") else 0,
        hdr=inp.get("hdr", 0) if has("dtc") else 0, hdf=inp.get("hdf", 0) if has("dtc") else 0,
        om=inp.get("om", 0) if has("sixstep") else 0,
        carry=tuple(inp.get("carry", (0, 0, 0))) if has("carry") else (0, 0, 0))
    sc = [fixed.snap_carry(x, P, thr) for x in c]
    return sector, tuple(x for x, _ in sc), sat, err, tuple(e for _, e in sc)
