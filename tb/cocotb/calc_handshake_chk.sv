// SPDX-License-Identifier: Apache-2.0
// calc_handshake_chk: testbench checker of the duty calculators' output handshake (svpwm_duty,
// svpwm_duty_lite; used by their harnesses), evaluated at every rising edge on the outputs of the
// previous clock, so the cocotb tests only wake on events:
//   chk_o[0]  a result output changed on a clock without done_o
//   chk_o[1]  done_o high for more than one clock
//   chk_o[2]  done_o not preceded by exactly BusyClocks busy_o clocks, done_o with busy_o,
//             or busy_o longer than BusyClocks clocks
// The flags are sticky until rst_ni. Parameters: ResWidth - width of the concatenated results;
// BusyClocks - the calculator's latency - 1. Simulation only.
`timescale 1ns / 1ps
`default_nettype none

module calc_handshake_chk #(
  parameter int ResWidth   = 1,
  parameter int BusyClocks = 1
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                busy_i,
  input  logic                done_i,
  input  logic [ResWidth-1:0] res_i,     // every result output, concatenated
  output logic [2:0]          chk_o
);
  logic [ResWidth-1:0] res_prev;
  logic                done_prev;
  int                  busy_run;

  always @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      chk_o     <= '0;
      res_prev  <= '0;
      done_prev <= 1'b0;
      busy_run  <= 0;
    end else begin
      if (res_i != res_prev && !done_i) chk_o[0] <= 1'b1;
      if (done_i && done_prev) chk_o[1] <= 1'b1;
      if (done_i && (busy_i || busy_run != BusyClocks)) chk_o[2] <= 1'b1;
      if (busy_run > BusyClocks) chk_o[2] <= 1'b1;
      res_prev  <= res_i;
      done_prev <= done_i;
      busy_run  <= busy_i ? busy_run + 1 : 0;
    end
  end
endmodule

`default_nettype wire
