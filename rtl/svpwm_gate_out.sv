// SPDX-License-Identifier: Apache-2.0
// svpwm_gate_out: the last stage between the dead-time registers and the pins: trip (fault) forcing,
// shoot-through interlock and gate polarity. The forcing is combinational after registers, so a fault
// forces the gates off in the same cycle, and even with the clock stopped (like TI ePWM trip zones /
// STM32 TIM1 break).
//   * fault_i (asynchronous, active high) turns the high sides off at once, combinationally, and the
//     low sides too unless the safe state is "low sides on" (safe_lo_i): the low sides are then turned
//     on by the dead-time FSMs (trip_sync_o -> brake), after the dead time -- an asynchronous force
//     could only turn a low side on without dead time, so it never turns anything on.
//   * the pins are forced safe by fault_i, both synchroniser flops and the latch, so a fault that a
//     clock edge has seen holds the safe state without a break until the trip releases: the latch
//     follows the synchroniser two clock edges late, and what lies between is covered by the earlier
//     stages. A pulse that no clock edge sees (shorter than a clock, between two edges) forces the pins
//     off while it lasts and is not latched (a glitch: the dead-time FSMs never see it).
//   * latched mode (cbc_i = 0): a fault latches (after the 2-flop synchroniser); the gates stay safe
//     until fault_i has returned low AND fault_clear_i is pulsed. A clear at the clock edge that sees a
//     new fault pulse cannot lose it: the pins stay forced by the synchroniser, which sets the latch
//     again two edges later.
//   * cycle-by-cycle mode (cbc_i = 1): the latch releases by itself at the next carrier valley
//     (valley_i) at which the synchronised fault input is low.
//   * trip_sync_o (the dead-time FSMs' trip: braking or all off) is the synchronised fault, the latch and
//     the latch of the clock before: a release holds it one clock longer, so that a fault the
//     synchroniser caught at the releasing clock edge keeps it high without a break.
//   * safe state: safe_lo_i = 0 all six gates off (default); 1 low sides on (active braking).
//   * interlock: a leg whose two gate requests are both on gets both gates off, whatever happens
//     upstream (it cannot happen with rtl/deadtime.sv; this stage does not rely on that).
//   * polarity: pol_i[0] = 1 makes the high-side pins active low, pol_i[1] the low-side pins; "off"
//     is the right level at the pins in every state, reset included (pol_i are straps/static config).
// Latency: 0 clocks from fault_i to the pins (off); 2 clocks to fault_o / trip_sync_o.
`default_nettype none

module svpwm_gate_out (
  input  logic       clk_i,          // core clock
  input  logic       rst_ni,         // asynchronous reset, active low (latch cleared)
  input  logic [2:0] hi_i,           // {c, b, a} high-side requests from the dead-time registers
  input  logic [2:0] lo_i,           // {c, b, a} low-side requests
  input  logic       fault_i,        // trip input, asynchronous, active high
  input  logic       fault_clear_i,  // latched mode: clears the latch once fault_i is low (pulse)
  input  logic       cbc_i,          // 1: cycle-by-cycle (auto release at a valley), 0: latched
  input  logic       valley_i,       // carrier valley strobe (cycle-by-cycle release point)
  input  logic       safe_lo_i,      // safe state: 0 all off, 1 low sides on
  input  logic [1:0] pol_i,          // {low side, high side}: 1 = active-low pins
  output logic [2:0] gate_hi_o,      // high-side pins
  output logic [2:0] gate_lo_o,      // low-side pins
  output logic       fault_o,        // synchronised fault input level (status)
  output logic       trip_sync_o,    // synchronous trip state for the dead-time FSMs (sync'd input or latch)
  output logic       tripped_o       // the safe state is forced (latch set or fault_i high)
);

  logic [1:0] sync_q;                // fault_i synchroniser
  logic       latch_d, latch_q, latch_prev_q;
  logic       held_q;                // == sync_q[1] || latch_q, as one register (the pins' and the FSMs'
                                     // trip start at a flip-flop: shorter status and read paths)
  logic       safe, off_lo;
  logic [2:0] hi_ok, lo_ok, hi_on, lo_on;

  always_comb begin
    latch_d = latch_q;
    if (sync_q[1]) begin
      latch_d = 1'b1;
    end else if (latch_q && (cbc_i ? valley_i : fault_clear_i)) begin
      latch_d = 1'b0;
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      sync_q       <= '0;
      latch_q      <= 1'b0;
      latch_prev_q <= 1'b0;
      held_q       <= 1'b0;
    end else begin
      sync_q       <= {sync_q[0], fault_i};
      latch_q      <= latch_d;
      latch_prev_q <= latch_q;
      held_q       <= sync_q[0] || latch_d;     // the next clock's sync_q[1] || latch_q
    end
  end

  assign safe   = fault_i || sync_q[0] || held_q;
  assign off_lo = safe && !safe_lo_i;
  assign hi_ok  = hi_i & ~lo_i;      // interlock: both requested -> both off
  assign lo_ok  = lo_i & ~hi_i;
  assign hi_on  = safe   ? 3'b000 : hi_ok;
  assign lo_on  = off_lo ? 3'b000 : lo_ok;

  assign gate_hi_o = pol_i[0] ? ~hi_on : hi_on;
  assign gate_lo_o = pol_i[1] ? ~lo_on : lo_on;
  assign fault_o     = sync_q[1];
  assign trip_sync_o = held_q || latch_prev_q;
  assign tripped_o   = safe;

`ifdef FORMAL
  logic f_past_valid = 1'b0;
  always_ff @(posedge clk_i) f_past_valid <= 1'b1;
  always_comb if (!f_past_valid) assume (!rst_ni);
  // a leg never has both gates on, whatever the inputs
  always_comb assert (!(hi_on & lo_on));
  // fault asserted => high sides off in the same cycle, and low sides off unless braking
  always_comb if (fault_i) assert (hi_on == 3'b000);
  always_comb if (fault_i && !safe_lo_i) assert (lo_on == 3'b000);
  // once latched, safe until cleared: the latch only falls on a clear (latched) or valley (cbc)
  // with the synchronised input low
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni && $past(latch_q) && !latch_q)
    assert (!$past(sync_q[1]) && ($past(cbc_i) ? $past(valley_i) : $past(fault_clear_i)));
  always_comb if (latch_q) assert (hi_on == 3'b000 && (safe_lo_i || lo_on == 3'b000));
  always_comb cover (latch_q && !fault_i && !cbc_i);
  always_ff @(posedge clk_i) cover (f_past_valid && $past(latch_q) && !latch_q && $past(fault_i, 3));

  // ---- issue 27: the safe state without a break. The monitors have no reset (declaration values; they
  // sample rst_ni like any input). A fault is "seen" by the clock edge that ends a formal step with
  // fault_i high and rst_ni high (async2sync: one step per clock, an input holds for the step, so a pulse
  // in a step spans that edge; a fault only in reset is not latched: the reset holds the synchroniser,
  // and no gate turns on in the reset hold after it). f_trip_q: a fault has been seen and the trip has
  // not been released since: it rises after the edge that sees fault_i, falls after a reset (a reset
  // clears the latch) and after the edge at which
  // the latch falls (a clear, latched; a valley, cbc), unless a fault was seen at that edge or the one
  // before (a fault in the synchroniser is a new trip, issue 27 F2). f_age_q: its clocks (saturating at 2;
  // the clocks in reset not counted: the synchroniser is held).
  logic       f_seen1_q = 1'b0, f_trip_q = 1'b0;
  logic [1:0] f_age_q = 2'd0;
  logic       f_rel, f_trip_d;
  assign f_rel    = latch_q && !latch_d && !f_seen1_q;          // the latch falls, nothing seen before
  assign f_trip_d = (fault_i && rst_ni) || (f_trip_q && rst_ni && !f_rel);
  always_ff @(posedge clk_i) begin
    f_seen1_q <= fault_i;
    f_trip_q  <= f_trip_d;
    f_age_q   <= !f_trip_d ? 2'd0 : !rst_ni ? 2'd0 : !f_trip_q ? 2'd1 : (f_age_q == 2'd2) ? 2'd2
                                                                                          : f_age_q + 1'b1;
  end
  // (c) from the first edge that sees fault_i until the release the high-side pins are off in every
  // clock, the low sides too unless braking (F2, F4: a clear with a new fault, a pulse over one edge;
  // a reset releases the trip at once: it clears the latch); and the FSMs' trip (trip_sync_o) is high
  // from the second clock on without a gap until the release
  always_comb if (f_trip_q && rst_ni) assert (hi_on == 3'b000 && (safe_lo_i || lo_on == 3'b000));
  always_comb if (f_trip_q && rst_ni && f_age_q == 2'd2) assert (trip_sync_o);
  // (b) latched mode: a fault seen at the edge of a clear, or at the edge before, survives the clear: the
  // latch is set again within 3 clocks (the pins stay safe meanwhile: (c))
  always_ff @(posedge clk_i) if (f_past_valid && rst_ni && $past(rst_ni) && $past(rst_ni, 2)
                                 && $past(rst_ni, 3) && $past(latch_q, 3) && !$past(latch_q, 2)
                                 && ($past(fault_i, 3) || $past(f_seen1_q, 3)))
    assert (latch_q || $past(latch_q));
  // induction helpers
  always_comb if (f_trip_q && rst_ni) assert (f_age_q != 2'd0);
  always_comb if (f_trip_q && rst_ni && f_age_q == 2'd1) assert (sync_q[0] || latch_q);
  // (d) a clear in the clock of a new fault, and the latch set again; a pulse over one clock edge only
  always_ff @(posedge clk_i) if (f_past_valid) begin
    cover (latch_q && !$past(latch_q) && !$past(latch_q, 2) && $past(latch_q, 3) && $past(fault_i, 3)
           && $past(fault_clear_i, 3) && !$past(cbc_i, 3) && !$past(fault_i, 4));
    cover (latch_q && !$past(latch_q) && !$past(cbc_i) && $past(fault_i, 3) && !$past(fault_i, 4)
           && !$past(fault_i, 2) && !$past(fault_i) && !fault_i);
  end
`endif

endmodule

`default_nettype wire
