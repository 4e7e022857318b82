// SPDX-License-Identifier: Apache-2.0
// tb_svpwm_carrier: unit harness around svpwm_carrier. Generates the clock (10 ns) in SystemVerilog.
`timescale 1ns / 1ps
`default_nettype none

module tb_svpwm_carrier #(
  parameter int CntWidth = 16
) (
  input  logic                rst_ni,
  input  logic                run_i,
  input  logic [CntWidth-1:0] period_i,
  output logic                clk,
  output logic [CntWidth-1:0] count_o,
  output logic                up_o,
  output logic [CntWidth-1:0] period_o,
  output logic                valley_o,
  output logic                peak_o,
  output logic                pre_peak_o,
  output logic                load_o
);

  initial clk = 1'b0;
  always #5 clk = ~clk;

  svpwm_carrier #(.CntWidth(CntWidth)) u_dut (
    .clk_i    (clk),
    .rst_ni   (rst_ni),
    .run_i    (run_i),
    .period_i (period_i),
    .count_o  (count_o),
    .up_o     (up_o),
    .period_o (period_o),
    .valley_o (valley_o),
    .peak_o   (peak_o),
    .pre_peak_o (pre_peak_o),
    .load_o   (load_o),
    .point_o  ()              // (formal/carrier.sby proves it equal to load_o || pre_peak_o running)
  );

endmodule

`default_nettype wire
