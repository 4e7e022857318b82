// SPDX-License-Identifier: Apache-2.0
// tb_svpwm_duty: unit harness around svpwm_duty (with its sine_rom). Generates the clock (10 ns) in
// SystemVerilog.
`timescale 1ns / 1ps
`default_nettype none

module tb_svpwm_duty #(
  parameter int CntWidth = 16
) (
  input  logic                  rst_ni,
  input  logic                  start_i,
  input  logic [2:0]            sector_i,
  input  logic [15:0]           angle_i,
  input  logic [15:0]           m_i,
  input  logic [CntWidth-1:0]   period_i,
  output logic                  clk,
  output logic                  busy_o,
  output logic                  done_o,
  output logic [2:0]            sector_o,
  output logic [3*CntWidth-1:0] cmp_o
);

  initial clk = 1'b0;
  always #5 clk = ~clk;

  svpwm_duty #(.CntWidth(CntWidth)) u_dut (
    .clk_i    (clk),
    .rst_ni   (rst_ni),
    .start_i  (start_i),
    .sector_i (sector_i),
    .angle_i  (angle_i),
    .m_i      (m_i),
    .period_i (period_i),
    .busy_o   (busy_o),
    .done_o   (done_o),
    .sector_o (sector_o),
    .cmp_o    (cmp_o)
  );

endmodule

`default_nettype wire
