# SPDX-License-Identifier: Apache-2.0
"""The seeds' tables transcribed as data (shared/seeds/*.txt), faithfully, errors included.

Conventions of this module:

* sectors are indexed 0..5 (= the seeds' sectors 1..6);
* a switching state is a tuple of three bits (a, b, c) = (R, Y, B) = (S_a+, S_b+, S_c+), 1 = upper switch on,
  written MSB first like the binary numbers of Minas Table I ("100" = phase a on);
* voltages are in units of E = Udc (AVR495) / Vdc (Verma).

Where a printed entry is wrong (it contradicts the seed's own formulas and the other seeds) it is kept as
printed here and the corrected value is listed in an ``*_ERRATA`` dict beside the table, so the tests can
show both facts: the printed value differs, the corrected one follows from the equations.
"""
from __future__ import annotations

import math

State = tuple[int, int, int]

_S3 = math.sqrt(3.0)

# ---- Minas, Martins, Couto, Table I "State sequence within a reference period" -----------------------
# Sector (code index) -> the 7 states of one carrier period, centre-aligned: zero vector 000 at both ends,
# 111 in the middle, one leg switching per transition.  Seed's sectors 1..6 cover alpha = 0-60, 60-120, ...
MINAS_TABLE_I: tuple[tuple[State, ...], ...] = (
    # 1: 0 -> 60 deg      000 -> 100 -> 110 -> 111 -> 110 -> 100 -> 000
    ((0, 0, 0), (1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 1, 0), (1, 0, 0), (0, 0, 0)),
    # 2: 60 -> 120 deg    000 -> 010 -> 110 -> 111 -> 110 -> 010 -> 000
    ((0, 0, 0), (0, 1, 0), (1, 1, 0), (1, 1, 1), (1, 1, 0), (0, 1, 0), (0, 0, 0)),
    # 3: 120 -> 180 deg   000 -> 010 -> 011 -> 111 -> 011 -> 010 -> 000
    ((0, 0, 0), (0, 1, 0), (0, 1, 1), (1, 1, 1), (0, 1, 1), (0, 1, 0), (0, 0, 0)),
    # 4: 180 -> 240 deg   000 -> 001 -> 011 -> 111 -> 011 -> 001 -> 000
    ((0, 0, 0), (0, 0, 1), (0, 1, 1), (1, 1, 1), (0, 1, 1), (0, 0, 1), (0, 0, 0)),
    # 5: 240 -> 300 deg   000 -> 001 -> 101 -> 111 -> 101 -> 001 -> 000
    ((0, 0, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (1, 0, 1), (0, 0, 1), (0, 0, 0)),
    # 6: 300 -> 360 deg   000 -> 100 -> 101 -> 111 -> 101 -> 100 -> 000
    ((0, 0, 0), (1, 0, 0), (1, 0, 1), (1, 1, 1), (1, 0, 1), (1, 0, 0), (0, 0, 0)),
)

# ---- Atmel AVR495, Table 4-1 "Switching configurations and output voltages of a 3-phase inverter" ----
# state (S_a+, S_b+, S_c+) -> row, voltages in units of E.  alpha/beta use the seed's (unscaled) Concordia
# matrix [[1, -1/2, -1/2], [0, sqrt3/2, -sqrt3/2]] applied to (V_an, V_bn, V_cn): |active vector| = E.
AVR495_TABLE_4_1: dict[State, dict[str, object]] = {
    (0, 0, 0): dict(S="S0", Vab=0.0, Vbc=0.0, Vca=0.0, Van=0.0, Vbn=0.0, Vcn=0.0,
                    alpha=0.0, beta=0.0, V="V0"),
    (0, 0, 1): dict(S="S1", Vab=0.0, Vbc=-1.0, Vca=1.0, Van=-1 / 3, Vbn=-1 / 3, Vcn=2 / 3,
                    alpha=-1 / 2, beta=-_S3 / 2, V="V5"),
    (0, 1, 0): dict(S="S2", Vab=-1.0, Vbc=1.0, Vca=0.0, Van=-1 / 3, Vbn=2 / 3, Vcn=-1 / 3,
                    alpha=-1 / 2, beta=_S3 / 2, V="V3"),
    # printed as: -E 0 E | -2E/3 -E/3 -E/3 | -E 0  (V_bn, V_cn signs wrong, see errata)
    (0, 1, 1): dict(S="S3", Vab=-1.0, Vbc=0.0, Vca=1.0, Van=-2 / 3, Vbn=-1 / 3, Vcn=-1 / 3,
                    alpha=-1.0, beta=0.0, V="V4"),
    (1, 0, 0): dict(S="S4", Vab=1.0, Vbc=0.0, Vca=-1.0, Van=2 / 3, Vbn=-1 / 3, Vcn=-1 / 3,
                    alpha=1.0, beta=0.0, V="V1"),
    (1, 0, 1): dict(S="S5", Vab=1.0, Vbc=-1.0, Vca=0.0, Van=1 / 3, Vbn=-2 / 3, Vcn=1 / 3,
                    alpha=1 / 2, beta=-_S3 / 2, V="V6"),
    (1, 1, 0): dict(S="S6", Vab=0.0, Vbc=1.0, Vca=-1.0, Van=1 / 3, Vbn=1 / 3, Vcn=-2 / 3,
                    alpha=1 / 2, beta=_S3 / 2, V="V2"),
    (1, 1, 1): dict(S="S7", Vab=0.0, Vbc=0.0, Vca=0.0, Van=0.0, Vbn=0.0, Vcn=0.0,
                    alpha=0.0, beta=0.0, V="V7"),
}
# Fact: row S3 (011) prints V_bn = V_cn = -E/3.  The phase voltages then sum to -4E/3 (must be 0 with an
# isolated neutral), contradict the seed's own V_bn = (V_bc - V_ab)/3 = +E/3, V_cn = (V_ca - V_bc)/3 = +E/3,
# and contradict the row's own V_alpha = -E (= V_an - V_bn/2 - V_cn/2 only with +E/3, +E/3).
# Verma Table 1 row 4 (011) prints +1/3, +1/3.
AVR495_TABLE_4_1_ERRATA: dict[State, dict[str, float]] = {
    (0, 1, 1): dict(Vbn=1 / 3, Vcn=1 / 3),
}
# Fact: the text says V_k = E e^{j(k-1)2pi/3}, k = 1..6; the table's alpha/beta (V1 at 0 deg, V2 at 60 deg,
# ..., V6 at 300 deg) need e^{j(k-1)pi/3}.  The table is taken as right (the hexagon has 60 deg steps).

# ---- Atmel AVR495, Table 4-2 "Expressions of the duty cycles in each sector" --------------------------
# sector -> ((offset_k, sign_k), (offset_k1, sign_k1)): d_k = m sin(offset_k + sign_k*theta),
# d_k+1 = m sin(offset_k1 + sign_k1*theta), with the FULL angle theta (not theta') and
# m = 2/sqrt3 * V_s/E (the seed's prefactor; equals the project's m).
_P = math.pi
AVR495_TABLE_4_2: tuple[tuple[tuple[float, int], tuple[float, int]], ...] = (
    ((_P / 3, -1), (0.0, +1)),              # 1 [0, pi/3]:       sin(pi/3 - th),  sin(th)
    ((_P / 3, +1), (5 * _P / 3, +1)),       # 2 [pi/3, 2pi/3]:   sin(pi/3 + th),  sin(5pi/3 + th)
    ((0.0, +1), (4 * _P / 3, +1)),          # 3 [2pi/3, pi]:     sin(th),         sin(4pi/3 + th)
    ((5 * _P / 3, +1), (2 * _P, -1)),       # 4 [pi, 4pi/3]:     sin(5pi/3 + th), sin(2pi - th)
    ((4 * _P / 3, +1), (2 * _P / 3, +1)),   # 5 [4pi/3, 5pi/3]:  sin(4pi/3 + th), sin(2pi/3 + th)
    ((2 * _P, -1), (_P / 3, +1)),           # 6 [5pi/3, 2pi]:    sin(2pi - th),   sin(pi/3 + th)
)

# ---- Atmel AVR495, Table 4-3 "Compare Register Values vs Sector Number" -------------------------------
# sector -> per phase (a, b, c) the coefficient pair (c_a, c_b) of  4/Ts * C_x - 1 = c_a*d_a + c_b*d_b,
# i.e. C_x = Ts/4 * (1 + k) = P/2 * (1 + c_a*d_a + c_b*d_b), P = Ts/2 = the counter's top (half carrier
# period); the counter runs 0..P..0 and a phase is high while counter >= C_x: high fraction (1 - k)/2.
AVR495_TABLE_4_3: tuple[tuple[tuple[int, int], ...], ...] = (
    ((-1, -1), (+1, -1), (+1, +1)),   # 1:  -da-db   da-db   da+db
    ((-1, +1), (-1, -1), (+1, +1)),   # 2:  -da+db  -da-db   da+db
    ((+1, +1), (-1, -1), (+1, -1)),   # 3:   da+db  -da-db   da-db
    ((+1, +1), (-1, +1), (-1, -1)),   # 4:   da+db  -da+db  -da-db
    ((+1, -1), (+1, +1), (-1, -1)),   # 5:   da-db   da+db  -da-db
    ((-1, -1), (+1, +1), (-1, +1)),   # 6:  -da-db   da+db  -da+db
)

# ---- Verma, Dhingra, Soni, Table 1 "Switching combination showing Line-Line and Line-neutral ..." -----
# (R, Y, B) -> (VRN, VYN, VBN, VRY, VYB, VBR, Mag, Ang_deg), voltages in units of Vdc, Mag in units of the
# active-vector length ("the lengths of vectors V1..V6 are unity"), i.e. |alpha + j beta| of AVR495's
# Concordia in units of Vdc.  Column headers print as "YRN", "YRY" (for VRN, VRY).  S.No. 1..8 in order.
VERMA_TABLE_1: dict[State, tuple[float, float, float, float, float, float, float, float]] = {
    (0, 0, 0): (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0),                     # 1
    (0, 0, 1): (-1 / 3, -1 / 3, 2 / 3, 0.0, -1.0, 1.0, 0.999, -120.0),       # 2
    (0, 1, 0): (-1 / 3, 2 / 3, -1 / 3, -1.0, 1.0, 0.0, 0.999, 120.0),        # 3
    (0, 1, 1): (-2 / 3, 1 / 3, 1 / 3, -1.0, 0.0, 1.0, 1.0, 180.0),           # 4
    (1, 0, 0): (2 / 3, -1 / 3, -1 / 3, 1.0, 0.0, -1.0, 1.0, 0.0),            # 5
    # printed VBN = -1/3 (see errata)
    (1, 0, 1): (1 / 3, -2 / 3, -1 / 3, 1.0, -1.0, 0.0, 0.999, -60.0),        # 6
    (1, 1, 0): (1 / 3, 1 / 3, -2 / 3, 0.0, 1.0, -1.0, 0.999, 60.0),          # 7
    (1, 1, 1): (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0),                     # 8
}
VERMA_COLUMNS = ("VRN", "VYN", "VBN", "VRY", "VYB", "VBR", "Mag", "Ang")
# Fact: row 6 (101) prints VBN = -1/3; the phase voltages then sum to -2/3 (must be 0), and
# VBN = B - (R+Y+B)/3 = 1 - 2/3 = +1/3.  AVR495 Table 4-1 row S5 (101) prints V_cn = +E/3.
VERMA_TABLE_1_ERRATA: dict[State, dict[str, float]] = {
    (1, 0, 1): dict(VBN=1 / 3),
}
# Facts about Verma's Table 1 that are rounding, not errors:
# * Mag prints 0.999 for the four active vectors at +-60/+-120 deg and 1 for those at 0/180 deg: |1/2 +
#   j 0.866| truncated to three decimals; all six have length exactly 1.  Compare with tolerance >= 1e-3.
# * Ang prints -120 and -60 deg where AVR495 Table 4-1 puts V5 at 240 deg and V6 at 300 deg: the same
#   angles modulo 360 deg (no sign disagreement once taken modulo 360).
# Facts about Verma's equations (2) (text, not the table): V_Yn = (V_RY - V_BY)/3 and V_Bn = (V_BY - V_BR)/3
# as printed give +1/3 for state 100 where Table 1 (and V_Yn = (V_YB - V_RY)/3, V_Bn = (V_BR - V_YB)/3)
# give -1/3; eq. (5) prints a 1/(3 Vdc) prefactor where Vdc/3 is meant.
