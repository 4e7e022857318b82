// SPDX-License-Identifier: Apache-2.0
// tb_svpwm_calc: unit harness around svpwm_calc (the core's one calculator). Generates the clock (10 ns)
// and checks the handshake on every clock against a reference of it, so the cocotb test only wakes on
// events (start, done). The reference: start_i in cycle c (sampled by the edge ending c) is accepted when
// idle and abort_i is low; busy_o is high in cycles c+1 .. c+L-1, done_o is high in cycle c+L (L = latency_i)
// only; abort_i returns to idle at once (no done_o); the done cycle is idle. Sticky flags until rst_ni:
//   chk_o[0]  busy_o differs from the reference (start not taken / ignored, busy too short / long, abort)
//   chk_o[1]  done_o differs from the reference (missing, early, late, extra, longer than one clock)
//   chk_o[2]  the testbench broke the input rule: an input other than sector_i / angle_i changed while
//             busy (checked at every edge the calculator computes on; a self-check of the stimulus)
// err_cyc_o: the clock count at the first flag (0: none). Results (sector_o, cmp_o, sat_o, err_o) are
// defined only in the done cycle; the test compares them there. latency_i: the expected start -> done_o
// clocks, driven by the test (its LATENCY, from the model), held from reset on.
`timescale 1ns / 1ps
`default_nettype none

module tb_svpwm_calc #(
  parameter bit Compact  = 1'b0,
  parameter bit Dsp      = svpwm_pkg::core_dsp(Compact),   // 0: the serial multiplier (no core builds it)
  parameter int CntWidth = 16,
  parameter int DtWidth  = 10
) (
  input  logic [15:0]           latency_i,
  input  logic                  rst_ni,
  input  logic                  start_i,
  input  logic                  abort_i,
  input  logic [2:0]            mode_i,
  input  logic [2:0]            sector_i,
  input  logic [15:0]           angle_i,
  input  logic [15:0]           theta_i,
  input  logic [15:0]           m_i,
  input  logic [15:0]           fabs_i,
  input  logic signed [15:0]    v1_i,
  input  logic signed [15:0]    v2_i,
  input  logic [15:0]           vf_boost_i,
  input  logic [15:0]           vf_slope_i,
  input  logic [15:0]           vf_mmax_i,
  input  logic [1:0]            dpwm_i,
  input  logic [CntWidth-1:0]   period_i,
  input  logic [DtWidth:0]      thr_i,
  output logic                  clk,
  output logic                  busy_o,
  output logic                  done_o,
  output logic [2:0]            sector_o,
  output logic [3*CntWidth-1:0] cmp_o,
  output logic                  sat_o,
  output logic                  err_o,
  output logic [2:0]            chk_o,
  output logic [31:0]           err_cyc_o
);

  localparam int HeldWidth = 3 + 16 * 8 + 2 + CntWidth + DtWidth + 1;

  initial clk = 1'b0;
  always #5 clk = ~clk;

  svpwm_calc #(.Compact(Compact), .Dsp(Dsp), .CntWidth(CntWidth), .DtWidth(DtWidth)) u_dut (
    .clk_i      (clk),
    .rst_ni     (rst_ni),
    .start_i    (start_i),
    .abort_i    (abort_i),
    .mode_i     (mode_i),
    .sector_i   (sector_i),
    .angle_i    (angle_i),
    .theta_i    (theta_i),
    .m_i        (m_i),
    .fabs_i     (fabs_i),
    .v1_i       (v1_i),
    .v2_i       (v2_i),
    .vf_boost_i (vf_boost_i),
    .vf_slope_i (vf_slope_i),
    .vf_mmax_i  (vf_mmax_i),
    .dpwm_i     (dpwm_i),
    .period_i   (period_i),
    .thr_i      (thr_i),
    .busy_o     (busy_o),
    .done_o     (done_o),
    .sector_o   (sector_o),
    .cmp_o      (cmp_o),
    .sat_o      (sat_o),
    .err_o      (err_o)
  );

  // ---- handshake reference and checker (header) ----
  logic [HeldWidth-1:0] held, held_q;
  int unsigned          ref_st, cyc;       // ref_st: 0 idle, k = k-th clock after the accepted start
  logic                 ref_done;

  assign held = {mode_i, theta_i, m_i, fabs_i, v1_i, v2_i, vf_boost_i, vf_slope_i, vf_mmax_i, dpwm_i,
                 period_i, thr_i};

  always @(posedge clk or negedge rst_ni) begin
    if (!rst_ni) begin
      chk_o     <= '0;
      err_cyc_o <= '0;
      ref_st    <= 0;
      ref_done  <= 1'b0;
      held_q    <= '0;
      cyc       <= 0;
    end else begin
      cyc <= cyc + 1;
      // the outputs of the cycle this edge ends against the reference of that cycle
      if (busy_o != (ref_st != 0)) chk_o[0] <= 1'b1;
      if (done_o != ref_done)      chk_o[1] <= 1'b1;
      if (ref_st != 0 && held != held_q) chk_o[2] <= 1'b1;
      if (err_cyc_o == 0 && (busy_o != (ref_st != 0) || done_o != ref_done || (ref_st != 0 && held != held_q)))
        err_cyc_o <= cyc + 1;
      // the reference's next cycle
      ref_done <= 1'b0;
      if (abort_i) begin
        ref_st <= 0;
      end else if (ref_st == 32'(latency_i) - 1) begin
        ref_st   <= 0;
        ref_done <= 1'b1;
      end else if (ref_st != 0) begin
        ref_st <= ref_st + 1;
      end else if (start_i) begin
        ref_st <= 1;
        held_q <= held;
      end
    end
  end

endmodule

`default_nettype wire
