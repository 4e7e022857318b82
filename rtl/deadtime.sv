// SPDX-License-Identifier: Apache-2.0
// deadtime: dead-time insertion for one inverter leg, pole state -> high-side and low-side gates.
// A gate turns off on the clock after its pole request goes away; the other gate turns on only after
// both gates have been off for dt_i clocks (the WFG dead-time generator of Minas sec. III-A). Every
// gate on-pulse lasts at least max(dt_i, mp_i) clocks (a gate turned on is held until then), and every
// off-gap between two on-pulses of the same gate lasts at least dt_i clocks, so no runt pulse reaches a
// gate. (svpwm_calc's minimum-pulse rule already keeps the pole pulses long enough; this is the
// last-stage guarantee.)
// en_i low turns both gates off on the next clock, whatever the state (safety before pulse length).
// Reset turns both gates off and the dead time counts from its release, so a reset in mid-pulse
// is followed by the full dead time too.
// brake_i (active braking, the trip safe state "low sides on"): the high side turns off on the next
// clock, the low side turns on once both have been off for dt_i -- braking never skips the dead time.
// dt_i = 0: complementary gates switch on the same clock edge (no dead time, still never both on).
// dt_i and mp_i are read ONE CLOCK AHEAD: the values on the ports in clock n are in force in clock n + 1
// (svpwm_core passes its dead-time registers, so a new dead time reaches the legs one clock after the
// valley). The module compares its counter with them a clock early, so its decision reads only
// flip-flops ("held" flags, not a 10-bit compare). In the first clock after reset no gate turns on
// (nothing is held yet, whatever dt_i).
// Parameters: DtWidth - dead-time / minimum-pulse width in bits (max 2^DtWidth - 1 clocks).
// Latency: one clock from pole_i to a turn-off, 1 + dt clocks to the complementary turn-on (dt in force).
// Model: model/svpwm_model/deadtime.py (step_cycle, simulate_events).
`default_nettype none

module deadtime #(
  parameter int DtWidth = 10
) (
  input  logic               clk_i,    // core clock
  input  logic               rst_ni,   // asynchronous reset, active low (both gates off)
  input  logic               en_i,     // 0: both gates off (next clock)
  input  logic               brake_i,  // 1: low side wanted regardless of pole_i, high side off at once
  input  logic               pole_i,   // 1: high side wanted, 0: low side wanted
  input  logic [DtWidth-1:0] dt_i,     // dead time in clocks, in force from the NEXT clock on
  input  logic [DtWidth-1:0] mp_i,     // minimum on-pulse in clocks (on-time >= max(dt, mp)), next clock
  output logic               hi_o,     // high-side gate (registered), 1 = on
  output logic               lo_o      // low-side gate (registered), 1 = on
);

  if (DtWidth < 1 || DtWidth > 16) begin : gen_bad_width
    initial $fatal(1, "deadtime: DtWidth must be 1..16, got %0d", DtWidth);
  end

  // cnt = clocks the gate state has been unchanged, this one included (saturating at 2^DtWidth - 1;
  // 0 only in the clock after reset). The register holds the count the NEXT clock has if the state
  // stays: min(cnt + 1, 2^DtWidth - 1).
  logic               hi_d, hi_q, lo_d, lo_q, chg;
  logic [DtWidth-1:0] cnt1_d, cnt1_q;
  logic               held_d, held_q;         // cnt >= dt and cnt >= 1: the present state has lasted dt
  logic               held_on_d, held_on_q;   // ... and cnt >= mp (the minimum on-time is served)
  logic               dtz_d, dtz_q;           // dt == 0 (a gate swaps straight to the other)

  always_comb begin
    hi_d = hi_q;
    lo_d = lo_q;
    if (!en_i) begin
      hi_d = 1'b0;
      lo_d = 1'b0;
    end else if (hi_q) begin
      if (brake_i || (!pole_i && held_on_q)) begin   // turn off (or swap if dt == 0)
        hi_d = 1'b0;
        lo_d = dtz_q;
      end
    end else if (lo_q) begin
      if (!brake_i && pole_i && held_on_q) begin
        lo_d = 1'b0;
        hi_d = dtz_q;
      end
    end else if (held_q) begin          // both off for dt clocks: the wanted gate may turn on
      hi_d = pole_i && !brake_i;
      lo_d = !pole_i || brake_i;
    end
    chg = (hi_d != hi_q) || (lo_d != lo_q);
  end

  // the next clock's flags: its count is 1 after a change, else cnt1_q (both compares run in parallel
  // with the decision above, which only selects)
  always_comb begin
    cnt1_d    = chg ? ((DtWidth > 1) ? DtWidth'(2) : DtWidth'(1)) : (&cnt1_q) ? cnt1_q : cnt1_q + 1'b1;
    held_d    = chg ? (dt_i >> 1) == '0 : (dt_i <= cnt1_q);
    held_on_d = held_d && (chg ? (mp_i >> 1) == '0 : (mp_i <= cnt1_q));
    dtz_d     = (dt_i == '0);
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      hi_q      <= 1'b0;
      lo_q      <= 1'b0;
      cnt1_q    <= DtWidth'(1);          // cnt = 0: a reset is a turn-off, the dead time runs from its release
      held_q    <= 1'b0;
      held_on_q <= 1'b0;
      dtz_q     <= 1'b0;                 // (read only while a gate is on)
    end else begin
      hi_q      <= hi_d;
      lo_q      <= lo_d;
      cnt1_q    <= cnt1_d;
      held_q    <= held_d;
      held_on_q <= held_on_d;
      dtz_q     <= dtz_d;
    end
  end

  assign hi_o = hi_q;
  assign lo_o = lo_q;

`ifdef FORMAL
  logic f_past_valid = 1'b0;
  always_ff @(posedge clk_i) f_past_valid <= 1'b1;
  always_comb if (!f_past_valid) assume (!rst_ni);
  // the dead time and minimum pulse in force (the ports one clock late), and the count itself (the
  // counter the flags replace: cnt_q >= dt_i of the earlier design)
  logic [DtWidth-1:0] f_dt_q, f_mp_q, f_cnt_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      f_dt_q  <= '0;
      f_mp_q  <= '0;
      f_cnt_q <= '0;
    end else begin
      f_dt_q  <= dt_i;
      f_mp_q  <= mp_i;
      f_cnt_q <= chg ? DtWidth'(1) : (&f_cnt_q) ? f_cnt_q : f_cnt_q + 1'b1;
    end
  end
  // the precomputed flags are the compares they replace
  always_comb assert (cnt1_q == ((&f_cnt_q) ? f_cnt_q : f_cnt_q + 1'b1));
  always_comb assert (held_q == (f_cnt_q != '0 && f_cnt_q >= f_dt_q));
  always_comb assert (held_on_q == (held_q && f_cnt_q >= f_mp_q));
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni) assert (dtz_q == (f_dt_q == '0));
  // never both gates of the leg on
  always_comb assert (!(hi_q && lo_q));
  // a gate turns on only after both were off for the dead time in force (or swaps when it is 0)
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni && hi_q && !$past(hi_q))
    assert ($past(f_dt_q) == '0 || (!$past(lo_q) && $past(f_cnt_q) >= $past(f_dt_q)));
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni && lo_q && !$past(lo_q))
    assert ($past(f_dt_q) == '0 || (!$past(hi_q) && $past(f_cnt_q) >= $past(f_dt_q)));
  // every on-pulse lasts max(dt, mp) unless cut by en_i low or (high side) by braking
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni && !hi_q && $past(hi_q)
                                 && $past(en_i) && !$past(brake_i))
    assert ($past(f_cnt_q) >= $past(f_dt_q) && $past(f_cnt_q) >= $past(f_mp_q));
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni && !lo_q && $past(lo_q)
                                 && $past(en_i))
    assert ($past(f_cnt_q) >= $past(f_dt_q) && $past(f_cnt_q) >= $past(f_mp_q));
  always_comb cover (hi_q && f_dt_q > DtWidth'(2) && f_mp_q > f_dt_q);
  always_comb cover (lo_q && f_dt_q > DtWidth'(2));
  always_comb cover (lo_q && brake_i && f_dt_q > DtWidth'(2));
  always_comb cover (hi_q && f_dt_q != dt_i);
`endif

endmodule

`default_nettype wire
