// SPDX-License-Identifier: Apache-2.0
// deadtime: dead-time insertion for one inverter leg, pole state -> high-side and low-side gates.
// A gate turns off on the clock after its pole request goes away; the other gate turns on only after
// both gates have been off for its edge's dead time (the WFG dead-time generator of Minas sec. III-A):
// the high side dt_i clocks after the low side turned off (the rising-edge delay), the low side dtf_i
// clocks after the high side turned off (the falling-edge delay; gate drivers whose turn-off delays
// differ). Every gate on-pulse lasts at least max(dt_i, dtf_i, mp_i) clocks (a gate turned on is held
// until then), and every off-gap between two on-pulses of the same gate lasts at least its own turn-on
// dead time, so no runt pulse reaches a gate. (svpwm_calc's minimum-pulse rule already keeps the pole
// pulses long enough; this is the last-stage guarantee.)
// en_i low turns both gates off on the next clock, whatever the state (safety before pulse length).
// Reset turns both gates off and counts as a turn-off of unknown dead time: the dead-time registers
// that fed this leg before the reset are cleared by it too, so after the release no gate turns on
// before the counter has saturated, 2^DtWidth - 1 clocks (the longest dead time any configuration can
// hold): a gate turns on at the earliest in the 2^DtWidth-th clock after the release (rst_hold_q).
// brake_i (active braking, the trip safe state "low sides on"): the high side turns off on the next
// clock, the low side turns on once both have been off for dtf_i -- braking never skips the dead time.
// A zero dead time for an edge: that edge's gate turns on in the clock the other turns off (no dead
// time, still never both on).
// dt_i, dtf_i and mp_i are read ONE CLOCK AHEAD: the values on the ports in clock n are in force in
// clock n + 1 (svpwm_core passes its dead-time registers, so a new dead time reaches the legs one clock
// after the valley). The module compares its counter with them a clock early, so its decision reads only
// flip-flops ("held" flags, not a 10-bit compare). In the first clock after reset no gate turns on
// (nothing is held yet, whatever the dead times).
// Timing: en_i, brake_i and pole_i arrive late in svpwm_core, so they only select between next states
// formed from registers (en_i in the last LUT, brake_i / pole_i in the two last), and no counter or
// flag register depends on them: the counter and its compares run a clock behind the decision for both
// outcomes (the gates changed in the last clock or not) and a registered "changed" bit selects.
// The reset hold of legs reset together is the same (their counters run alike until the hold ends), so
// svpwm_core builds it once: leg a computes it (HoldIn = 0, hold_o), legs b and c take it (hold_i).
// Parameters: DtWidth - dead-time / minimum-pulse width in bits (max 2^DtWidth - 1 clocks).
//             HoldIn  - 0: the reset hold from this leg's counter (rst_hold_q); 1: from hold_i, the hold_o
//                       of a leg with the same clock and reset and HoldIn = 0.
// Latency: one clock from pole_i to a turn-off, 1 + dt (high side) / 1 + dtf (low side) clocks to the
// complementary turn-on (the dead times in force).
// Model: model/svpwm_model/deadtime.py (step_cycle, simulate_events).
`default_nettype none

module deadtime #(
  parameter int DtWidth = 10,
  parameter bit HoldIn  = 1'b0
) (
  input  logic               clk_i,    // core clock
  input  logic               rst_ni,   // asynchronous reset, active low (both gates off)
  input  logic               en_i,     // 0: both gates off (next clock)
  input  logic               brake_i,  // 1: low side wanted regardless of pole_i, high side off at once
  input  logic               pole_i,   // 1: high side wanted, 0: low side wanted
  input  logic [DtWidth-1:0] dt_i,     // rising dead time (low off -> high on), clocks, from the NEXT clock
  input  logic [DtWidth-1:0] dtf_i,    // falling dead time (high off -> low on), clocks, next clock
  input  logic [DtWidth-1:0] mp_i,     // minimum on-pulse in clocks (on-time >= max(dt, dtf, mp)), next clock
  input  logic               hold_i,   // HoldIn = 1: the reset hold of the next clock (another leg's hold_o)
  output logic               hold_o,   // the reset hold of the next clock (nothing turns on while high)
  output logic               hi_o,     // high-side gate (registered), 1 = on
  output logic               lo_o      // low-side gate (registered), 1 = on
);

  if (DtWidth < 1 || DtWidth > 16) begin : gen_bad_width
`ifdef __ICARUS__  // Icarus 11 has no elaboration-time tasks: at time 0
    initial $fatal(1, "deadtime: DtWidth must be 1..16, got %0d (%m)", DtWidth);
`else              // at elaboration (Yosys formats $display only, then stops at $error)
    initial $display("deadtime: DtWidth must be 1..16, got %0d (%m)", DtWidth);
    $error("deadtime: DtWidth must be 1..16, got %0d", DtWidth);
`endif
  end

  // cnt = clocks the gate state has been unchanged, this one included (saturating at 2^DtWidth - 1;
  // 0 only in the clock after reset); cnt1 = min(cnt + 1, 2^DtWidth - 1), the count the NEXT clock has
  // if the state stays. Nothing of the counter and the flags waits for the late inputs: the counter and
  // the compares run one clock behind the decision, for both cases (the gates change in this clock or
  // stay), and chg_q (the last clock changed the gates) selects in the next clock.
  //   ncnt1_q: ~cnt1 unless the last clock changed the gates (then cnt1 = 2): a down-counter saturating
  //   at 0, so that dt <= cnt1 is the carry-out of dt + ncnt1_q, a plain adder chain without inverters.
  //   held_r = cnt >= dt and cnt >= 1 (off long enough for the high side): after a change cnt = 1, so
  //   held_r = (the last clock's dt <= 1), dtr_le1_q; else held_r_stay_q, the last clock's dt <= cnt1.
  //   held_f the same for dtf (the low side). held_on = cnt >= max(dt, dtf, mp, 1) (a gate on may turn
  //   off: minimum on-time served), the three compares ANDed a clock ahead (on_le1_q, held_on_stay_q).
  localparam logic [DtWidth-1:0] CntMax   = '1;
  localparam logic [DtWidth-1:0] Cnt1Rst  = DtWidth'(1);                                // cnt1 after reset
  localparam logic [DtWidth-1:0] Cnt1Chg  = (DtWidth > 1) ? DtWidth'(2) : DtWidth'(1);  // cnt1 after a change
  localparam logic [DtWidth-1:0] Cnt1Chg2 = (Cnt1Chg == CntMax) ? Cnt1Chg : Cnt1Chg + 1'b1;  // a clock later

  logic               hi_d, hi_q, lo_d, lo_q;
  logic               chg_d, chg_q;            // the gates change in this clock / changed in the last
  logic [DtWidth-1:0] ncnt1_d, ncnt1_q;        // ~cnt1 if the last clock did not change the gates
  logic               held_r_stay_d, held_r_stay_q, held_f_stay_d, held_f_stay_q;
  logic               held_on_stay_d, held_on_stay_q, mp_stay;
  logic               dtr_le1_d, dtr_le1_q, dtf_le1_d, dtf_le1_q, on_le1_d, on_le1_q;
  logic               dtzr_d, dtzr_q, dtzf_d, dtzf_q;  // dt / dtf == 0 (a gate swaps straight to the other)
  logic               rst_hold_d, rst_hold_q;  // since reset the counter has not saturated (nothing turns on)
  logic               held_r, held_f, held_on;
  logic [DtWidth:0]   dtr_sum, dtf_sum, mp_sum;

  logic [DtWidth:0]   ncnt1_dec;               // {borrow, ncnt1_q - 1}: borrow = (ncnt1_q == 0), saturated
  logic               cnt_sat;
  assign ncnt1_dec      = {1'b0, ncnt1_q} - 1'b1;
  assign cnt_sat        = ncnt1_dec[DtWidth];
  assign ncnt1_d        = chg_q ? ~Cnt1Chg2 : cnt_sat ? ncnt1_q : ncnt1_dec[DtWidth-1:0];
  assign dtr_sum        = {1'b0, dt_i} + {1'b0, ncnt1_q};       // no carry-out: dt <= ~ncnt1_q
  assign dtf_sum        = {1'b0, dtf_i} + {1'b0, ncnt1_q};
  assign mp_sum         = {1'b0, mp_i} + {1'b0, ncnt1_q};
  assign dtr_le1_d      = (dt_i >> 1) == '0;
  assign dtf_le1_d      = (dtf_i >> 1) == '0;
  assign on_le1_d       = dtr_le1_d && dtf_le1_d && (mp_i >> 1) == '0;
  // x <= cnt1; after a change x <= 2 (written as == compares: a <= with a constant becomes a carry chain)
  // after a reset nothing is held until the next clock's count is CntMax (ncnt1_q == 0); both gates
  // stay off meanwhile (nothing held: no change), so the count runs 0, 1, .. CntMax undisturbed
  if (HoldIn) begin : gen_hold_in
    assign rst_hold_d   = hold_i;
  end else begin : gen_hold_own
    assign rst_hold_d   = rst_hold_q && !cnt_sat;
  end
  assign hold_o         = rst_hold_d;
  assign held_r_stay_d  = !rst_hold_d && (chg_q ? (dtr_le1_d || dt_i == Cnt1Chg) : !dtr_sum[DtWidth]);
  assign held_f_stay_d  = !rst_hold_d && (chg_q ? (dtf_le1_d || dtf_i == Cnt1Chg) : !dtf_sum[DtWidth]);
  assign mp_stay        = chg_q ? ((mp_i >> 1) == '0 || mp_i == Cnt1Chg) : !mp_sum[DtWidth];
  assign held_on_stay_d = held_r_stay_d && held_f_stay_d && mp_stay;
  assign dtzr_d         = (dt_i == '0);
  assign dtzf_d         = (dtf_i == '0);
  assign held_r         = chg_q ? dtr_le1_q : held_r_stay_q;
  assign held_f         = chg_q ? dtf_le1_q : held_f_stay_q;
  assign held_on        = chg_q ? on_le1_q : held_on_stay_q;

  // The next gates for each target, from registered state only; the late inputs (en_i, brake_i,
  // pole_i) only select between the four (a Shannon split on them, en_i last). Target HI (pole_i high):
  // a low side on turns off once its minimum on-time is served (a swap if dt == 0), with both off the
  // high side turns on once the rising dead time is served; LO the mirror image with the falling dead
  // time (a swap if dtf == 0); BRAKE: the high side turns off at once (a swap if dtf == 0), the low side
  // turns on after the falling dead time; OFF (en_i low): both off.
  logic hi_hi, lo_hi, hi_lo, lo_lo, lo_brk, off, chg_off, chg_brk, chg_hi, chg_lo;
  assign off     = !hi_q && !lo_q;
  assign hi_hi   = hi_q || (lo_q ? (held_on && dtzr_q) : held_r);
  assign lo_hi   = lo_q && !held_on;
  assign hi_lo   = hi_q && !held_on;
  assign lo_lo   = lo_q || (hi_q ? (held_on && dtzf_q) : held_f);
  assign lo_brk  = lo_q || (hi_q ? dtzf_q : held_f);
  assign chg_off = !off;
  assign chg_brk = hi_q || (off && held_f);
  assign chg_hi  = (lo_q && held_on) || (off && held_r);
  assign chg_lo  = (hi_q && held_on) || (off && held_f);

  // {hi, lo, change} of the next clock for each target, and the selection as two LUT-sized terms and
  // an en_i mux: pole_i / brake_i pass 2 LUT levels, en_i one (a plain if / else chain would put en_i
  // behind a 5-input function)
  logic [2:0] nx_brk, nx_hi, nx_lo, nx_off, sel_pole, sel_brk, nx;
  assign nx_off   = {1'b0, 1'b0, chg_off};
  assign nx_brk   = {1'b0, lo_brk, chg_brk};
  assign nx_hi    = {hi_hi, lo_hi, chg_hi};
  assign nx_lo    = {hi_lo, lo_lo, chg_lo};
  assign sel_pole = brake_i ? 3'b0 : pole_i ? nx_hi : nx_lo;
  assign sel_brk  = brake_i ? nx_brk : 3'b0;
  assign nx       = en_i ? (sel_pole | sel_brk) : nx_off;
  assign {hi_d, lo_d, chg_d} = nx;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      hi_q           <= 1'b0;
      lo_q           <= 1'b0;
      chg_q          <= 1'b0;
      ncnt1_q        <= ~Cnt1Rst;      // cnt = 0: a reset is a turn-off, the dead time runs from its release
      held_r_stay_q  <= 1'b0;          // nothing held in the first clock (cnt = 0)
      held_f_stay_q  <= 1'b0;
      held_on_stay_q <= 1'b0;
      dtr_le1_q      <= 1'b0;          // (read only after a change)
      dtf_le1_q      <= 1'b0;
      on_le1_q       <= 1'b0;
      dtzr_q         <= 1'b0;          // (read only while a gate is on)
      dtzf_q         <= 1'b0;
      rst_hold_q     <= 1'b1;          // a reset: no turn-on before the count saturates
    end else begin
      hi_q           <= hi_d;
      lo_q           <= lo_d;
      chg_q          <= chg_d;
      ncnt1_q        <= ncnt1_d;
      held_r_stay_q  <= held_r_stay_d;
      held_f_stay_q  <= held_f_stay_d;
      held_on_stay_q <= held_on_stay_d;
      dtr_le1_q      <= dtr_le1_d;
      dtf_le1_q      <= dtf_le1_d;
      on_le1_q       <= on_le1_d;
      dtzr_q         <= dtzr_d;
      dtzf_q         <= dtzf_d;
      rst_hold_q     <= rst_hold_d;
    end
  end

  assign hi_o = hi_q;
  assign lo_o = lo_q;

  // HoldIn = 1 reads hold_i and not rst_hold_q (removed by synthesis), HoldIn = 0 the other way round
  logic unused_hold;
  assign unused_hold = hold_i ^ rst_hold_q;

`ifdef FORMAL
  logic f_past_valid = 1'b0;
  always_ff @(posedge clk_i) f_past_valid <= 1'b1;
  always_comb if (!f_past_valid) assume (!rst_ni);
  // the dead times and minimum pulse in force (the ports one clock late), and the count itself (the
  // counter the flags replace: cnt_q >= dt_i of the earlier design), updated in the clock of the change;
  // f_hold_q: since the reset the count has not reached CntMax (rst_hold_q: nothing is held, so
  // nothing turns on). These model the implementation and restart with it at a reset.
  logic               f_chg, f_chg_q, f_hold_q;
  logic [DtWidth-1:0] f_dt_q, f_dtf_q, f_mp_q, f_cnt_q, f_on;
  assign f_chg = (hi_d != hi_q) || (lo_d != lo_q);
  // the minimum on-time in force: max(dt, dtf, mp)
  assign f_on  = (f_dt_q >= f_dtf_q && f_dt_q >= f_mp_q) ? f_dt_q : (f_dtf_q >= f_mp_q) ? f_dtf_q : f_mp_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      f_dt_q   <= '0;
      f_dtf_q  <= '0;
      f_mp_q   <= '0;
      f_cnt_q  <= '0;
      f_chg_q  <= 1'b0;
      f_hold_q <= 1'b1;
    end else begin
      f_dt_q   <= dt_i;
      f_dtf_q  <= dtf_i;
      f_mp_q   <= mp_i;
      f_cnt_q  <= f_chg ? DtWidth'(1) : (&f_cnt_q) ? f_cnt_q : f_cnt_q + 1'b1;
      f_chg_q  <= f_chg;
      f_hold_q <= f_hold_q && f_cnt_q < CntMax - 1'b1;
    end
  end
  // the counter one clock behind: chg_q is the last clock's change, ~ncnt1_q the shadow's count + 1
  // unless that change restarted it
  always_comb assert (chg_q == f_chg_q);
  always_comb assert (chg_q ? f_cnt_q == DtWidth'(1) : ~ncnt1_q == ((&f_cnt_q) ? f_cnt_q : f_cnt_q + 1'b1));
  // the hold: the RTL flag is the formal one; both gates off and unchanged while it lasts
  always_comb assert (rst_hold_q == f_hold_q);
  always_comb if (f_hold_q) assert (!hi_q && !lo_q && !chg_q);
  // the precomputed flags are the compares they replace (nothing held during the hold after a reset:
  // issue 27: the RTL's rst_hold_q)
  always_comb assert (held_r == (!f_hold_q && f_cnt_q != '0 && f_cnt_q >= f_dt_q));
  always_comb assert (held_f == (!f_hold_q && f_cnt_q != '0 && f_cnt_q >= f_dtf_q));
  always_comb assert (held_on == (!f_hold_q && f_cnt_q != '0 && f_cnt_q >= f_on));
  always_comb if (!chg_q) assert (held_r_stay_q == (!f_hold_q && f_cnt_q != '0 && f_cnt_q >= f_dt_q));
  always_comb if (!chg_q) assert (held_f_stay_q == (!f_hold_q && f_cnt_q != '0 && f_cnt_q >= f_dtf_q));
  always_comb if (!chg_q) assert (held_on_stay_q == (!f_hold_q && f_cnt_q != '0 && f_cnt_q >= f_on));
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni) begin
    assert (dtr_le1_q == (f_dt_q <= 1));
    assert (dtf_le1_q == (f_dtf_q <= 1));
    assert (on_le1_q == (f_on <= 1));
    assert (dtzr_q == (f_dt_q == '0));
    assert (dtzf_q == (f_dtf_q == '0));
  end
  // never both gates of the leg on
  always_comb assert (!(hi_q && lo_q));
  // the high side turns on only after both were off for the rising dead time in force (or swaps from
  // the low side when it is 0), the low side only after the falling dead time (or swaps when it is 0);
  // both-off for cnt clocks: the other gate turned off at least cnt clocks ago
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni && hi_q && !$past(hi_q))
    assert ($past(f_dt_q) == '0 || (!$past(lo_q) && $past(f_cnt_q) >= $past(f_dt_q)));
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni && lo_q && !$past(lo_q))
    assert ($past(f_dtf_q) == '0 || (!$past(hi_q) && $past(f_cnt_q) >= $past(f_dtf_q)));
  // a swap happens only at a zero dead time of its edge
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni && hi_q && $past(lo_q))
    assert ($past(f_dt_q) == '0);
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni && lo_q && $past(hi_q))
    assert ($past(f_dtf_q) == '0);
  // every on-pulse lasts max(dt, dtf, mp) unless cut by en_i low or (high side) by braking
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni && !hi_q && $past(hi_q)
                                 && $past(en_i) && !$past(brake_i))
    assert ($past(f_cnt_q) >= $past(f_on));
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni && !lo_q && $past(lo_q)
                                 && $past(en_i))
    assert ($past(f_cnt_q) >= $past(f_on));

  // ---- issue 27: dead time across resets, at the outputs. The monitors below have NO reset (declaration
  // values only; they sample rst_ni like any input), so they remember what was on before a reset: a
  // reset is a turn-off like any other, and the dead time in force before it is not forgotten.
  //   f_rel_q:   clocks since the release (0 in the release clock, the first with rst_ni high), saturating
  //   f_dtu_q / f_dtfu_q: the dead times in force (dt_i / dtf_i one clock late), kept through a reset
  //   f_*off_q:  clocks the gate has been off before this one (saturating); f_*off_dt_q: the other
  //              gate's dead time in force in the first clock this gate was off; f_*off_rst_q: a reset
  //              since this gate turned off (or while it was on)
  localparam logic [31:0] FW = DtWidth + 1;
  localparam logic [FW-1:0] FSat = FW'(CntMax) + 1'b1;  // CntMax + 1
  logic [FW-1:0]      f_rel_q = '0, f_hoff_q = '0, f_loff_q = '0;
  logic [DtWidth-1:0] f_dtu_q = '0, f_dtfu_q = '0, f_hoff_dt_q = '0, f_loff_dt_q = '0;
  logic               f_hoff_rst_q = 1'b0, f_loff_rst_q = 1'b0;
  always_ff @(posedge clk_i) begin
    f_rel_q      <= !rst_ni ? '0 : (f_rel_q == FSat) ? f_rel_q : f_rel_q + 1'b1;
    f_dtu_q      <= dt_i;
    f_dtfu_q     <= dtf_i;
    f_hoff_q     <= hi_q ? '0 : (f_hoff_q == FSat) ? f_hoff_q : f_hoff_q + 1'b1;
    f_loff_q     <= lo_q ? '0 : (f_loff_q == FSat) ? f_loff_q : f_loff_q + 1'b1;
    if (hi_q) f_hoff_dt_q <= dtf_i;      // the low side's dead time in force in hi's first off clock
    if (lo_q) f_loff_dt_q <= dt_i;       // the high side's, in lo's first off clock
    f_hoff_rst_q <= hi_q ? 1'b0 : (f_hoff_rst_q || !rst_ni);
    f_loff_rst_q <= lo_q ? 1'b0 : (f_loff_rst_q || !rst_ni);
  end
  // (a) after a reset no gate is on before the CntMax + 1-th clock after the release (the release clock
  // counted): a turn-on after a reset comes > CntMax clocks after the release, so after more than any
  // dead time the core could have had in force before the reset
  always_comb if (hi_q || lo_q) assert (f_rel_q == FSat);
  // (a) a turn-on comes after the other gate has been off for the dead time in force at the decision
  // (or swaps at dead time 0), resets included; and when a reset came since the other gate turned off,
  // for at least the dead time that was in force when it turned off (F1: a reset while a high side is
  // on, braking, turned the low side on 3 clocks after the release with dt 7)
  always_ff @(posedge clk_i) if (f_past_valid && hi_q && !$past(hi_q)) begin
    assert ($past(f_dtu_q) == '0 || f_loff_q >= FW'($past(f_dtu_q)));
    if (f_loff_rst_q) assert (f_loff_q > FW'(f_loff_dt_q) && f_loff_q > FW'(CntMax));
  end
  always_ff @(posedge clk_i) if (f_past_valid && lo_q && !$past(lo_q)) begin
    assert ($past(f_dtfu_q) == '0 || f_hoff_q >= FW'($past(f_dtfu_q)));
    if (f_hoff_rst_q) assert (f_hoff_q > FW'(f_hoff_dt_q) && f_hoff_q > FW'(CntMax));
  end
  // induction helpers: during the hold the release count is the count; after a reset the other gate's
  // off count is at least the release count
  always_comb if (rst_ni && f_hold_q) assert (FW'(f_cnt_q) == f_rel_q);
  always_comb if (rst_ni && !f_hold_q) assert (f_rel_q >= FW'(CntMax));
  always_comb if (f_loff_rst_q && !lo_q) assert (f_loff_q > f_rel_q || f_loff_q == FSat);
  always_comb if (f_hoff_rst_q && !hi_q) assert (f_hoff_q > f_rel_q || f_hoff_q == FSat);
  always_comb assert (f_rel_q <= FSat && f_loff_q <= FSat && f_hoff_q <= FSat);
  always_comb if (!lo_q) assert (f_loff_q == FSat || f_loff_q + 1'b1 >= FW'(f_cnt_q));
  always_comb if (!hi_q) assert (f_hoff_q == FSat || f_hoff_q + 1'b1 >= FW'(f_cnt_q));

  always_comb cover (hi_q && f_dt_q > DtWidth'(2) && f_mp_q > f_dt_q);
  always_comb cover (lo_q && f_dt_q > DtWidth'(2));
  always_comb cover (lo_q && brake_i && f_dt_q > DtWidth'(2));
  always_comb cover (hi_q && f_dt_q != dt_i);
  always_comb cover (held_on && chg_q && f_dt_q <= DtWidth'(1) && f_mp_q <= DtWidth'(1));
  // asymmetric dead times: each turn-on after its own dead time, both orders of dt and dtf, braking,
  // and a swap on one edge with a dead time on the other
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni) begin
    cover (hi_q && !$past(hi_q) && !$past(lo_q) && $past(f_dt_q) > DtWidth'(2)
           && $past(f_dtf_q) > $past(f_dt_q) && $past(f_cnt_q) == $past(f_dt_q));
    cover (lo_q && !$past(lo_q) && !$past(hi_q) && $past(f_dtf_q) > DtWidth'(2)
           && $past(f_dt_q) > $past(f_dtf_q) && $past(f_cnt_q) == $past(f_dtf_q));
    cover (lo_q && !$past(lo_q) && $past(brake_i) && $past(f_dtf_q) > DtWidth'(2)
           && $past(f_dt_q) != $past(f_dtf_q));
    cover (lo_q && $past(hi_q) && $past(f_dtf_q) == '0 && $past(f_dt_q) > DtWidth'(2));
    cover (hi_q && $past(lo_q) && $past(f_dt_q) == '0 && $past(f_dtf_q) > DtWidth'(2));
  end
  // (d) F1's scenario: a reset during a high-side pulse with braking, and the low side on after the hold
  // (a dead time of at least 3 in force when the high side went off)
  always_ff @(posedge clk_i) if (f_past_valid)
    cover (lo_q && !$past(lo_q) && $past(brake_i) && f_hoff_rst_q && f_hoff_dt_q > DtWidth'(2));
`endif

endmodule

`default_nettype wire
