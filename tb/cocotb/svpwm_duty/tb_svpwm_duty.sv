// SPDX-License-Identifier: Apache-2.0
// tb_svpwm_duty: unit harness around svpwm_duty (with its sine_rom). Generates the clock (10 ns) in
// SystemVerilog and checks the output handshake on every clock in SystemVerilog, so the cocotb test
// only has to wake up on events (start, done):
//   chk_o[0]  an output (sector_o, cmp_o, sat_o, err_o) changed on a clock without done_o
//   chk_o[1]  done_o high for more than one clock
//   chk_o[2]  done_o not preceded by exactly DutyLatency - 1 = 33 busy_o clocks, done_o with busy_o,
//             or busy_o longer than 33 clocks
// The flags are sticky until rst_ni.
`timescale 1ns / 1ps
`default_nettype none

module tb_svpwm_duty #(
  parameter int CntWidth = 16
) (
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
  output logic                  clk,
  output logic                  busy_o,
  output logic                  done_o,
  output logic [2:0]            sector_o,
  output logic [3*CntWidth-1:0] cmp_o,
  output logic                  sat_o,
  output logic                  err_o,
  output logic [2:0]            chk_o
);

  localparam int BusyClocks = 33;   // DutyLatency - 1

  initial clk = 1'b0;
  always #5 clk = ~clk;

  svpwm_duty #(.CntWidth(CntWidth)) u_dut (
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
    .busy_o     (busy_o),
    .done_o     (done_o),
    .sector_o   (sector_o),
    .cmp_o      (cmp_o),
    .sat_o      (sat_o),
    .err_o      (err_o)
  );

  // ---- handshake checker (chk_o, header): tb/cocotb/calc_handshake_chk.sv ----
  calc_handshake_chk #(.ResWidth(3 * CntWidth + 5), .BusyClocks(BusyClocks)) u_chk (
    .clk_i  (clk),
    .rst_ni (rst_ni),
    .busy_i (busy_o),
    .done_i (done_o),
    .res_i  ({sector_o, cmp_o, sat_o, err_o}),
    .chk_o  (chk_o)
  );

endmodule

`default_nettype wire
