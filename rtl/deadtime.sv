// SPDX-License-Identifier: Apache-2.0
// deadtime: dead-time insertion for one inverter leg, pole state -> high-side and low-side gates.
// A gate turns off on the clock after its pole request goes away; the other gate turns on only after
// both gates have been off for dt_i clocks (the WFG dead-time generator of Minas sec. III-A). Every
// gate on-pulse lasts at least max(dt_i, mp_i) clocks (a gate turned on is held until then), and every
// off-gap between two on-pulses of the same gate lasts at least dt_i clocks, so no runt pulse reaches a
// gate. (svpwm_minpulse already keeps the pole pulses long enough; this is the last-stage guarantee.)
// en_i low turns both gates off on the next clock, whatever the state (safety before pulse length).
// Reset turns both gates off and the dead time counts from its release, so a reset in mid-pulse
// is followed by the full dead time too.
// brake_i (active braking, the trip safe state "low sides on"): the high side turns off on the next
// clock, the low side turns on once both have been off for dt_i -- braking never skips the dead time.
// dt_i = 0: complementary gates switch on the same clock edge (no dead time, still never both on).
// Parameters: DtWidth - dead-time / minimum-pulse width in bits (max 2^DtWidth - 1 clocks).
// Latency: one clock from pole_i to a turn-off, 1 + dt_i clocks to the complementary turn-on.
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
  input  logic [DtWidth-1:0] dt_i,     // dead time in clocks
  input  logic [DtWidth-1:0] mp_i,     // minimum on-pulse in clocks (the on-time is >= max(dt, mp))
  output logic               hi_o,     // high-side gate (registered), 1 = on
  output logic               lo_o      // low-side gate (registered), 1 = on
);

  if (DtWidth < 1 || DtWidth > 16) begin : gen_bad_width
    initial $fatal(1, "deadtime: DtWidth must be 1..16, got %0d", DtWidth);
  end

  logic               hi_d, hi_q, lo_d, lo_q;
  logic [DtWidth-1:0] cnt_d, cnt_q;     // clocks the gate state has been unchanged, incl. this one (sat.)
  logic               held;             // the present state has lasted dt_i clocks
  logic               held_on;          // ... and mp_i clocks (minimum on-time served)

  assign held    = cnt_q >= dt_i;
  assign held_on = held && cnt_q >= mp_i;

  always_comb begin
    hi_d = hi_q;
    lo_d = lo_q;
    if (!en_i) begin
      hi_d = 1'b0;
      lo_d = 1'b0;
    end else if (hi_q) begin
      if (brake_i || (!pole_i && held_on)) begin   // turn off (or swap if dt_i == 0)
        hi_d = 1'b0;
        lo_d = (dt_i == '0);
      end
    end else if (lo_q) begin
      if (!brake_i && pole_i && held_on) begin
        lo_d = 1'b0;
        hi_d = (dt_i == '0);
      end
    end else if (held) begin            // both off for dt_i clocks: the wanted gate may turn on
      hi_d = pole_i && !brake_i;
      lo_d = !pole_i || brake_i;
    end
    if (hi_d != hi_q || lo_d != lo_q) cnt_d = DtWidth'(1);
    else if (cnt_q != '1)             cnt_d = cnt_q + 1'b1;
    else                              cnt_d = cnt_q;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      hi_q  <= 1'b0;
      lo_q  <= 1'b0;
      cnt_q <= '0;                     // a reset is a turn-off: the dead time runs from its release
    end else begin
      hi_q  <= hi_d;
      lo_q  <= lo_d;
      cnt_q <= cnt_d;
    end
  end

  assign hi_o = hi_q;
  assign lo_o = lo_q;

`ifdef FORMAL
  logic f_past_valid = 1'b0;
  always_ff @(posedge clk_i) f_past_valid <= 1'b1;
  always_comb if (!f_past_valid) assume (!rst_ni);
  // never both gates of the leg on
  always_comb assert (!(hi_q && lo_q));
  // a gate turns on only after both were off for the dead time in force (or swaps when it is 0)
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni && hi_q && !$past(hi_q))
    assert ($past(dt_i) == '0 || (!$past(lo_q) && $past(cnt_q) >= $past(dt_i)));
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni && lo_q && !$past(lo_q))
    assert ($past(dt_i) == '0 || (!$past(hi_q) && $past(cnt_q) >= $past(dt_i)));
  // every on-pulse lasts max(dt, mp) unless cut by en_i low or (high side) by braking
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni && !hi_q && $past(hi_q)
                                 && $past(en_i) && !$past(brake_i))
    assert ($past(cnt_q) >= $past(dt_i) && $past(cnt_q) >= $past(mp_i));
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni && !lo_q && $past(lo_q)
                                 && $past(en_i))
    assert ($past(cnt_q) >= $past(dt_i) && $past(cnt_q) >= $past(mp_i));
  always_comb cover (hi_q && dt_i > DtWidth'(2) && mp_i > dt_i);
  always_comb cover (lo_q && dt_i > DtWidth'(2));
  always_comb cover (lo_q && brake_i && dt_i > DtWidth'(2));
`endif

endmodule

`default_nettype wire
