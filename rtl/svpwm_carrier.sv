// SPDX-License-Identifier: Apache-2.0
// svpwm_carrier: up/down (centre-aligned) carrier counter 0 -> P -> 0, one step per clock.
// Parameters: CntWidth - counter / period width in bits; MinPeriod - the smallest period_i the user
// applies (svpwm_core: its MinPeriod clamp); from 2 on the one-clock-half-period case is left out.
// f_sw = f_clk / (2 * period): the count runs 0,1,..,P-1 (counting up) then P,P-1,..,1 (counting down).
// Latency: none, count_o / up_o are the registers. The period is taken only at the valley: it loads
// in the cycle load_o is high (the last cycle before a valley, or any idle cycle) and is active from
// the valley on, so a period never changes in mid-carrier (Minas sec. III-A: WG_COUNTER/WG_RELOAD).
// Reset: count 0, counting up, period 2 (used as is if run_i rises in the first clock after reset).
// Restrictions: period_i >= MinPeriod >= 1 (svpwm_core clamps it to its MinPeriod).
`default_nettype none

module svpwm_carrier #(
  parameter int CntWidth  = 16,
  parameter int MinPeriod = 1
) (
  input  logic                clk_i,       // core clock
  input  logic                rst_ni,      // asynchronous reset, active low
  input  logic                run_i,       // count while high; while low hold at the valley (0, up)
  input  logic [CntWidth-1:0] period_i,    // next half period in clocks, loaded when load_o is high
  output logic [CntWidth-1:0] count_o,     // carrier value, 0..period_o
  output logic                up_o,        // 1 while counting up (count 0..P-1), 0 while down (P..1)
  output logic [CntWidth-1:0] period_o,    // active half period
  output logic                valley_o,    // running and count == 0: first cycle of a carrier period
  output logic                peak_o,      // running and count == period: the middle of the period
  output logic                pre_peak_o,  // the next clock is a peak (registered-peak detect input)
  output logic                load_o,      // shadow load strobe: the next cycle is a valley (or idle)
  output logic                point_o      // running, the next cycle is a valley or a peak: load_o or
                                           // pre_peak_o while run_i, from flip-flops only (ld_q, topu_q)
);

  if (CntWidth < 8 || CntWidth > 16) begin : gen_bad_width
`ifdef __ICARUS__  // Icarus 11 has no elaboration-time tasks: at time 0
    initial $fatal(1, "svpwm_carrier: CntWidth must be 8..16, got %0d (%m)", CntWidth);
`else              // at elaboration (Yosys formats $display only, then stops at $error)
    initial $display("svpwm_carrier: CntWidth must be 8..16, got %0d (%m)", CntWidth);
    $error("svpwm_carrier: CntWidth must be 8..16, got %0d", CntWidth);
`endif
  end
  if (MinPeriod < 1 || MinPeriod >= (1 << CntWidth)) begin : gen_bad_min_period
`ifdef __ICARUS__  // Icarus 11 has no elaboration-time tasks: at time 0
    initial $fatal(1, "svpwm_carrier: MinPeriod must be 1..2^CntWidth-1, got %0d (%m)", MinPeriod);
`else              // at elaboration (Yosys formats $display only, then stops at $error)
    initial $display("svpwm_carrier: MinPeriod must be 1..2^CntWidth-1, got %0d (%m)", MinPeriod);
    $error("svpwm_carrier: MinPeriod must be 1..2^CntWidth-1, got %0d", MinPeriod);
`endif
  end

  localparam bit OneClk = MinPeriod < 2;     // a one-clock half period can be applied

  logic [CntWidth-1:0] count_d, count_q, period_d, period_q;
  logic                up_d, up_q;
  logic                peak_d, peak_q;     // registered peak detect (keeps the compare off later paths)
  logic [CntWidth-1:0] pm2_d, pm2_q;       // period - 2, registered with the period (no subtractor)
  logic                topu_d, topu_q;     // counting up and count == period - 1 (the clock before the
                                           // peak), registered: computed a clock ahead from count == P - 2
  logic                p1_d, p1_q;         // period == 1 (the peak follows the valley at once)
  logic                ld_d, ld_q;         // count == 1 counting down (the last clock before a valley),
                                           // registered: the load strobe comes from a flip-flop
  logic                vz_q;               // count == 0 counting up (a valley while running): the
                                           // registered load strobe (after a load the count is 0, up)

  assign load_o = !run_i || ld_q;

  always_comb begin
    count_d  = count_q;
    up_d     = up_q;
    period_d = load_o ? period_i : period_q;
    pm2_d    = load_o ? period_i - CntWidth'(2) : pm2_q;
    p1_d     = load_o ? OneClk && period_i == CntWidth'(1) : p1_q;
    if (!run_i) begin
      count_d = '0;
      up_d    = 1'b1;
    end else begin
      count_d = count_q + {{(CntWidth-1){!up_q}}, 1'b1};   // +1 up, -1 down: one adder
      if (topu_q) up_d = 1'b0;
      if (ld_q)   up_d = 1'b1;                // count == 1, down
    end
    // next clock counting up at count == P - 1: after a load (count 0) when P == 1, else one step
    // after count == P - 2 counting up (never right after the top itself: the count turns down)
    topu_d = load_o ? (OneClk && period_i == CntWidth'(1)) : (up_q && !topu_q && count_q == pm2_q);
    peak_d = run_i && topu_q;               // next clock: count == period, down
    // next clock: count == 1, down (from 2 down, or from the peak of a one-clock half period)
    ld_d   = run_i && (topu_q ? p1_q : (!up_q && count_q == CntWidth'(2)));
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      count_q  <= '0;
      up_q     <= 1'b1;
      period_q <= CntWidth'(2);           // (every flag below then resets to 0)
      pm2_q    <= '0;
      topu_q   <= 1'b0;
      p1_q     <= 1'b0;
      peak_q   <= 1'b0;
      ld_q     <= 1'b0;
      vz_q     <= 1'b1;
    end else begin
      count_q  <= count_d;
      up_q     <= up_d;
      period_q <= period_d;
      pm2_q    <= pm2_d;
      topu_q   <= topu_d;
      p1_q     <= p1_d;
      peak_q   <= peak_d;
      ld_q     <= ld_d;
      vz_q     <= load_o;
    end
  end

  assign count_o  = count_q;
  assign up_o     = up_q;
  assign period_o = period_q;
  assign valley_o = run_i && vz_q;       // == run_i && up_q && count_q == 0
  assign peak_o     = run_i && peak_q;    // == run_i && !up_q && count_q == period_q
  assign pre_peak_o = peak_d;
  assign point_o    = ld_q || topu_q;

`ifdef FORMAL
  logic f_past_valid = 1'b0;
  always_ff @(posedge clk_i) f_past_valid <= 1'b1;
  always_comb if (!f_past_valid) assume (!rst_ni);
  always_comb assume (period_i >= CntWidth'(MinPeriod) && period_i != '0);
  // the carrier never leaves [0, period]
  always_comb if (rst_ni) assert (count_q <= period_q);
  always_comb if (rst_ni && up_q) assert (count_q < period_q || period_q == '0);
  // the period only changes at a valley (or while idle)
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni && period_q != $past(period_q))
    assert (count_q == '0 && up_q);
  always_comb if (rst_ni) assert (peak_o == (run_i && !up_q && count_q == period_q));
  always_comb if (rst_ni) assert (pm2_q == period_q - CntWidth'(2));
  always_comb if (rst_ni) assert (p1_q == (period_q == CntWidth'(1)));
  always_comb if (rst_ni) assert (topu_q == (up_q && count_q == period_q - 1'b1));
  always_comb if (rst_ni) assert (vz_q == (up_q && count_q == '0));
  always_comb if (rst_ni) assert (ld_q == (!up_q && count_q == CntWidth'(1)));
  always_comb if (rst_ni && run_i) assert (point_o == (load_o || pre_peak_o));
  always_comb cover (rst_ni && peak_o && period_q == CntWidth'(3));
`endif

endmodule

`default_nettype wire
