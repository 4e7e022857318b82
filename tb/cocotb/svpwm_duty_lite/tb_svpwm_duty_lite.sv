// SPDX-License-Identifier: Apache-2.0
// tb_svpwm_duty_lite: unit harness around svpwm_duty_lite (with its sine_rom). Generates the clock (10 ns)
// and checks the output handshake on every clock in SystemVerilog, so the cocotb test only wakes on events:
//   chk_o[0]  an output (sector_o, cmp_o, sat_o) changed on a clock without done_o
//   chk_o[1]  done_o high for more than one clock
//   chk_o[2]  done_o not preceded by exactly Latency - 1 busy_o clocks, done_o with busy_o,
//             or busy_o longer than Latency - 1 clocks
// The flags are sticky until rst_ni. Latency: the expected start -> done_o clocks (the test passes the
// model's fixed.LITE_DUTY_LATENCY, so a differing RTL Latency fails chk_o[2]).
`timescale 1ns / 1ps
`default_nettype none

module tb_svpwm_duty_lite #(
  parameter int CntWidth = 16,
  parameter int DtWidth  = 10,
  parameter int Latency  = 225
) (
  input  logic                  rst_ni,
  input  logic                  start_i,
  input  logic                  abort_i,
  input  logic [2:0]            sector_i,
  input  logic [15:0]           angle_i,
  input  logic [15:0]           m_i,
  input  logic [CntWidth-1:0]   period_i,
  input  logic [DtWidth:0]      thr_i,
  output logic                  clk,
  output logic                  busy_o,
  output logic                  done_o,
  output logic [2:0]            sector_o,
  output logic [3*CntWidth-1:0] cmp_o,
  output logic                  sat_o,
  output logic [2:0]            chk_o
);

  localparam int BusyClocks = Latency - 1;

  initial clk = 1'b0;
  always #5 clk = ~clk;

  svpwm_duty_lite #(.CntWidth(CntWidth), .DtWidth(DtWidth)) u_dut (
    .clk_i    (clk),
    .rst_ni   (rst_ni),
    .start_i  (start_i),
    .abort_i  (abort_i),
    .sector_i (sector_i),
    .angle_i  (angle_i),
    .m_i      (m_i),
    .period_i (period_i),
    .thr_i    (thr_i),
    .busy_o   (busy_o),
    .done_o   (done_o),
    .sector_o (sector_o),
    .cmp_o    (cmp_o),
    .sat_o    (sat_o)
  );

  // ---- handshake checker (chk_o, header): tb/cocotb/calc_handshake_chk.sv ----
  calc_handshake_chk #(.ResWidth(3 * CntWidth + 4), .BusyClocks(BusyClocks)) u_chk (
    .clk_i  (clk),
    .rst_ni (rst_ni),
    .busy_i (busy_o),
    .done_i (done_o),
    .res_i  ({sector_o, cmp_o, sat_o}),
    .chk_o  (chk_o)
  );

endmodule

`default_nettype wire
