// SPDX-License-Identifier: Apache-2.0
// tb_deadtime: unit harness around deadtime (one inverter leg). Generates the clock (10 ns) in
// SystemVerilog.
`timescale 1ns / 1ps
`default_nettype none

module tb_deadtime #(
  parameter int DtWidth = 10
) (
  input  logic               rst_ni,
  input  logic               en_i,
  input  logic               brake_i,
  input  logic               pole_i,
  input  logic [DtWidth-1:0] dt_i,
  input  logic [DtWidth-1:0] dtf_i,
  input  logic [DtWidth-1:0] mp_i,
  output logic               clk,
  output logic               hold_o,
  output logic               hi_o,
  output logic               lo_o
);

  initial clk = 1'b0;
  always #5 clk = ~clk;

  deadtime #(.DtWidth(DtWidth)) u_dut (
    .clk_i  (clk),
    .rst_ni (rst_ni),
    .en_i    (en_i),
    .brake_i (brake_i),
    .pole_i  (pole_i),
    .dt_i    (dt_i),
    .dtf_i   (dtf_i),
    .mp_i    (mp_i),
    .hold_i  (1'b0),                // HoldIn = 0: the leg's own reset hold
    .hold_o  (hold_o),
    .hi_o   (hi_o),
    .lo_o   (lo_o)
  );

endmodule

`default_nettype wire
