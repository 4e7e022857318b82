// SPDX-License-Identifier: Apache-2.0
// svpwm_adc: current sampling support of svpwm_core (feature ADC): two programmable ADC trigger points
// and the per-phase shunt-window report (model: svpwm_model/adc.py, docs/reference.md "Current sampling").
// Trigger points: point k fires (pt_o[k], one clock) once per carrier period while the carrier runs: in
// the clock where the carrier is at count cnt_k counting up (dn_k = 0) or down (dn_k = 1); the valley
// (count 0) and the peak (count P) are one clock each and fire for either direction, and a count beyond
// the active half period P fires at the peak. The points (en, dn, cnt) and the minimum window are
// sampled with the reference (sample_i: the core's sample clock) and take effect with the compare values
// computed from it (take_i: the update), like a shadow / active register pair, so the trigger points of a
// period are those of its compare values.
// Shunt-window report, per phase x from the active compare value C, half period P and dead times dt
// (rising: before a high side) and dtf (falling: before a low side), the gates' on-times in a period
// whose neighbour has the same values:
//   win_lo = 2P if C == P, else max(2C - dtf, 0): the low side's on-time around the valley
//   win_hi = 2P if C == 0, else max(2(P - C) - dt, 0): the high side's on-time around the peak
//   win_ok[x] = win_lo[x] >= max(the minimum window, 1) (the ADC's settling + acquisition around its
//               sample point)
//   win_recon = the phase with the shortest low-side window (the first of equal ones): read the other two
//               and reconstruct it as minus their sum (i_a + i_b + i_c = 0)
// all zero while the compare values are not valid (active_i low: stopped or tripped).
// Parameters: CntWidth - carrier width (svpwm_core's), DtWidth - dead-time width.
// Latency: pt_o combinational from registers (the carrier's count / direction, the active points);
// win_lo_o / win_hi_o follow the active values and dead times one clock later, win_ok_o / win_recon_o
// two clocks later.
`default_nettype none

module svpwm_adc #(
  parameter int CntWidth = 16,
  parameter int DtWidth  = 10
) (
  input  logic                      clk_i,         // core clock
  input  logic                      rst_ni,        // asynchronous reset, active low
  input  logic                      run_i,         // the carrier runs (the core's run_q)
  input  logic [CntWidth-1:0]       count_i,       // carrier value
  input  logic                      up_i,          // carrier counting up
  input  logic                      valley_i,      // running and count == 0
  input  logic                      peak_i,        // running and count == P
  input  logic [CntWidth-1:0]       period_i,      // active half period P
  input  logic                      sample_i,      // the reference is sampled (the core's event_now)
  input  logic                      take_i,        // the update: compare values computed from it active
  input  logic [1:0]                pt_en_i,       // trigger point k enabled
  input  logic [1:0]                pt_dn_i,       // trigger point k on the down count
  input  logic [2*CntWidth-1:0]     pt_cnt_i,      // {cnt_1, cnt_0}: carrier counts of the points
  input  logic [CntWidth:0]         win_min_i,     // minimum low-side window, clocks
  input  logic                      active_i,      // active compare values valid (running, not tripped)
  input  logic [3*CntWidth-1:0]     cmp_i,         // {C_c, C_b, C_a} active
  input  logic [DtWidth-1:0]        dt_i,          // rising dead time in force
  input  logic [DtWidth-1:0]        dtf_i,         // falling dead time in force
  output logic [1:0]                pt_o,          // pulse: trigger point k
  output logic [3*(CntWidth+1)-1:0] win_lo_o,      // {c, b, a} low-side windows, clocks
  output logic [3*(CntWidth+1)-1:0] win_hi_o,      // {c, b, a} high-side windows, clocks
  output logic [2:0]                win_ok_o,      // {c, b, a} low-side window >= the minimum
  output logic [1:0]                win_recon_o    // the phase to reconstruct (0 a, 1 b, 2 c)
);

  localparam int WW = CntWidth + 1;

  // ---- trigger points: sampled with the reference, active from its update ------------------------
  logic [1:0]            en_smp_d, en_smp_q, dn_smp_d, dn_smp_q, en_act_d, en_act_q, dn_act_d, dn_act_q;
  logic [2*CntWidth-1:0] cnt_smp_d, cnt_smp_q, cnt_act_d, cnt_act_q;
  logic [WW-1:0]         min_smp_d, min_smp_q, min_act_d, min_act_q;

  always_comb begin
    en_smp_d  = en_smp_q;
    dn_smp_d  = dn_smp_q;
    cnt_smp_d = cnt_smp_q;
    min_smp_d = min_smp_q;
    en_act_d  = en_act_q;
    dn_act_d  = dn_act_q;
    cnt_act_d = cnt_act_q;
    min_act_d = min_act_q;
    if (sample_i) begin
      en_smp_d  = pt_en_i;
      dn_smp_d  = pt_dn_i;
      cnt_smp_d = pt_cnt_i;
      min_smp_d = win_min_i;
    end
    if (take_i) begin
      en_act_d  = en_smp_q;
      dn_act_d  = dn_smp_q;
      cnt_act_d = cnt_smp_q;
      min_act_d = min_smp_q;
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      en_smp_q  <= '0;
      dn_smp_q  <= '0;
      cnt_smp_q <= '0;
      min_smp_q <= '0;
      en_act_q  <= '0;
      dn_act_q  <= '0;
      cnt_act_q <= '0;
      min_act_q <= '0;
    end else begin
      en_smp_q  <= en_smp_d;
      dn_smp_q  <= dn_smp_d;
      cnt_smp_q <= cnt_smp_d;
      min_smp_q <= min_smp_d;
      en_act_q  <= en_act_d;
      dn_act_q  <= dn_act_d;
      cnt_act_q <= cnt_act_d;
      min_act_q <= min_act_d;
    end
  end

  for (genvar k = 0; k < 2; k++) begin : gen_point
    logic [CntWidth-1:0] cnt;
    assign cnt   = cnt_act_q[k*CntWidth +: CntWidth];
    assign pt_o[k] = en_act_q[k] && ((run_i && count_i == cnt && up_i == !dn_act_q[k])
                                     || (peak_i && cnt >= period_i) || (valley_i && cnt == '0));
  end

  // ---- shunt-window report -----------------------------------------------------------------------
  // the low side's window around the valley: 2C clocks of pole low, less the falling dead time (none
  // when the pole never goes high, C == P); the high side's around the peak: 2(P - C) less the rising one
  function automatic logic [WW-1:0] lo_window(input logic [CntWidth-1:0] c, input logic [CntWidth-1:0] p,
                                              input logic [DtWidth-1:0] dtf);
    logic [WW-1:0] lo2;
    lo2 = {c, 1'b0};
    lo_window = (c == p) ? lo2 : (lo2 >= WW'(dtf)) ? lo2 - WW'(dtf) : '0;
  endfunction

  function automatic logic [WW-1:0] hi_window(input logic [CntWidth-1:0] c, input logic [CntWidth-1:0] p,
                                              input logic [DtWidth-1:0] dt);
    logic [WW-1:0] hi2;
    hi2 = {p - c, 1'b0};
    hi_window = (c == '0) ? hi2 : (hi2 >= WW'(dt)) ? hi2 - WW'(dt) : '0;
  endfunction

  logic [3*WW-1:0] lo_d, lo_q, hi_d, hi_q;
  logic [2:0]      ok_d, ok_q;
  logic [1:0]      recon_d, recon_q;
  logic [WW-1:0]   lo_a, lo_b, lo_c;

  for (genvar ph = 0; ph < 3; ph++) begin : gen_window
    assign lo_d[ph*WW +: WW] = active_i ? lo_window(cmp_i[ph*CntWidth +: CntWidth], period_i, dtf_i) : '0;
    assign hi_d[ph*WW +: WW] = active_i ? hi_window(cmp_i[ph*CntWidth +: CntWidth], period_i, dt_i) : '0;
    assign ok_d[ph]          = lo_q[ph*WW +: WW] != '0 && lo_q[ph*WW +: WW] >= min_act_q;
  end

  assign lo_a    = lo_q[0 +: WW];
  assign lo_b    = lo_q[WW +: WW];
  assign lo_c    = lo_q[2*WW +: WW];
  assign recon_d = (lo_a <= lo_b && lo_a <= lo_c) ? 2'd0 : (lo_b <= lo_c) ? 2'd1 : 2'd2;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      lo_q    <= '0;
      hi_q    <= '0;
      ok_q    <= '0;
      recon_q <= '0;
    end else begin
      lo_q    <= lo_d;
      hi_q    <= hi_d;
      ok_q    <= ok_d;
      recon_q <= recon_d;
    end
  end

  assign win_lo_o    = lo_q;
  assign win_hi_o    = hi_q;
  assign win_ok_o    = ok_q;
  assign win_recon_o = recon_q;

endmodule

`default_nettype wire
