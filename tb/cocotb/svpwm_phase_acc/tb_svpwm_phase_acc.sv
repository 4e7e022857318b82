// SPDX-License-Identifier: Apache-2.0
// tb_svpwm_phase_acc: unit harness around svpwm_phase_acc. Generates the clock (10 ns) in SystemVerilog
// and counts the clocks since reset (cyc_o) so event-driven checks can time sector changes exactly.
`timescale 1ns / 1ps
`default_nettype none

module tb_svpwm_phase_acc #(
  parameter int PhaseWidth = 34,
  parameter int FreqWidth  = 24,
  parameter bit Split = 1'b1
) (
  input  logic                        rst_ni,
  input  logic                        run_i,
  input  logic signed [FreqWidth-1:0] step_i,
  output logic                        clk,
  output logic [2:0]                  sector_o,
  output logic [PhaseWidth-1:0]       angle_o,
  output logic [31:0]                 cyc_o      // rising edges since the reset was released
);

  initial clk = 1'b0;
  always #5 clk = ~clk;

  always_ff @(posedge clk or negedge rst_ni) begin
    if (!rst_ni) cyc_o <= '0;
    else         cyc_o <= cyc_o + 32'd1;
  end

  svpwm_phase_acc #(
    .PhaseWidth (PhaseWidth),
    .FreqWidth  (FreqWidth),
    .Split(Split)
  ) u_dut (
    .clk_i    (clk),
    .rst_ni   (rst_ni),
    .run_i    (run_i),
    .step_i   (step_i),
    .sector_o (sector_o),
    .angle_o  (angle_o)
  );

endmodule

`default_nettype wire
