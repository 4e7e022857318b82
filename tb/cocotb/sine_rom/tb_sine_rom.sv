// SPDX-License-Identifier: Apache-2.0
// tb_sine_rom: unit harness around sine_rom. Generates the clock (10 ns) in SystemVerilog.
`timescale 1ns / 1ps
`default_nettype none

module tb_sine_rom (
  input  logic [8:0]  addr_i,
  output logic        clk,
  output logic [15:0] data_o
);

  initial clk = 1'b0;
  always #5 clk = ~clk;

  sine_rom u_dut (
    .clk_i  (clk),
    .addr_i (addr_i),
    .data_o (data_o)
  );

endmodule

`default_nettype wire
